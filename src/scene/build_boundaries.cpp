// Boundary definitions resolved to the gridpoints and edges of their deformable blocks (and the
// free-field columns beside them), and the gridpoints and zones that histories sample.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/shown.hpp"
#include "scene/build_parts.hpp"

namespace vdec {

std::array<double, 3> StressTable::at(double a, const Origin& origin) const {
  if (a < angle.front() - 1e-9 || a > angle.back() + 1e-9)
    origin.fail("stress_table", file + " covers angles " + shown(angle.front()) + " to " + shown(angle.back()) +
                                    " degrees, not the edge at " + shown(a) + " degrees");
  const auto it = std::upper_bound(angle.begin(), angle.end(), a);
  const std::size_t k = std::clamp<std::size_t>(static_cast<std::size_t>(it - angle.begin()), 1, angle.size() - 1);
  const double w = (a - angle[k - 1]) / (angle[k] - angle[k - 1]);
  std::array<double, 3> out{};
  for (int i = 0; i < 3; ++i) out[i] = (1.0 - w) * stress[k - 1][i] + w * stress[k][i];
  return out;
}

namespace {

double polarAngleDegrees(Vec2 d) { return std::atan2(d.y, d.x) * 180.0 / std::numbers::pi; }

// The impedances rho C_p and rho C_s of a material.
std::pair<double, double> impedances(const BlockMaterial& mat) {
  return {std::sqrt(mat.density * (mat.bulk + 4.0 * mat.shear / 3.0)), std::sqrt(mat.density * mat.shear)};
}

// The material whose impedances a viscous or free-field boundary's dashpots take: the medium
// beyond it that the boundary names, else BLOCK_MATERIAL. A material without elastic constants has
// no wave speeds, and would give dashpots that absorb nothing.
int dashpotMaterial(const BoundaryDefinition& d, const Model& m, int blockMaterial) {
  const bool named = !d.material.empty();
  const int material = named ? blockMaterialNamed(m, d.origin, "material", d.material) : blockMaterial;
  const BlockMaterial& mat = m.blockMaterials[material];
  if (!mat.elastic())
    d.origin.fail(named ? "material" : "block",
                  "block material '" + mat.name + "' has no elastic constants, and the dashpots need its wave speeds: " +
                      (named ? "give it young and poisson, or name an elastic material"
                             : "give it young and poisson, or name the medium beyond the boundary with material = \"...\""));
  return material;
}

int historyOf(const BoundaryDefinition& d, Model& m) {
  if (!d.history) return -1;
  m.timeFunctions.push_back(*d.history);
  return static_cast<int>(m.timeFunctions.size()) - 1;
}

// The free-field column beside the selected side edges (all vertical, all on one side): its
// nodes at the heights of their end gridpoints, each element of the material of the edge beside it.
FreeFieldColumn freeFieldColumn(const BoundaryDefinition& d, Model& m, const std::vector<Model::BoundaryEdge>& edges,
                                double slack) {
  const Gridpoints& g = m.gridpoints;
  FreeFieldColumn c;
  double side = 0.0;  // -1: a left side, its edges going down (counter-clockwise); +1: a right side
  for (const Model::BoundaryEdge& be : edges) {
    const Vec2 a = g.initialPosition[be.from], b = g.initialPosition[be.to];
    if (std::abs(b.x - a.x) > slack)
      d.origin.fail("x", "selects the edge from (" + shown(a.x) + ", " + shown(a.y) + ") to (" + shown(b.x) + ", " +
                             shown(b.y) + ") of block '" + m.blocks.name[be.block] +
                             "', which is not vertical: a free-field column runs beside a vertical side; give x = [x0, x0] "
                             "at that side");
    if (std::abs(a.x - g.initialPosition[edges.front().from].x) > slack)
      d.origin.fail("x", "selects vertical edges at x = " + shown(g.initialPosition[edges.front().from].x) + " and at x = " +
                             shown(a.x) + ": a free-field column runs beside one straight side; give x = [x0, x0]");
    const double edgeSide = b.y < a.y ? -1.0 : 1.0;
    if (side != 0.0 && side != edgeSide)
      d.origin.fail("x", "selects edges of a left side and of a right side: give one free-field table per side");
    side = edgeSide;
    const auto [zn, zs] = impedances(m.blockMaterials[m.blocks.material[be.block]]);
    c.edges.push_back({be.from, be.to, zn, zs});
    c.nodeY.insert(c.nodeY.end(), {a.y, b.y});
  }
  std::sort(c.nodeY.begin(), c.nodeY.end());
  c.nodeY.erase(std::unique(c.nodeY.begin(), c.nodeY.end(), [slack](double u, double v) { return v - u <= slack; }),
                c.nodeY.end());
  const std::size_t elements = c.nodeY.size() - 1;
  c.elementMaterial.assign(elements, -1);
  for (std::size_t e = 0; e < elements; ++e) {
    const double mid = 0.5 * (c.nodeY[e] + c.nodeY[e + 1]);
    for (const Model::BoundaryEdge& be : edges) {
      const double ya = g.initialPosition[be.from].y, yb = g.initialPosition[be.to].y;
      if (std::min(ya, yb) <= mid && mid <= std::max(ya, yb)) c.elementMaterial[e] = m.blocks.material[be.block];
    }
    if (c.elementMaterial[e] < 0)
      d.origin.failTable("leaves the side uncovered between y = " + shown(c.nodeY[e]) + " and " + shown(c.nodeY[e + 1]) +
                         " m: a free-field column needs an unbroken vertical side; close the gap in the model's side, or give one "
                         "free-field table per unbroken stretch (narrow y)");
  }
  for (FreeFieldEdge& edge : c.edges) {
    const std::array<double, 2> y{g.initialPosition[edge.from].y, g.initialPosition[edge.to].y};
    for (int k = 0; k < 2; ++k) {
      const auto above = std::upper_bound(c.nodeY.begin(), c.nodeY.end(), y[k] + slack);
      const int j = std::clamp(static_cast<int>(above - c.nodeY.begin()) - 1, 0, static_cast<int>(elements) - 1);
      edge.node[k] = j;
      edge.weight[k] = std::clamp((y[k] - c.nodeY[j]) / (c.nodeY[j + 1] - c.nodeY[j]), 0.0, 1.0);
    }
    // The elements between the lower and the upper end.
    const int low = y[0] < y[1] ? 0 : 1;
    edge.firstElement = edge.weight[low] >= 1.0 ? edge.node[low] + 1 : edge.node[low];
    edge.lastElement = edge.weight[1 - low] <= 0.0 ? edge.node[1 - low] - 1 : edge.node[1 - low];
  }
  c.nodeMass.assign(c.nodeY.size(), 0.0);
  for (std::size_t e = 0; e < elements; ++e) {
    const double half = 0.5 * m.blockMaterials[c.elementMaterial[e]].density * (c.nodeY[e + 1] - c.nodeY[e]);
    c.nodeMass[e] += half;
    c.nodeMass[e + 1] += half;
  }
  c.nodeVelocity.assign(c.nodeY.size(), Vec2{});
  c.sxx.assign(elements, 0.0);
  c.syy.assign(elements, 0.0);
  c.sxy.assign(elements, 0.0);
  std::tie(c.baseNormalImpedance, c.baseShearImpedance) =
      impedances(m.blockMaterials[dashpotMaterial(d, m, c.elementMaterial.front())]);
  c.inputVelocity = d.inputVelocity;
  c.history = historyOf(d, m);
  return c;
}

// A viscous boundary on the edges of a rigid block whose two end vertices the ranges select (at
// the block's input position).
BoundaryCondition rigidViscousBoundary(const BoundaryDefinition& d, Model& m, int block) {
  BoundaryCondition condition;
  condition.name = d.name;
  const auto [zn, zs] = impedances(m.blockMaterials[dashpotMaterial(d, m, m.blocks.material[block])]);
  const int first = m.blocks.firstVertex[block], count = m.blocks.vertexCount[block];
  const double slack = 1e-9 * std::max(1.0, 2.0 * m.blocks.boundingRadius[block]);
  auto selected = [&](int v) {
    const Vec2 p = m.vertices.geometry[v].position, r = p - d.centre;
    return d.x.holds(p.x, slack) && d.y.holds(p.y, slack) && d.r.holds(norm(r), slack) &&
           d.angle.holds(polarAngleDegrees(r), 1e-7);
  };
  const int history = historyOf(d, m);
  for (int k = 0; k < count; ++k) {
    const int from = first + k, to = first + (k + 1) % count;
    if (selected(from) && selected(to))
      condition.rigidDashpots.push_back({block, from, to, zn, zs, -1, d.inputVelocity, history, 0.0});
  }
  if (condition.rigidDashpots.empty())
    d.origin.failTable("selects no edge of rigid block '" + m.blocks.name[block] +
                       "': dashpots act on the edges whose two end vertices are both selected; check x, y, r, angle");
  return condition;
}

}  // namespace

GridpointSelection selectGridpoints(const Model& m, const std::vector<char>& inBlocks, const CoordinateRange& x,
                                    const CoordinateRange& y, const CoordinateRange& r, const CoordinateRange& angle,
                                    Vec2 centre) {
  GridpointSelection s;
  // Slack: round-off of the generated coordinates, relative to the blocks' size.
  double size = 1.0;
  for (int b = 0; b < m.blocks.size(); ++b)
    if (inBlocks[b]) size = std::max(size, 2.0 * m.blocks.boundingRadius[b]);
  s.slack = 1e-9 * size;
  s.selected.assign(m.gridpoints.size(), 0);
  for (int i = 0; i < m.gridpoints.size(); ++i) {
    if (!inBlocks[m.gridpoints.block[i]]) continue;
    const Vec2 p = m.gridpoints.initialPosition[i];
    const Vec2 d = p - centre;
    if (x.holds(p.x, s.slack) && y.holds(p.y, s.slack) && r.holds(norm(d), s.slack) &&
        angle.holds(polarAngleDegrees(d), 1e-7)) {
      s.selected[i] = 1;
      ++s.count;
    }
  }
  s.selectedVertex.assign(m.vertices.size(), 0);
  for (int v = 0; v < m.vertices.size(); ++v) {
    const int b = m.vertices.block[v];
    if (!inBlocks[b] || m.blocks.deformable[b]) continue;
    const Vec2 p = m.vertices.geometry[v].position;
    const Vec2 d = p - centre;
    s.selectedVertex[v] = x.holds(p.x, s.slack) && y.holds(p.y, s.slack) && r.holds(norm(d), s.slack) &&
                          angle.holds(polarAngleDegrees(d), 1e-7);
  }
  return s;
}

BoundaryCondition resolveBoundary(const BoundaryDefinition& d, Model& m) {
  BoundaryCondition condition;
  condition.name = d.name;
  // The blocks it selects from: the one named, or every deformable block for a free field.
  std::vector<char> inBlocks(m.blocks.size(), 0);
  if (d.block.empty()) {
    for (int b = 0; b < m.blocks.size(); ++b) inBlocks[b] = m.blocks.deformable[b];
  } else {
    const int block = blockNamed(m, d.origin, "block", d.block);
    if (!m.blocks.deformable[block]) {
      if (d.viscous && m.strainModes.holds(block))
        d.origin.fail("block", "block '" + m.blocks.name[block] + "' is simply deformable: a viscous boundary's dashpots "
                               "act on a rigid block's motion alone and would leave its strain without them");
      if (d.viscous) return rigidViscousBoundary(d, m, block);
      d.origin.fail("block", "block '" + m.blocks.name[block] + "' is rigid: [[boundary]] applies to deformable blocks, and "
                             "to rigid ones only as viscous = true; give a rigid block `fix`, `velocity` or `force` in "
                             "its [[block]] table");
    }
    inBlocks[block] = 1;
  }
  const std::string which = d.block.empty() ? "any deformable block" : "block '" + d.block + "'";
  const GridpointSelection picked = selectGridpoints(m, inBlocks, d.x, d.y, d.r, d.angle, d.centre);
  const std::vector<char>& selected = picked.selected;
  const double slack = picked.slack;
  if (picked.count == 0) d.origin.failTable("selects no gridpoint of " + which + ": check x, y, r, angle");
  // Edges of the blocks' outlines whose two ends are both selected.
  auto selectedEdges = [&] {
    std::vector<Model::BoundaryEdge> edges;
    for (const Model::BoundaryEdge& be : m.boundaryEdges)
      if (inBlocks[be.block] && selected[be.from] && selected[be.to]) edges.push_back(be);
    return edges;
  };
  auto noEdge = [&](const std::string& what) {
    d.origin.failTable("selects no boundary edge of " + which + ": " + what +
                       " act on edges of the block's outline whose two ends are both selected");
  };

  if (d.freeField) {
    const std::vector<Model::BoundaryEdge> edges = selectedEdges();
    if (edges.empty()) noEdge("free-field columns");
    condition.freeField.push_back(freeFieldColumn(d, m, edges, slack));
    return condition;
  }
  if (d.viscous) {
    const int history = historyOf(d, m);
    for (const Model::BoundaryEdge& be : selectedEdges()) {
      const auto [zn, zs] = impedances(m.blockMaterials[dashpotMaterial(d, m, m.blocks.material[be.block])]);
      condition.dashpots.push_back({be.from, be.to, zn, zs, -1, d.inputVelocity, history, 0.0});
    }
    if (condition.dashpots.empty()) noEdge("dashpots");
    return condition;
  }
  if (d.history) {
    m.timeFunctions.push_back(*d.history);
    condition.history = static_cast<int>(m.timeFunctions.size()) - 1;
  }
  if (!d.loaded) {
    condition.fix = d.fix;
    condition.velocityBits = d.velocityBits;
    condition.velocity = d.velocity;
    for (int i = 0; i < m.gridpoints.size(); ++i)
      if (selected[i]) condition.gridpoints.push_back(i);
    return condition;
  }
  for (const Model::BoundaryEdge& be : selectedEdges()) {
    const Vec2 mid = 0.5 * (m.gridpoints.initialPosition[be.from] + m.gridpoints.initialPosition[be.to]);
    LoadedEdge e;
    e.from = be.from;
    e.to = be.to;
    e.history = condition.history;
    if (d.stressTable) {
      const std::array<double, 3> v = d.stressTable->at(polarAngleDegrees(mid - d.centre), d.origin);
      e.sxx = v[0];
      e.syy = v[1];
      e.sxy = v[2];
    } else {
      const auto &s = d.stress, &gx = d.gradientX, &gy = d.gradientY;
      e.sxx = s[0] + gx[0] * mid.x + gy[0] * mid.y;
      e.syy = s[1] + gx[1] * mid.x + gy[1] * mid.y;
      e.sxy = s[2] + gx[2] * mid.x + gy[2] * mid.y;
    }
    condition.edges.push_back(e);
  }
  if (condition.edges.empty()) noEdge("stress and pressure");
  return condition;
}

int nearestGridpoint(const Model& m, int block, Vec2 point) {
  int best = -1;
  double bestDistance = INFINITY;
  for (int i = 0; i < m.gridpoints.size(); ++i) {
    if (m.gridpoints.block[i] != block) continue;
    const double d = norm(m.gridpoints.initialPosition[i] - point);
    if (d < bestDistance) {
      bestDistance = d;
      best = i;
    }
  }
  return best;
}

int zoneAt(const Model& m, int block, Vec2 point) {
  const Gridpoints& g = m.gridpoints;
  for (int z = 0; z < m.zones.size(); ++z) {
    if (m.zones.block[z] != block) continue;
    const auto& n = m.zones.gridpoint[z];
    const Vec2 p0 = g.initialPosition[n[0]], p1 = g.initialPosition[n[1]], p2 = g.initialPosition[n[2]];
    const double scale = 1e-12 * cross(p1 - p0, p2 - p0);
    // Inside or on the boundary (the first zone in id order wins a shared edge).
    if (cross(p1 - p0, point - p0) >= -scale && cross(p2 - p1, point - p1) >= -scale &&
        cross(p0 - p2, point - p2) >= -scale)
      return z;
  }
  return -1;
}

}  // namespace vdec
