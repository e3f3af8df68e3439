// Boundary definitions resolved to the gridpoints and edges of their deformable block, and the
// gridpoints and zones that histories sample.
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

}  // namespace

BoundaryCondition resolveBoundary(const BoundaryDefinition& d, Model& m) {
  BoundaryCondition condition;
  condition.name = d.name;
  const int block = blockNamed(m, d.origin, "block", d.block);
  if (!m.blocks.deformable[block])
    d.origin.fail("block", "block '" + m.blocks.name[block] + "' is rigid: [[boundary]] applies to deformable blocks; "
                           "give a rigid block `fix`, `velocity` or `force` in its [[block]] table");
  // Selection slack: round-off of the generated coordinates, relative to the block's size.
  const double slack = 1e-9 * std::max(1.0, 2.0 * m.blocks.boundingRadius[block]);
  std::vector<char> selected(m.gridpoints.size(), 0);
  int count = 0;
  for (int i = 0; i < m.gridpoints.size(); ++i) {
    if (m.gridpoints.block[i] != block) continue;
    const Vec2 p = m.gridpoints.initialPosition[i];
    const Vec2 r = p - d.centre;
    if (d.x.holds(p.x, slack) && d.y.holds(p.y, slack) && d.r.holds(norm(r), slack) &&
        d.angle.holds(polarAngleDegrees(r), 1e-7)) {
      selected[i] = 1;
      ++count;
    }
  }
  if (count == 0) d.origin.failTable("selects no gridpoint of block '" + m.blocks.name[block] + "': check x, y, r, angle");
  // Edges of the block's outline whose two ends are both selected.
  auto selectedEdges = [&] {
    std::vector<Model::BoundaryEdge> edges;
    for (const Model::BoundaryEdge& be : m.boundaryEdges)
      if (be.block == block && selected[be.from] && selected[be.to]) edges.push_back(be);
    return edges;
  };

  if (d.viscous) {
    const BlockMaterial& mat = m.blockMaterials[m.blocks.material[block]];
    int history = -1;
    if (d.history) {
      m.timeFunctions.push_back(*d.history);
      history = static_cast<int>(m.timeFunctions.size()) - 1;
    }
    for (const Model::BoundaryEdge& be : selectedEdges())
      condition.dashpots.push_back({be.from, be.to, std::sqrt(mat.density * (mat.bulk + 4.0 * mat.shear / 3.0)),
                                    std::sqrt(mat.density * mat.shear), -1, d.inputVelocity, history, 0.0});
    if (condition.dashpots.empty())
      d.origin.failTable("selects no boundary edge of block '" + m.blocks.name[block] +
                         "': dashpots act on edges of the block's outline whose two ends are both selected");
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
  if (condition.edges.empty())
    d.origin.failTable("selects no boundary edge of block '" + m.blocks.name[block] +
                       "': stress and pressure act on edges of the block's outline whose two ends are both selected");
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
