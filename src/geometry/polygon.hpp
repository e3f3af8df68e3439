#pragma once
// Polygon properties and validity for blocks. Blocks are convex, counter-clockwise polygons.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/vec2.hpp"

namespace vdec {

using Polygon = std::vector<Vec2>;

double signedArea(const Polygon& p);
Vec2 centroid(const Polygon& p);
// Second moment of area about the centroid, J = int (x^2 + y^2) dA; inertia = density * J.
double polarSecondMoment(const Polygon& p);
// The second moments of area about the centroid: int x^2 dA, int y^2 dA and int x y dA.
struct SecondMoments {
  double xx = 0.0, yy = 0.0, xy = 0.0;
};
SecondMoments secondMoments(const Polygon& p);

// Throws GeometryError naming `what` (e.g. "block 'top'") when the polygon has fewer than
// three vertices, zero area, clockwise order, a self-intersection, a reflex (concave) corner,
// or an edge too short to round with the rounding length (length <= 2 d).
void validateBlockPolygon(const Polygon& p, double roundingLength, const std::string& what);

// Whether the point lies strictly inside the convex, counter-clockwise polygon.
bool containsPoint(const Polygon& p, Vec2 point);

// Splits a convex polygon along the infinite line through `point` with direction `dir`.
// Returns nothing when the line does not cross the interior.
std::optional<std::pair<Polygon, Polygon>> splitConvex(const Polygon& p, Vec2 point, Vec2 dir);

// The chord of the line through (point, dir) inside the convex polygon, as line parameters
// [s0, s1] along dir (unit); nothing when the line misses the interior.
std::optional<std::pair<double, double>> chordParameters(const Polygon& p, Vec2 point, Vec2 dir);

}  // namespace vdec
