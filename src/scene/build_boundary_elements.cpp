// The boundary-element far field: the interface picked from the deformable blocks' outer edges,
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

// The selected outer edges, in order along the boundary: each edge's end meets the next's start
// (coincident gridpoints of two blocks where the boundary crosses a joint).
std::vector<Model::BoundaryEdge> orderedEdges(const Model& m, const BoundaryElementsDefinition& d,
                                              std::vector<Model::BoundaryEdge> edges, double slack, bool& closed) {
  const std::vector<Vec2>& p = m.gridpoints.initialPosition;
  auto meets = [&](int to, int from) { return norm(p[to] - p[from]) <= slack; };
  std::size_t first = 0;
  if (d.halfPlane) {
    // The chain starts at the edge no other edge leads into.
    first = edges.size();
    for (std::size_t e = 0; e < edges.size() && first == edges.size(); ++e) {
      bool entered = false;
      for (const Model::BoundaryEdge& other : edges) entered = entered || meets(other.to, edges[e].from);
      if (!entered) first = e;
    }
    if (first == edges.size())
      d.origin.failTable("selects a closed loop of edges; a half-plane's interface is a chain from the free surface "
                         "round the model and back to it: leave the surface's edges out of the selection");
  }
  std::vector<Model::BoundaryEdge> chain{edges[first]};
  edges.erase(edges.begin() + static_cast<long>(first));
  while (!edges.empty()) {
    const auto next = std::find_if(edges.begin(), edges.end(), [&](const Model::BoundaryEdge& e) { return meets(chain.back().to, e.from); });
    if (next == edges.end()) break;
    chain.push_back(*next);
    edges.erase(next);
  }
  closed = meets(chain.back().to, chain.front().from);
  if (!edges.empty())
    d.origin.failTable("selects edges that do not form one " + std::string(d.halfPlane ? "chain" : "loop") +
                       " along the outer boundary (" + std::to_string(chain.size()) + " of " +
                       std::to_string(chain.size() + edges.size()) + " edges follow each other from " +
                       at(p[chain.front().from]) + "): select the whole outer boundary and nothing inside it");
  if (!d.halfPlane && !closed)
    d.origin.failTable("selects edges that do not close round the model (the chain runs from " + at(p[chain.front().from]) +
                       " to " + at(p[chain.back().to]) + "): an infinite plane surrounds the model; select its whole outer "
                       "boundary, or give half_plane = true");
  double twiceArea = 0.0;
  for (const Model::BoundaryEdge& e : chain) twiceArea += cross(p[e.from], p[e.to]);
  if (!d.halfPlane && twiceArea < 0.0)
    d.origin.failTable("selects a loop that runs clockwise round what it encloses: the edge of a hole, not the "
                       "model's outer boundary; select the outer boundary");
  if (d.halfPlane) {
    for (const Vec2 end : {p[chain.front().from], p[chain.back().to]})
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
  std::vector<char> inBlocks(m.blocks.size(), 0);
  if (d.block.empty()) {
    for (int b = 0; b < m.blocks.size(); ++b) inBlocks[b] = m.blocks.deformable[b];
  } else {
    const int block = blockNamed(m, d.origin, "block", d.block);
    if (!m.blocks.deformable[block])
      d.origin.fail("block", "block '" + d.block + "' is rigid: the far field couples to deformable blocks' gridpoints");
    inBlocks[block] = 1;
  }
  const GridpointSelection picked = selectGridpoints(m, inBlocks, d.x, d.y, d.r, d.angle, d.centre);
  const std::vector<char>& selected = picked.selected;
  const double slack = picked.slack;
  const Gridpoints& g = m.gridpoints;
  // An edge another block's edge lies against (a joint) is inside the model, not on its outer boundary.
  auto jointed = [&](const Model::BoundaryEdge& e) {
    for (const Model::BoundaryEdge& other : m.boundaryEdges)
      if (other.block != e.block && norm(g.initialPosition[other.from] - g.initialPosition[e.to]) <= slack &&
          norm(g.initialPosition[other.to] - g.initialPosition[e.from]) <= slack)
        return true;
    return false;
  };
  // Nor is an edge on a half-plane's free surface: the region has none there.
  auto onSurface = [&](const Model::BoundaryEdge& e) {
    return d.halfPlane && std::abs(g.initialPosition[e.from].y - d.surfaceY) <= slack &&
           std::abs(g.initialPosition[e.to].y - d.surfaceY) <= slack;
  };
  std::vector<Model::BoundaryEdge> edges;
  for (const Model::BoundaryEdge& be : m.boundaryEdges)
    if (inBlocks[be.block] && selected[be.from] && selected[be.to] && !jointed(be) && !onSurface(be)) edges.push_back(be);
  if (edges.size() < 3)
    d.origin.failTable("selects " + std::to_string(edges.size()) + " outer edges; the interface needs at least 3: check x, y, r, angle");
  BoundaryElementField be;
  const std::vector<Model::BoundaryEdge> chain = orderedEdges(m, d, edges, slack, be.closed);
  be.young = d.young;
  be.poisson = d.poisson;
  be.halfPlane = d.halfPlane;
  be.surfaceY = d.surfaceY;
  const std::size_t nodes = be.closed ? chain.size() : chain.size() + 1;
  for (std::size_t k = 0; k < nodes; ++k) {
    be.firstGridpoint.push_back(static_cast<int>(be.gridpoints.size()));
    std::vector<int> joined;
    if (k < chain.size()) joined.push_back(chain[k].from);
    const int before = k > 0 ? chain[k - 1].to : (be.closed ? chain.back().to : -1);
    if (before >= 0 && std::find(joined.begin(), joined.end(), before) == joined.end()) joined.push_back(before);
    Vec2 mean;
    for (const int p : joined) mean += g.position[p];
    be.node.push_back((1.0 / static_cast<double>(joined.size())) * mean);
    be.gridpoints.insert(be.gridpoints.end(), joined.begin(), joined.end());
  }
  be.firstGridpoint.push_back(static_cast<int>(be.gridpoints.size()));
  for (const Model::BoundaryEdge& e : chain) be.edge.push_back({e.from, e.to});
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

}  // namespace vdec
