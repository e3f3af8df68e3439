#include "geometry/zoning.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

namespace vdec {

namespace {

// Where the diagonals a-c and b-d of a convex quadrilateral cross.
Vec2 diagonalCrossing(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const Vec2 ac = c - a, bd = d - b;
  const double t = cross(b - a, bd) / cross(ac, bd);
  return a + t * ac;
}

// A structured grid of (nx + 1) x (ny + 1) nodes from a map (i, j) -> point, right-handed
// (increasing i then j turns counter-clockwise), crossed: a node where each cell's diagonals
// cross and four triangles per cell. At the crossing the four triangles pair into the two
// diagonal splits of the cell, which is what frees crossed zones from volumetric locking under
// isochoric plastic flow (1.5.2); the mean of the corners does that only in parallelograms.
template <class Map>
Mesh crossedGrid(int nx, int ny, Map map) {
  Mesh mesh;
  auto corner = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) mesh.nodes.push_back(map(i, j));
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = corner(i, j), b = corner(i + 1, j), c = corner(i + 1, j + 1), d = corner(i, j + 1);
      const int centre = static_cast<int>(mesh.nodes.size());
      mesh.nodes.push_back(diagonalCrossing(mesh.nodes[a], mesh.nodes[b], mesh.nodes[c], mesh.nodes[d]));
      mesh.triangles.push_back({a, b, centre});
      mesh.triangles.push_back({b, c, centre});
      mesh.triangles.push_back({c, d, centre});
      mesh.triangles.push_back({d, a, centre});
    }
  }
  return mesh;
}

}  // namespace

Mesh crossedQuadMesh(const std::array<Vec2, 4>& p, int nx, int ny) {
  return crossedGrid(nx, ny, [&](int i, int j) {
    const double u = static_cast<double>(i) / nx, v = static_cast<double>(j) / ny;
    return (1 - u) * (1 - v) * p[0] + u * (1 - v) * p[1] + u * v * p[2] + (1 - u) * v * p[3];
  });
}

Mesh crossedAnnulusMesh(const AnnulusSpec& s) {
  // Radii with each cell `grading` times the one inside it; the outermost lands exactly on
  // `outer` rather than by summing.
  std::vector<double> radius(s.radial + 1);
  double total = 0.0, thickness = 1.0;
  for (int k = 0; k < s.radial; ++k, thickness *= s.grading) total += thickness;
  double sum = 0.0;
  thickness = 1.0;
  for (int k = 0; k <= s.radial; ++k) {
    radius[k] = k == s.radial ? s.outer : s.inner + (s.outer - s.inner) * sum / total;
    sum += thickness;
    thickness *= s.grading;
  }
  return crossedGrid(s.radial, s.circumferential, [&](int i, int j) {
    const double theta = j == s.circumferential ? s.angle1
                                                : s.angle0 + (s.angle1 - s.angle0) * j / s.circumferential;
    return s.centre + radius[i] * Vec2{std::cos(theta), std::sin(theta)};
  });
}

std::vector<std::array<int, 2>> boundaryEdges(const Mesh& mesh) {
  std::map<std::pair<int, int>, int> uses;  // undirected side -> number of triangles
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) ++uses[{std::min(t[c], t[(c + 1) % 3]), std::max(t[c], t[(c + 1) % 3])}];
  std::vector<std::array<int, 2>> edges;
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      if (uses[{std::min(t[c], t[(c + 1) % 3]), std::max(t[c], t[(c + 1) % 3])}] == 1)
        edges.push_back({t[c], t[(c + 1) % 3]});
  return edges;
}

MeshQuality meshQuality(const Mesh& mesh) {
  MeshQuality q;
  q.minAngleDegrees = 180.0;
  q.minArea = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Vec2 p[3] = {mesh.nodes[tri[0]], mesh.nodes[tri[1]], mesh.nodes[tri[2]]};
    const double area = 0.5 * cross(p[1] - p[0], p[2] - p[0]);
    double longest = 0.0;
    for (int k = 0; k < 3; ++k) {
      const Vec2 e1 = p[(k + 1) % 3] - p[k], e2 = p[(k + 2) % 3] - p[k];
      const double angle = std::atan2(std::abs(cross(e1, e2)), dot(e1, e2)) * 180.0 / std::numbers::pi;
      if (angle < q.minAngleDegrees) {
        q.minAngleDegrees = angle;
        q.worstTriangle = static_cast<int>(t);
      }
      longest = std::max(longest, norm(e1));
    }
    q.minArea = std::min(q.minArea, area);
    // Shortest height = 2 A / longest edge.
    q.maxAspectRatio = std::max(q.maxAspectRatio, area > 0 ? longest * longest / (2.0 * area) : INFINITY);
  }
  return q;
}

}  // namespace vdec
