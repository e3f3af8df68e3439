// The boundary-element far field: the interface picked from the blocks' outer edges (deformable or rigid),
// ordered into a loop (or, for a half-plane, a chain between two points of the free surface), its
// stiffness formed, and the stress the zones hold there at installation taken as its own.
#include <chrono>
#include <cmath>

#include "bem/boundary_elements.hpp"
#include "bem/far_field.hpp"
#include "core/shown.hpp"
#include "scene/build_parts.hpp"

namespace vdec {

namespace {

std::string at(Vec2 p) { return "(" + shown(p.x) + ", " + shown(p.y) + ")"; }

// A point of a block's outline: a deformable block's gridpoint or a rigid block's vertex.
struct OutlinePoint {
  int gridpoint = -1, vertex = -1;
  Vec2 position;  // at the start
  bool operator==(const OutlinePoint& o) const { return gridpoint == o.gridpoint && vertex == o.vertex; }
};

// An edge of a block's outline, counter-clockwise about the block.
struct Side {
  int block = -1;
  OutlinePoint from, to;
};

// The outline edges of the blocks taken whose two ends the selection holds.
std::vector<Side> selectedSides(const Model& m, const BoundaryElementsDefinition& d, const std::vector<char>& inBlocks,
                                double& slack) {
  const GridpointSelection picked = selectGridpoints(m, inBlocks, d.x, d.y, d.r, d.angle, d.centre);
  slack = picked.slack;
  std::vector<Side> sides;
  for (const Model::BoundaryEdge& e : m.boundaryEdges)
    if (inBlocks[e.block] && picked.selected[e.from] && picked.selected[e.to])
      sides.push_back({e.block, {e.from, -1, m.gridpoints.initialPosition[e.from]}, {e.to, -1, m.gridpoints.initialPosition[e.to]}});
  for (int b = 0; b < m.blocks.size(); ++b) {
    if (!inBlocks[b] || m.blocks.deformable[b]) continue;
    const int first = m.blocks.firstVertex[b], count = m.blocks.vertexCount[b];
    for (int k = 0; k < count; ++k) {
      const int from = first + k, to = first + (k + 1) % count;
      if (picked.selectedVertex[from] && picked.selectedVertex[to])
        sides.push_back({b, {-1, from, m.vertices.geometry[from].position}, {-1, to, m.vertices.geometry[to].position}});
    }
  }
  return sides;
}

// The selected outer edges, in order along the boundary: each edge's end meets the next's start
// (coincident points of two blocks where the boundary crosses a joint).
std::vector<Side> orderedSides(const BoundaryElementsDefinition& d, std::vector<Side> sides, double slack, bool& closed) {
  auto meets = [&](const OutlinePoint& to, const OutlinePoint& from) { return norm(to.position - from.position) <= slack; };
  std::size_t first = 0;
  if (d.halfPlane) {
    // The chain starts at the edge no other edge leads into.
    first = sides.size();
    for (std::size_t e = 0; e < sides.size() && first == sides.size(); ++e) {
      bool entered = false;
      for (const Side& other : sides) entered = entered || meets(other.to, sides[e].from);
      if (!entered) first = e;
    }
    if (first == sides.size())
      d.origin.failTable("selects a closed loop of edges; a half-plane's interface is a chain from the free surface "
                         "round the model and back to it: leave the surface's edges out of the selection");
  }
  std::vector<Side> chain{sides[first]};
  sides.erase(sides.begin() + static_cast<long>(first));
  while (!sides.empty()) {
    const auto next = std::find_if(sides.begin(), sides.end(), [&](const Side& e) { return meets(chain.back().to, e.from); });
    if (next == sides.end()) break;
    chain.push_back(*next);
    sides.erase(next);
  }
  closed = meets(chain.back().to, chain.front().from);
  if (!sides.empty())
    d.origin.failTable("selects edges that do not form one " + std::string(d.halfPlane ? "chain" : "loop") +
                       " along the outer boundary (" + std::to_string(chain.size()) + " of " +
                       std::to_string(chain.size() + sides.size()) + " edges follow each other from " +
                       at(chain.front().from.position) + "): select the whole outer boundary and nothing inside it");
  if (!d.halfPlane && !closed)
    d.origin.failTable("selects edges that do not close round the model (the chain runs from " + at(chain.front().from.position) +
                       " to " + at(chain.back().to.position) + "): an infinite plane surrounds the model; select its whole outer "
                       "boundary, or give half_plane = true");
  double twiceArea = 0.0;
  for (const Side& e : chain) twiceArea += cross(e.from.position, e.to.position);
  if (!d.halfPlane && twiceArea < 0.0)
    d.origin.failTable("selects a loop that runs clockwise round what it encloses: the edge of a hole, not the "
                       "model's outer boundary; select the outer boundary");
  if (d.halfPlane) {
    for (const Vec2 end : {chain.front().from.position, chain.back().to.position})
      if (std::abs(end.y - d.surfaceY) > slack)
        d.origin.fail("surface_y", "the interface's chain ends at " + at(end) + ", not on the free surface y = " +
                                       shown(d.surfaceY) + ": the model's top must lie on the surface");
  }
  return chain;
}

}  // namespace

BoundaryElementField boundaryElementField(const Model& m, const BoundaryElementsDefinition& d) {
  if (m.gravity.x != 0.0 || m.gravity.y != 0.0)
    d.origin.failTable("needs gravity = [0, 0]: the far field has no weight of its own to carry the blocks'; give the "
                       "stress of depth as [initial_stress]");
  std::vector<char> inBlocks(m.blocks.size(), 1);
  if (!d.block.empty()) {
    inBlocks.assign(m.blocks.size(), 0);
    inBlocks[blockNamed(m, d.origin, "block", d.block)] = 1;
  }
  double slack = 0.0;
  const std::vector<Side> candidates = selectedSides(m, d, inBlocks, slack);
  // An edge another block's edge lies against (a joint) is inside the model, not on its outer boundary.
  auto jointed = [&](const Side& e) {
    for (const Side& other : candidates)
      if (other.block != e.block && norm(other.from.position - e.to.position) <= slack &&
          norm(other.to.position - e.from.position) <= slack)
        return true;
    return false;
  };
  // Nor is an edge on a half-plane's free surface: the region has none there.
  auto onSurface = [&](const Side& e) {
    return d.halfPlane && std::abs(e.from.position.y - d.surfaceY) <= slack && std::abs(e.to.position.y - d.surfaceY) <= slack;
  };
  std::vector<Side> sides;
  for (const Side& e : candidates)
    if (!jointed(e) && !onSurface(e)) sides.push_back(e);
  if (sides.size() < 3)
    d.origin.failTable("selects " + std::to_string(sides.size()) + " outer edges; the interface needs at least 3: check x, y, r, angle");
  BoundaryElementField be;
  const std::vector<Side> chain = orderedSides(d, sides, slack, be.closed);
  be.young = d.young;
  be.poisson = d.poisson;
  be.halfPlane = d.halfPlane;
  be.surfaceY = d.surfaceY;
  const std::size_t nodes = be.closed ? chain.size() : chain.size() + 1;
  be.edgeMember.assign(chain.size(), {-1, -1});
  auto length = [&](std::size_t e) { return norm(chain[e].to.position - chain[e].from.position); };
  for (std::size_t k = 0; k < nodes; ++k) {
    be.firstMember.push_back(static_cast<int>(be.memberGridpoint.size()));
    // The edge leaving the node (edge k) and the one arriving (edge k - 1), where they exist.
    const bool leaving = k < chain.size(), arriving = k > 0 || be.closed;
    const std::size_t before = k > 0 ? k - 1 : chain.size() - 1;
    auto add = [&](const OutlinePoint& p, double weight) {
      be.memberGridpoint.push_back(p.gridpoint);
      be.memberVertex.push_back(p.vertex);
      be.memberWeight.push_back(weight);
      return static_cast<int>(be.memberGridpoint.size()) - 1;
    };
    if (leaving && arriving && !(chain[k].from == chain[before].to)) {
      const double out = length(k), in = length(before);
      be.edgeMember[k][0] = add(chain[k].from, out / (out + in));
      be.edgeMember[before][1] = add(chain[before].to, in / (out + in));
      be.node.push_back((out * chain[k].from.position + in * chain[before].to.position) * (1.0 / (out + in)));
      continue;
    }
    const OutlinePoint& p = leaving ? chain[k].from : chain[before].to;
    const int member = add(p, 1.0);
    if (leaving) be.edgeMember[k][0] = member;
    if (arriving) be.edgeMember[before][1] = member;
    be.node.push_back(p.position);
  }
  be.firstMember.push_back(static_cast<int>(be.memberGridpoint.size()));
  for (const Side& e : chain) be.edge.push_back({e.from.gridpoint, e.to.gridpoint});
  const auto started = std::chrono::steady_clock::now();
  ElasticRegion region;
  region.young = d.young;
  region.poisson = d.poisson;
  region.halfPlane = d.halfPlane;
  region.surfaceY = d.surfaceY;
  // Collocation gives a K that is symmetric only to its discretisation; its symmetric part keeps
  // the coupling conservative and lets the direct solve's symmetric factorisation take it.
  const Eigen::MatrixXd raw = boundaryStiffness(be.node, be.closed, region);
  const Eigen::MatrixXd K = 0.5 * (raw + raw.transpose());
  be.stiffness.resize(static_cast<std::size_t>(K.rows()) * static_cast<std::size_t>(K.cols()));
  for (Eigen::Index r = 0; r < K.rows(); ++r)
    for (Eigen::Index c = 0; c < K.cols(); ++c) be.stiffness[static_cast<std::size_t>(r * K.cols() + c)] = K(r, c);
  be.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return be;
}

void holdInSitu(BoundaryElementField& be, const InitialStressDefinition& d) {
  for (int c = 0; c < 3; ++c) {
    be.inSitu[c] = d.stress[c];
    be.inSituGradientX[c] = d.gradientX[c];
    be.inSituGradientY[c] = d.gradientY[c];
  }
}

}  // namespace vdec
