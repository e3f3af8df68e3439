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
  std::vector<int> boundary;                  // counter-clockwise loop of node ids
};

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

struct MeshQuality {
  double minAngleDegrees = 0.0;   // smallest interior angle of any triangle
  double maxAspectRatio = 0.0;    // largest of longest edge / shortest height
  double minArea = 0.0;
  int worstTriangle = -1;         // of the smallest angle
};
MeshQuality meshQuality(const Mesh& mesh);

}  // namespace vdec
