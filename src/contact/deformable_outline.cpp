#include "contact/deformable_outline.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>

#include "core/errors.hpp"

namespace vdec {

namespace {

// The outer loop of a block's boundary edges (each directed with the block on its left).
std::vector<int> outerLoop(const Model& m, int block) {
  std::map<int, int> nextOf;
  for (const Model::BoundaryEdge& e : m.boundaryEdges) {
    if (e.block != block) continue;
    if (!nextOf.emplace(e.from, e.to).second) {
      const Vec2 p = m.gridpoints.initialPosition[e.from];
      std::ostringstream s;
      s << "block '" << m.blocks.name[block] << "': its outline touches itself at the gridpoint at (" << p.x << ", "
        << p.y << "), where zones meet only at a corner; contacts need a simple outline: change the zoning or the "
        << "excavation so that no two zones of the block meet at a single point";
      throw GeometryError(s.str());
    }
  }
  // Each loop with positive area is a piece of the block's outline; holes run clockwise.
  std::vector<int> outer;
  int pieces = 0;
  std::map<int, char> visited;
  for (const auto& [start, ignored] : nextOf) {
    if (visited[start]) continue;
    std::vector<int> loop;
    double area = 0.0;
    for (int g = start; !visited[g]; g = nextOf.at(g)) {
      visited[g] = 1;
      loop.push_back(g);
      area += 0.5 * cross(m.gridpoints.initialPosition[g], m.gridpoints.initialPosition[nextOf.at(g)]);
    }
    if (area <= 0.0) continue;
    ++pieces;
    outer = std::move(loop);
  }
  if (pieces != 1)
    throw GeometryError("block '" + m.blocks.name[block] + "' is in " + std::to_string(pieces) + " pieces (an "
                        "excavation cut it apart): contacts need each deformable block in one piece; give the "
                        "pieces as blocks of their own, or change the excavation");
  return outer;
}

// The interior angle (radians) of a counter-clockwise outline at `here`.
double interiorAngle(Vec2 before, Vec2 here, Vec2 after) {
  const Vec2 in = here - before, out = after - here;
  const double turn = std::atan2(cross(in, out), dot(in, out));  // left turn positive
  return std::numbers::pi - turn;
}

}  // namespace

void attachDeformableOutlines(Model& m) {
  const Vertices old = m.vertices;
  Vertices& vx = m.vertices;
  vx = {};
  const double maxAngle = kRoundedCornerMaxAngleDegrees * std::numbers::pi / 180.0;
  bool anyDeformable = false;
  for (int b = 0; b < m.blocks.size(); ++b) {
    const int oldFirst = m.blocks.firstVertex[b];
    m.blocks.firstVertex[b] = vx.size();
    if (!m.blocks.deformable[b]) {
      for (int v = oldFirst; v < oldFirst + m.blocks.vertexCount[b]; ++v) {
        vx.block.push_back(b);
        vx.localPosition.push_back(old.localPosition[v]);
        vx.gridpoint.push_back(-1);
        vx.pointCorner.push_back(0);
      }
      continue;
    }
    anyDeformable = true;
    const std::vector<int> loop = outerLoop(m, b);
    const int n = static_cast<int>(loop.size());
    m.blocks.vertexCount[b] = n;
    const auto& p = m.gridpoints.initialPosition;
    for (int k = 0; k < n; ++k) {
      const int g = loop[k];
      const double alpha = interiorAngle(p[loop[(k + n - 1) % n]], p[g], p[loop[(k + 1) % n]]);
      vx.block.push_back(b);
      vx.localPosition.push_back(p[g] - m.blocks.centroid[b]);
      vx.gridpoint.push_back(g);
      vx.pointCorner.push_back(alpha >= maxAngle ? 1 : 0);
    }
    // A rounded corner's arc meets its edges at the rounding length d from the vertex; an edge
    // must be long enough to hold the roundings of both its ends.
    const double d = m.roundingLength;
    const int first = m.blocks.firstVertex[b];
    for (int k = 0; k < n; ++k) {
      const int v = first + k, w = first + (k + 1) % n;
      const double needed = d * ((vx.pointCorner[v] ? 0 : 1) + (vx.pointCorner[w] ? 0 : 1));
      const double length = norm(p[loop[(k + 1) % n]] - p[loop[k]]);
      if (length > needed) continue;
      std::ostringstream s;
      s << "block '" << m.blocks.name[b] << "': the outline segment from (" << p[loop[k]].x << ", " << p[loop[k]].y
        << ") to (" << p[loop[(k + 1) % n]].x << ", " << p[loop[(k + 1) % n]].y << ") is " << length
        << " m long, too short for the rounding (" << d << " m at each of its rounded corners); lower "
        << "model.rounding or zone the block more coarsely near its corners";
      throw GeometryError(s.str());
    }
  }
  if (anyDeformable) m.gridpoints.contactForce.assign(m.gridpoints.size(), Vec2{});
}

void placeOutlineVertices(Model& m, int b) {
  Vertices& vx = m.vertices;
  const Gridpoints& g = m.gridpoints;
  const int first = m.blocks.firstVertex[b], last = first + m.blocks.vertexCount[b];
  for (int v = first; v < last; ++v) vx.geometry[v].position = g.position[vx.gridpoint[v]];
  for (int v = first; v < last; ++v) {
    VertexGeometry& here = vx.geometry[v];
    const Vec2 edge = vx.geometry[vx.next[v]].position - here.position;
    here.edgeLength = norm(edge);
    here.edgeDirection = (1.0 / here.edgeLength) * edge;
  }
  const double d = m.roundingLength;
  for (int v = first; v < last; ++v) {
    VertexGeometry& here = vx.geometry[v];
    if (vx.pointCorner[v]) {
      here.arcRadius = 0.0;
      here.arcCentre = here.position;
      continue;
    }
    // As for a rigid block's corner (computeBoundaryGeometry), from the present edges.
    const Vec2 toPrev = -vx.geometry[vx.prev[v]].edgeDirection, toNext = here.edgeDirection;
    const double halfAlpha = 0.5 * std::acos(std::clamp(dot(toPrev, toNext), -1.0, 1.0));
    here.arcRadius = d * std::tan(halfAlpha);
    here.arcCentre = here.position + (d / std::cos(halfAlpha)) * normalized(toPrev + toNext);
  }
}

}  // namespace vdec
