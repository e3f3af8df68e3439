#pragma once
// Zoning of deformable blocks into constant-strain triangles (NUREG/CR-5429 1.3.3.3).
// Structured zoning only: a quadrilateral block mapped bilinearly onto an nx x ny grid, or a
// graded quarter annulus (a quarter plane with a circular hole, a thick cylinder); every grid
// cell is "crossed" into four triangles through both diagonals (1.5.2), which keeps the
// response of a cell independent of a diagonal's direction and is what plastic flow needs.
#include <array>
#include <vector>

#include "core/vec2.hpp"

namespace vdec {

struct Mesh {
  std::vector<Vec2> nodes;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise
};

// The outline of a mesh: every triangle side no other triangle shares, directed as in its
// triangle (so the outside is on its right). Holes and several loops come out the same way.
std::vector<std::array<int, 2>> boundaryEdges(const Mesh& mesh);

// The mesh without the triangles whose centroid `inside` holds, and without nodes left unused
// (node ids renumbered in order).
template <class Inside>
Mesh withoutTriangles(const Mesh& mesh, Inside inside) {
  Mesh out;
  std::vector<int> renumber(mesh.nodes.size(), -1);
  for (const auto& t : mesh.triangles) {
    if (inside((1.0 / 3.0) * (mesh.nodes[t[0]] + mesh.nodes[t[1]] + mesh.nodes[t[2]]))) continue;
    std::array<int, 3> kept{};
    for (int c = 0; c < 3; ++c) {
      if (renumber[t[c]] < 0) {
        renumber[t[c]] = static_cast<int>(out.nodes.size());
        out.nodes.push_back(mesh.nodes[t[c]]);
      }
      kept[c] = renumber[t[c]];
    }
    out.triangles.push_back(kept);
  }
  return out;
}

// The mesh with its nodes numbered in the order its triangles first use them. A contiguous run
// of zones and one of gridpoints then cover the same part of a block, so that the threads'
// shares of the zone loop and of the gridpoint loop meet the same data (core/thread_team.hpp).
inline Mesh inZoneOrder(const Mesh& mesh) {
  return withoutTriangles(mesh, [](Vec2) { return false; });
}

// A convex quadrilateral (counter-clockwise corners) cut into nx x ny cells along its sides.
Mesh crossedQuadMesh(const std::array<Vec2, 4>& corners, int nx, int ny);

// The annular sector inner <= r <= outer, angle0 <= theta <= angle1 (radians) about `centre`:
// `radial` cells from the inside out, each `grading` times as thick as the one inside it, and
// `circumferential` equal cells in angle.
struct AnnulusSpec {
  Vec2 centre;
  double inner = 0.0, outer = 0.0;
  double angle0 = 0.0, angle1 = 0.0;
  int radial = 0, circumferential = 0;
  double grading = 1.0;
};
Mesh crossedAnnulusMesh(const AnnulusSpec& spec);

// A polygon (counter-clockwise) zoned into quality triangles by constrained Delaunay refinement
// (CGAL): smallest angle at least 20.7 degrees, no side longer than maxEdge.
Mesh delaunayMesh(const std::vector<Vec2>& outline, double maxEdge);

struct MeshQuality {
  double minAngleDegrees = 0.0;   // smallest interior angle of any triangle
  double maxAspectRatio = 0.0;    // largest of longest edge / shortest height
  double minArea = 0.0;
  int worstTriangle = -1;         // of the smallest angle
};
MeshQuality meshQuality(const Mesh& mesh);

}  // namespace vdec
