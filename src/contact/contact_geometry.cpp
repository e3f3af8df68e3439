#include "contact/contact_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/deformable_outline.hpp"
#include "contact/strained_outline.hpp"

namespace vdec {

namespace {

Vec2 outward(Vec2 edgeDirection) { return {edgeDirection.y, -edgeDirection.x}; }  // right of the edge

// Feature index within block B: 2k = corner k, 2k + 1 = edge k (from vertex k to k+1).
struct Evaluation {
  int step = 0;  // 0: the centre lies in this feature's region; -1 / +1: look backwards / forwards
  FeatureHit hit;
};

// Which side of point corner v a centre lies on: the edges at a point corner meet on the line
// through it along the mean of their normals, i.e. where the mean of their directions projects
// to zero; negative on the side of the edge before v, positive on the edge after it. Edges and
// the corner itself all use this one test, so that a walk never goes back and forth.
double pointCornerSide(const Vertices& vx, int v, Vec2 centre) {
  return dot(centre - vx.geometry[v].position, vx.geometry[vx.prev[v]].edgeDirection + vx.geometry[v].edgeDirection);
}

// Outline: B is a deformable block, whose outline has point corners. A template parameter, so
// that the rigid blocks' walk, the hot loop of the contact stage, stays as small as it was.
template <bool Outline>
Evaluation evaluate(const Model& m, int blockB, int localFeature, Vec2 centre, double radius) {
  const Vertices& vx = m.vertices;
  const int v = m.blocks.firstVertex[blockB] + localFeature / 2;
  Evaluation out;
  if (localFeature % 2 == 1) {
    const Vec2 a = vx.geometry[v].position, e = vx.geometry[v].edgeDirection;
    const Vec2 nOut = outward(e);
    const double d = m.roundingLength;
    const double s = dot(centre - a, e);
    // Regions overlap by a sliver of round-off so that a centre exactly on a boundary (blocks
    // meeting at a grid point) belongs to both neighbours, never to neither.
    const double slack = 1e-9 * d;
    if constexpr (!Outline) {
      if (s < d - slack) out.step = -1;
      else if (s > vx.geometry[v].edgeLength - d + slack) out.step = +1;
    } else {
      // A point corner has no region of its own (pointCornerSide); a rounded corner's arc starts
      // d along the edge, as above.
      const int w = vx.next[v];
      const bool pointBefore = vx.geometry[v].arcRadius == 0.0, pointAfter = vx.geometry[w].arcRadius == 0.0;
      if (pointBefore ? pointCornerSide(vx, v, centre) < -slack : s < d - slack)
        out.step = -1;
      else if (pointAfter ? pointCornerSide(vx, w, centre) > slack : s > vx.geometry[v].edgeLength - d + slack)
        out.step = +1;
    }
    const double h = dot(centre - a, nOut);
    out.hit = {v, FeatureKind::Edge, nOut, centre - (0.5 * (radius + h)) * nOut, radius - h};
    return out;
  }
  if (Outline && vx.geometry[v].arcRadius == 0.0) {
    // A point corner is never the feature: a walk passes through it to the edge on the centre's
    // side. As a feature it would claim centres inside B too, and report a gap where the corner
    // overlaps.
    out.step = pointCornerSide(vx, v, centre) < 0.0 ? -1 : +1;
    return out;
  }
  const Vec2 o = vx.geometry[v].arcCentre;
  const double rB = vx.geometry[v].arcRadius;
  const Vec2 w = centre - o;
  const double dist = norm(w);
  const Vec2 nPrev = outward(vx.geometry[vx.prev[v]].edgeDirection);
  const Vec2 nNext = outward(vx.geometry[v].edgeDirection);
  if (dist <= 0.0) {  // concentric arcs: as deep as two corners can go; any normal will do
    out.hit = {v, FeatureKind::Corner, normalized(nPrev + nNext), o, radius + rB};
    return out;
  }
  const Vec2 u = (1.0 / dist) * w;
  constexpr double slack = 1e-12;  // unit vectors: as for the edges, boundaries belong to both
  if (cross(nPrev, u) < -slack) out.step = -1;
  else if (cross(u, nNext) < -slack) out.step = +1;
  const Vec2 surfaceB = o + rB * u, surfaceA = centre - radius * u;
  out.hit = {v, FeatureKind::Corner, u, 0.5 * (surfaceA + surfaceB), radius + rB - dist};
  return out;
}

int localIndex(const Model& m, int blockB, int feature, FeatureKind kind) {
  return 2 * (feature - m.blocks.firstVertex[blockB]) + (kind == FeatureKind::Edge ? 1 : 0);
}

}  // namespace

void computeBoundaryGeometry(Model& m) {
  const double d = m.roundingLength;
  Vertices& vx = m.vertices;
  const int count = vx.size();
  vx.next.resize(count);
  vx.prev.resize(count);
  vx.localEdgeDirection.resize(count);
  vx.localArcCentre.resize(count);
  vx.geometry.resize(count);
  // Rigid blocks built without attachDeformableOutlines (tests) have only rigid vertices.
  if (vx.gridpoint.size() != static_cast<std::size_t>(count)) vx.gridpoint.assign(count, -1);
  if (vx.pointCorner.size() != static_cast<std::size_t>(count)) vx.pointCorner.assign(count, 0);
  for (int b = 0; b < m.blocks.size(); ++b) {
    const int first = m.blocks.firstVertex[b], n = m.blocks.vertexCount[b];
    for (int k = 0; k < n; ++k) {
      vx.next[first + k] = first + (k + 1) % n;
      vx.prev[first + k] = first + (k + n - 1) % n;
    }
  }
  for (int v = 0; v < count; ++v) {
    const Vec2 edge = vx.localPosition[vx.next[v]] - vx.localPosition[v];
    vx.geometry[v].edgeLength = norm(edge);
    vx.localEdgeDirection[v] = (1.0 / vx.geometry[v].edgeLength) * edge;
  }
  for (int v = 0; v < count; ++v) {
    if (vx.gridpoint[v] >= 0) continue;  // a deformable block's: placeOutlineVertices rounds it
    const Vec2 toPrev = -vx.localEdgeDirection[vx.prev[v]];
    const Vec2 toNext = vx.localEdgeDirection[v];
    const double halfAlpha = 0.5 * std::acos(std::clamp(dot(toPrev, toNext), -1.0, 1.0));  // alpha: interior angle
    vx.geometry[v].arcRadius = d * std::tan(halfAlpha);
    vx.localArcCentre[v] = vx.localPosition[v] + (d / std::cos(halfAlpha)) * normalized(toPrev + toNext);
  }
}

void placeBlockVertices(Model& m, int b) {
  if (m.blocks.deformable[b]) {
    placeOutlineVertices(m, b);
    return;
  }
  if (m.strainModes.holds(b)) {
    placeStrainedVertices(m, b);
    return;
  }
  const double c = std::cos(m.blocks.rotation[b]), s = std::sin(m.blocks.rotation[b]);
  const Vec2 centre = m.blocks.centroid[b];
  Vertices& vx = m.vertices;
  const int first = m.blocks.firstVertex[b], last = first + m.blocks.vertexCount[b];
  for (int v = first; v < last; ++v) {
    vx.geometry[v].position = centre + rotated(vx.localPosition[v], c, s);
    vx.geometry[v].arcCentre = centre + rotated(vx.localArcCentre[v], c, s);
    vx.geometry[v].edgeDirection = rotated(vx.localEdgeDirection[v], c, s);
  }
}

namespace {

template <bool Outline>
FeatureHit nearestFeatureOn(const Model& m, int corner, int blockB) {
  const Vec2 centre = m.vertices.geometry[corner].arcCentre;
  const double radius = m.vertices.geometry[corner].arcRadius;
  // The feature whose surface is nearest the centre, among those whose region holds it: outside
  // a convex block only one region does, but inside it (a sharp corner pressed in further than
  // its arc radius) several may, and outside a non-convex outline (a deformable block's notch or
  // hole) so may the wedge of a corner on the far side, at a large gap. The distance of the
  // centre from a feature's surface is radius - overlap (negative inside). A centre deep inside
  // B may lie in no feature's region; then the nearest edge line serves. A centre on the
  // boundary between an edge's region and a corner's (two blocks' corners meeting exactly)
  // belongs to the corner: that is what lets contact detection see the two corners as one
  // corner-corner contact rather than two corner-edge contacts on one spot.
  const double tie = 1e-9 * m.roundingLength;
  FeatureHit best, nearestEdge;
  double bestDistance = INFINITY;
  bool found = false, edgeFound = false;
  for (int f = 0; f < 2 * m.blocks.vertexCount[blockB]; ++f) {
    const Evaluation e = evaluate<Outline>(m, blockB, f, centre, radius);
    const double distance = std::abs(radius - e.hit.overlap);
    const bool nearer = !found || distance < bestDistance - tie ||
                        (e.hit.kind == FeatureKind::Corner && best.kind == FeatureKind::Edge && distance <= bestDistance + tie);
    if (e.step == 0 && nearer) {
      best = e.hit;
      bestDistance = distance;
      found = true;
    }
    if (f % 2 == 1 && (!edgeFound || e.hit.overlap < nearestEdge.overlap)) {
      nearestEdge = e.hit;
      edgeFound = true;
    }
  }
  return found ? best : nearestEdge;
}

template <bool Outline>
FeatureHit followFeatureOn(const Model& m, int corner, int blockB, int feature, FeatureKind kind) {
  const Vec2 centre = m.vertices.geometry[corner].arcCentre;
  const double radius = m.vertices.geometry[corner].arcRadius;
  const int count = 2 * m.blocks.vertexCount[blockB];
  int f = localIndex(m, blockB, feature, kind);
  int previousStep = 0;
  for (int i = 0; i < count; ++i) {
    const Evaluation e = evaluate<Outline>(m, blockB, f, centre, radius);
    // A reversal means the centre sits in a fold of two regions (only possible deep inside B).
    if (e.step == 0 || e.step == -previousStep) return e.step == 0 ? e.hit : nearestFeatureOn<Outline>(m, corner, blockB);
    previousStep = e.step;
    f = (f + e.step + count) % count;
  }
  return nearestFeatureOn<Outline>(m, corner, blockB);
}

}  // namespace

FeatureHit nearestFeature(const Model& m, int corner, int blockB) {
  return m.blocks.deformable[blockB] ? nearestFeatureOn<true>(m, corner, blockB)
                                     : nearestFeatureOn<false>(m, corner, blockB);
}

FeatureHit followFeature(const Model& m, int corner, int blockB, int feature, FeatureKind kind) {
  return m.blocks.deformable[blockB] ? followFeatureOn<true>(m, corner, blockB, feature, kind)
                                     : followFeatureOn<false>(m, corner, blockB, feature, kind);
}

BlockPoint cornerPoint(const Model& m, int corner) {
  BlockPoint p;
  if (const int g = m.vertices.gridpoint[corner]; g >= 0) {
    p.gridpoint[0] = g;
    p.weight[0] = 1.0;
  }
  return p;
}

BlockPoint featurePoint(const Model& m, const FeatureHit& hit, Vec2 where) {
  const Vertices& vx = m.vertices;
  BlockPoint p;
  const int g = vx.gridpoint[hit.feature];
  if (g < 0) return p;
  if (hit.kind == FeatureKind::Corner) {
    p.gridpoint[0] = g;
    p.weight[0] = 1.0;
    return p;
  }
  const VertexGeometry& e = vx.geometry[hit.feature];
  const double along = std::clamp(dot(where - e.position, e.edgeDirection) / e.edgeLength, 0.0, 1.0);
  p.gridpoint[0] = g;
  p.weight[0] = 1.0 - along;
  p.gridpoint[1] = vx.gridpoint[vx.next[hit.feature]];
  p.weight[1] = along;
  return p;
}

double contactLength(const Model& m, int corner, const FeatureHit& hit, bool onOutline) {
  const Vertices& vx = m.vertices;
  const Vec2 here = vx.geometry[corner].position;
  // The edges of B the corner may share a face with: the contacted edge, or both edges of the
  // contacted corner.
  const int edgesOfB[2] = {hit.kind == FeatureKind::Edge ? hit.feature : vx.prev[hit.feature], hit.feature};
  const int candidates = hit.kind == FeatureKind::Edge ? 1 : 2;
  double length = 0.0;
  const int before = vx.prev[corner], after = vx.next[corner];
  for (const int other : {before, after}) {
    const Vec2 far = vx.geometry[other].position;
    const double edgeLength = vx.geometry[other == after ? corner : before].edgeLength;
    double share = 0.0;
    for (int k = 0; k < candidates; ++k) {
      const int e = edgesOfB[k];
      const Vec2 origin = vx.geometry[e].position, along = vx.geometry[e].edgeDirection, out = outward(along);
      const double sHere = dot(here - origin, along), sFar = dot(far - origin, along);
      // Faces in contact run against each other (both outlines are counter-clockwise): an edge
      // of A that runs with B's edge, or at more than 60 degrees against it, faces no part of
      // it. (Without this, a side of A in line with a side of B, as at the corners of a stack,
      // would count the overlap of the two by the joint's closure; a nearly perpendicular edge,
      // a projection whose clipping is round-off.)
      const Vec2 alongA = vx.geometry[other == after ? corner : before].edgeDirection;
      if (dot(alongA, along) > -0.5) continue;
      const double perUnitAlong = 1.0 / (sFar - sHere);
      // A's edge from `here` to `far`, clipped to B's edge; it shares the face when its clipped
      // far end is within the contact tolerance of B's edge line.
      const double c0 = std::clamp(sHere, 0.0, vx.geometry[e].edgeLength), c1 = std::clamp(sFar, 0.0, vx.geometry[e].edgeLength);
      const double gapHere = dot(here - origin, out), gapFar = dot(far - origin, out);
      const double gapAtClippedFar = gapHere + (gapFar - gapHere) * (c1 - sHere) * perUnitAlong;
      // The share fades out as the far end lifts off B's edge line from half the contact
      // tolerance to the whole, so that the length is continuous in the geometry: a block
      // tilting on a face goes from its face's share to a corner's rounding length gradually,
      // not in one step. Within half the tolerance (a face pulled apart evenly, a joint closed
      // or opened by its load) the whole share stands.
      const double fade = std::clamp(2.0 - 2.0 * gapAtClippedFar / m.contactTolerance, 0.0, 1.0);
      if (fade == 0.0 || gapAtClippedFar < -m.contactTolerance) continue;
      share = std::max(share, 0.5 * std::abs((c1 - c0) * perUnitAlong) * edgeLength * fade);
    }
    length += share;
  }
  // A corner touching alone shares no face: it gets the rounding length, so that its stiffness
  // never vanishes. On a deformable block's outline a shared face can be shorter than d (zones
  // finer than the rounding), and there the share is the partition of the joint and stands.
  return onOutline && length > 0.0 ? length : std::max(length, m.roundingLength);
}

}  // namespace vdec
