#include "contact/strained_outline.hpp"

#include <algorithm>
#include <cmath>

namespace vdec {

namespace {

// (I + E) a
Vec2 strained(const Sym2& e, Vec2 a) { return {a.x + e.xx * a.x + e.xy * a.y, a.y + e.xy * a.x + e.yy * a.y}; }

}  // namespace

Vec2 bodyPoint(const StrainModes& s, int k, Vec2 r) {
  const Vec2 local = rotated(r, s.turn[k][0], -s.turn[k][1]);
  const Sym2& u = s.inverseStretch[k];
  return {u.xx * local.x + u.xy * local.y, u.xy * local.x + u.yy * local.y};
}

Vec2 strainVelocityAt(const StrainModes& s, int k, Vec2 X) {
  const Sym2& rate = s.strainRate[k];
  return rotated({rate.xx * X.x + rate.xy * X.y, rate.xy * X.x + rate.yy * X.y}, s.turn[k][0], s.turn[k][1]);
}

Vec2 strainVelocity(const Model& m, int b, Vec2 r) {
  const int k = m.strainModes.of[b];
  return strainVelocityAt(m.strainModes, k, bodyPoint(m.strainModes, k, r));
}

void addStrainForceAt(StrainModes& s, int k, Vec2 X, Vec2 f) {
  const Vec2 fl = rotated(f, s.turn[k][0], -s.turn[k][1]);
  Sym2& q = s.force[k];
  q.xx += fl.x * X.x;
  q.yy += fl.y * X.y;
  q.xy += fl.x * X.y + fl.y * X.x;
}

void placeStrainedVertices(Model& m, int b) {
  StrainModes& sm = m.strainModes;
  const int k = sm.of[b];
  const Sym2& e = sm.strain[k];
  const double c = std::cos(m.blocks.rotation[b]), s = std::sin(m.blocks.rotation[b]);
  sm.turn[k] = {c, s};
  // (I + E)^-1 by its adjugate
  const double a = 1.0 + e.xx, d = 1.0 + e.yy, det = a * d - e.xy * e.xy;
  sm.inverseStretch[k] = {d / det, a / det, -e.xy / det};
  const Vec2 centre = m.blocks.centroid[b];
  Vertices& vx = m.vertices;
  const int first = m.blocks.firstVertex[b], last = first + m.blocks.vertexCount[b];
  for (int v = first; v < last; ++v) vx.geometry[v].position = centre + rotated(strained(e, vx.localPosition[v]), c, s);
  for (int v = first; v < last; ++v) {
    const Vec2 edge = vx.geometry[vx.next[v]].position - vx.geometry[v].position;
    vx.geometry[v].edgeLength = norm(edge);
    vx.geometry[v].edgeDirection = (1.0 / vx.geometry[v].edgeLength) * edge;
  }
  // The rounding follows the strained corners, tangent to their edges at d from the vertex, as a
  // rigid block's is formed (contact_geometry.cpp): an arc centre strained with the block would
  // leave the surface off its edges by the strain times d, which stiff joints would read as
  // closure. With the interior angle alpha between the unit edge directions p and n
  // (cos alpha = p . n), the centre d / cos(alpha/2) along the bisector (p + n) / |p + n| is
  // vertex + d (p + n) / (1 + cos alpha), and the radius d tan(alpha/2) = d sqrt((1 - cos) / (1 + cos)).
  const double rounding = m.roundingLength;
  for (int v = first; v < last; ++v) {
    const Vec2 toPrev = -1.0 * vx.geometry[vx.prev[v]].edgeDirection, toNext = vx.geometry[v].edgeDirection;
    const double cosAlpha = std::clamp(dot(toPrev, toNext), -1.0, 1.0);
    vx.geometry[v].arcRadius = rounding * std::sqrt((1.0 - cosAlpha) / (1.0 + cosAlpha));
    vx.geometry[v].arcCentre = vx.geometry[v].position + (rounding / (1.0 + cosAlpha)) * (toPrev + toNext);
  }
}

}  // namespace vdec
