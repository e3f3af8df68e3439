#include "geometry/polygon.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "core/errors.hpp"

namespace vdec {

double signedArea(const Polygon& p) {
  double twice = 0.0;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) twice += cross(p[i], p[(i + 1) % n]);
  return 0.5 * twice;
}

Vec2 centroid(const Polygon& p) {
  // Shifting to the first vertex keeps the sums small for polygons far from the origin.
  const Vec2 o = p[0];
  double a2 = 0.0;
  Vec2 s;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    const Vec2 u = p[i] - o, v = p[(i + 1) % n] - o;
    const double c = cross(u, v);
    a2 += c;
    s += c * (u + v);
  }
  return o + (1.0 / (3.0 * a2)) * s;
}

double polarSecondMoment(const Polygon& p) {
  const Vec2 c = centroid(p);
  double j = 0.0;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    const Vec2 u = p[i] - c, v = p[(i + 1) % n] - c;
    j += cross(u, v) * (dot(u, u) + dot(u, v) + dot(v, v));
  }
  return j / 12.0;
}

SecondMoments secondMoments(const Polygon& p) {
  const Vec2 c = centroid(p);
  SecondMoments j;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    const Vec2 u = p[i] - c, v = p[(i + 1) % n] - c;
    const double w = cross(u, v);
    j.xx += w * (u.x * u.x + u.x * v.x + v.x * v.x);
    j.yy += w * (u.y * u.y + u.y * v.y + v.y * v.y);
    j.xy += w * (u.x * v.y + 2.0 * u.x * u.y + 2.0 * v.x * v.y + v.x * u.y);
  }
  j.xx /= 12.0;
  j.yy /= 12.0;
  j.xy /= 24.0;
  return j;
}

namespace {

bool segmentsCross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 &&
         d4 != 0;
}

std::string numberText(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

std::string pointText(Vec2 v) {
  std::ostringstream s;
  s.precision(10);
  s << "(" << v.x << ", " << v.y << ")";
  return s.str();
}

}  // namespace

void validateBlockPolygon(const Polygon& p, double d, const std::string& what) {
  const std::size_t n = p.size();
  if (n < 3) throw GeometryError(what + ": a block needs at least 3 vertices, got " + std::to_string(n));
  double scale = 0.0;
  for (const Vec2& v : p) scale = std::max(scale, std::max(std::abs(v.x), std::abs(v.y)));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      if (segmentsCross(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]))
        throw GeometryError(what + ": polygon is self-intersecting (edge " + std::to_string(i) +
                            " crosses edge " + std::to_string(j) + ")");
    }
  const double area = signedArea(p);
  double longest = 0.0;
  for (std::size_t i = 0; i < n; ++i) longest = std::max(longest, norm(p[(i + 1) % n] - p[i]));
  if (!std::isfinite(area) || !std::isfinite(longest))
    throw GeometryError(what + ": its area or an edge length overflows (coordinates up to " + numberText(scale) +
                        "): give the vertices in m, below about 1e150");
  if (std::abs(area) <= 1e-12 * longest * longest)
    throw GeometryError(what + ": polygon has zero area");
  if (area < 0)
    throw GeometryError(what + ": vertices are clockwise; list them counter-clockwise");
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 prev = p[(i + n - 1) % n], here = p[i], next = p[(i + 1) % n];
    const double turn = cross(here - prev, next - here);
    if (turn <= 1e-12 * norm(here - prev) * norm(next - here))
      throw GeometryError(what + ": corner " + std::to_string(i) + " at " + pointText(here) +
                          " is reflex or straight; vdec supports convex blocks only: split the "
                          "block with a crack through that corner, or remove the vertex");
    const double edge = norm(next - here);
    if (edge <= 2.0 * d)
      throw GeometryError(what + ": edge " + std::to_string(i) + " from " + pointText(here) +
                          " has length " + numberText(edge) +
                          ", not more than twice the rounding length d = " + numberText(d) +
                          "; reduce model.rounding or remove the short edge");
  }
}

std::optional<std::pair<double, double>> chordParameters(const Polygon& p, Vec2 point, Vec2 dir) {
  // Clip the line against each edge's inner half-plane (Cyrus-Beck for a convex polygon).
  double s0 = -std::numeric_limits<double>::infinity();
  double s1 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    const Vec2 a = p[i], b = p[(i + 1) % n];
    const Vec2 inward = perp(b - a);  // counter-clockwise polygon: left of the edge is inside
    const double num = dot(point - a, inward);
    const double den = dot(dir, inward);
    if (den == 0.0) {
      if (num <= 0.0) return std::nullopt;
      continue;
    }
    const double s = -num / den;
    if (den > 0) s0 = std::max(s0, s);
    else s1 = std::min(s1, s);
  }
  if (!(s1 > s0)) return std::nullopt;
  return std::make_pair(s0, s1);
}

std::optional<std::pair<Polygon, Polygon>> splitConvex(const Polygon& p, Vec2 point, Vec2 dir) {
  const std::size_t n = p.size();
  std::vector<double> side(n);
  bool anyLeft = false, anyRight = false;
  double scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) scale = std::max(scale, norm(p[i] - point));
  const double snap = 1e-12 * scale;
  for (std::size_t i = 0; i < n; ++i) {
    side[i] = cross(dir, p[i] - point);
    if (std::abs(side[i]) <= snap) side[i] = 0.0;  // a vertex on the line belongs to both parts
    anyLeft |= side[i] > 0;
    anyRight |= side[i] < 0;
  }
  if (!anyLeft || !anyRight) return std::nullopt;
  Polygon left, right;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if (side[i] >= 0) left.push_back(p[i]);
    if (side[i] <= 0) right.push_back(p[i]);
    if ((side[i] > 0 && side[j] < 0) || (side[i] < 0 && side[j] > 0)) {
      const double f = side[i] / (side[i] - side[j]);
      const Vec2 x = p[i] + f * (p[j] - p[i]);
      left.push_back(x);
      right.push_back(x);
    }
  }
  return std::make_pair(std::move(left), std::move(right));
}

bool containsPoint(const Polygon& p, Vec2 point) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!(cross(p[(i + 1) % p.size()] - p[i], point - p[i]) > 0.0)) return false;
  return true;
}

}  // namespace vdec
