#include "contact/contact_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vdec {

namespace {

int nextVertex(const Model& m, int v) {
  const int b = m.vertices.block[v];
  const int first = m.blocks.firstVertex[b], n = m.blocks.vertexCount[b];
  return first + (v - first + 1) % n;
}
int prevVertex(const Model& m, int v) {
  const int b = m.vertices.block[v];
  const int first = m.blocks.firstVertex[b], n = m.blocks.vertexCount[b];
  return first + (v - first + n - 1) % n;
}
Vec2 outwardNormal(Vec2 a, Vec2 b) {
  const Vec2 e = normalized(b - a);
  return {e.y, -e.x};  // right of the edge direction: outside for a counter-clockwise polygon
}

// Feature index within block B: 2k = corner k, 2k + 1 = edge k (from vertex k to k+1).
struct Evaluation {
  int step = 0;  // 0: the centre lies in this feature's region; -1 / +1: look backwards / forwards
  FeatureHit hit;
};

Evaluation evaluate(const Model& m, int blockB, int localFeature, Vec2 centre, double radius) {
  const int first = m.blocks.firstVertex[blockB], n = m.blocks.vertexCount[blockB];
  const int k = localFeature / 2;
  const int v = first + k;
  const auto& pos = m.vertices.position;
  Evaluation out;
  if (localFeature % 2 == 1) {
    const Vec2 a = pos[v], b = pos[first + (k + 1) % n];
    const double length = norm(b - a);
    const Vec2 e = (1.0 / length) * (b - a);
    const Vec2 nOut{e.y, -e.x};
    const double d = m.roundingLength;
    const double s = dot(centre - a, e);
    if (s < d) out.step = -1;
    else if (s > length - d) out.step = +1;
    const double h = dot(centre - a, nOut);
    out.hit = {v, FeatureKind::Edge, nOut, centre - (0.5 * (radius + h)) * nOut, radius - h};
    return out;
  }
  const Vec2 o = m.vertices.arcCentre[v];
  const double rB = m.vertices.arcRadius[v];
  const Vec2 w = centre - o;
  const double dist = norm(w);
  const Vec2 nPrev = outwardNormal(pos[first + (k + n - 1) % n], pos[v]);
  const Vec2 nNext = outwardNormal(pos[v], pos[first + (k + 1) % n]);
  if (dist <= 0.0) {
    out.hit = {v, FeatureKind::Corner, normalized(nPrev + nNext), o, std::numeric_limits<double>::infinity()};
    return out;
  }
  const Vec2 u = (1.0 / dist) * w;
  if (cross(nPrev, u) < 0.0) out.step = -1;
  else if (cross(u, nNext) < 0.0) out.step = +1;
  const Vec2 surfaceB = o + rB * u, surfaceA = centre - radius * u;
  out.hit = {v, FeatureKind::Corner, u, 0.5 * (surfaceA + surfaceB), radius + rB - dist};
  return out;
}

int localIndex(const Model& m, int blockB, int feature, FeatureKind kind) {
  return 2 * (feature - m.blocks.firstVertex[blockB]) + (kind == FeatureKind::Edge ? 1 : 0);
}

}  // namespace

void computeCornerArcs(Model& m) {
  const double d = m.roundingLength;
  auto& vx = m.vertices;
  vx.localArcCentre.resize(vx.size());
  vx.arcCentre.resize(vx.size());
  vx.arcRadius.resize(vx.size());
  for (int v = 0; v < vx.size(); ++v) {
    const Vec2 here = vx.localPosition[v];
    const Vec2 toPrev = normalized(vx.localPosition[prevVertex(m, v)] - here);
    const Vec2 toNext = normalized(vx.localPosition[nextVertex(m, v)] - here);
    const double cosAlpha = std::clamp(dot(toPrev, toNext), -1.0, 1.0);
    const double halfAlpha = 0.5 * std::acos(cosAlpha);  // alpha: interior angle
    const Vec2 bisector = normalized(toPrev + toNext);
    vx.arcRadius[v] = d * std::tan(halfAlpha);
    vx.localArcCentre[v] = here + (d / std::cos(halfAlpha)) * bisector;
  }
}

void placeBlockVertices(Model& m, int b) {
  const double c = std::cos(m.blocks.rotation[b]), s = std::sin(m.blocks.rotation[b]);
  const Vec2 centre = m.blocks.centroid[b];
  auto& vx = m.vertices;
  const int first = m.blocks.firstVertex[b], last = first + m.blocks.vertexCount[b];
  for (int v = first; v < last; ++v) {
    vx.position[v] = centre + rotated(vx.localPosition[v], c, s);
    vx.arcCentre[v] = centre + rotated(vx.localArcCentre[v], c, s);
  }
}

FeatureHit nearestFeature(const Model& m, int corner, int blockB) {
  const Vec2 centre = m.vertices.arcCentre[corner];
  const double radius = m.vertices.arcRadius[corner];
  // Outside B exactly one feature's region holds the centre; inside (a sharp corner pressed in
  // further than its arc radius) several may, and the one with least overlap is the nearest.
  FeatureHit best;
  best.overlap = std::numeric_limits<double>::infinity();
  bool found = false;
  for (int f = 0; f < 2 * m.blocks.vertexCount[blockB]; ++f) {
    const Evaluation e = evaluate(m, blockB, f, centre, radius);
    if (e.step == 0 && (!found || e.hit.overlap < best.overlap)) {
      best = e.hit;
      found = true;
    }
  }
  return best;
}

FeatureHit followFeature(const Model& m, int corner, int blockB, int feature, FeatureKind kind) {
  const Vec2 centre = m.vertices.arcCentre[corner];
  const double radius = m.vertices.arcRadius[corner];
  const int count = 2 * m.blocks.vertexCount[blockB];
  int f = localIndex(m, blockB, feature, kind);
  int previousStep = 0;
  for (int i = 0; i < count; ++i) {
    const Evaluation e = evaluate(m, blockB, f, centre, radius);
    // A reversal means the centre sits in a fold of two regions (only possible deep inside B).
    if (e.step == 0 || e.step == -previousStep) return e.step == 0 ? e.hit : nearestFeature(m, corner, blockB);
    previousStep = e.step;
    f = (f + e.step + count) % count;
  }
  return nearestFeature(m, corner, blockB);
}

double contactLength(const Model& m, int corner, const FeatureHit& hit) {
  const auto& pos = m.vertices.position;
  const Vec2 here = pos[corner];
  const Vec2 along = perp(hit.normal);
  // The contacted surface line and, for an edge, its extent along `along`.
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  if (hit.kind == FeatureKind::Edge) {
    const double s0 = dot(pos[hit.feature] - hit.point, along);
    const double s1 = dot(pos[nextVertex(m, hit.feature)] - hit.point, along);
    lo = std::min(s0, s1);
    hi = std::max(s0, s1);
  }
  double length = 0.0;
  for (const int other : {prevVertex(m, corner), nextVertex(m, corner)}) {
    const Vec2 far = pos[other];
    const double a = dot(here - hit.point, along), b = dot(far - hit.point, along);
    if (a == b) continue;
    const double c0 = std::clamp(a, lo, hi), c1 = std::clamp(b, lo, hi);
    // Clipped far end, as a point of the edge.
    const Vec2 clippedFar = here + ((c1 - a) / (b - a)) * (far - here);
    const Vec2 clippedNear = here + ((c0 - a) / (b - a)) * (far - here);
    const double gapAtFar = std::abs(dot(clippedFar - hit.point, hit.normal));
    if (gapAtFar <= m.contactTolerance) length += 0.5 * norm(clippedFar - clippedNear);
  }
  return std::max(length, m.roundingLength);
}

}  // namespace vdec
