#pragma once
// Contact geometry with rounded corners (NUREG/CR-5429 1.3.3.2, Fig. 1.3-2d).
// Block B's rounded boundary is a cyclic chain of features: corner arc j, straight part of edge
// j (from vertex j to j+1, shortened by d at both ends), corner arc j+1, ... Because the chain
// is tangent-continuous, the nearest point of it to a corner-arc centre, and so the contact
// normal, varies continuously as blocks move: corner-edge and corner-corner contacts blend.
#include "core/model.hpp"

namespace vdec {

struct FeatureHit {
  int feature = -1;                // vertex id on block B
  FeatureKind kind = FeatureKind::Edge;
  Vec2 normal;                     // unit, from B towards the corner
  Vec2 point;                      // midway between the two surfaces
  double overlap = 0.0;            // positive when interpenetrating
};

// Set-up time: neighbour ids, edge directions and lengths, and every corner's arc radius and
// centre in the block's local frame.
void computeBoundaryGeometry(Model& model);
// World positions of vertices, arc centres and edge directions from a block's rigid motion, or
// from a deformable block's gridpoints.
void placeBlockVertices(Model& model, int block);

// The feature of B nearest the corner, searching all of B's features.
FeatureHit nearestFeature(const Model& model, int corner, int blockB);
// The same, walking from a previous feature along B's boundary: what a contact does each step.
FeatureHit followFeature(const Model& model, int corner, int blockB, int feature, FeatureKind kind);

// Contact length (1.3-2, Fig. 1.3-2c): for each edge of A adjacent to the corner, half of the
// part of it that shares a face with B (the edge clipped to B's contacted edge, or to either
// edge of B's contacted corner, with its clipped far end within the contact tolerance of that
// edge's line); the rounding length d for a corner touching alone.
// onOutline: either block is deformable, where a share below d is the joint's partition and
// stands (the caller knows the blocks; looking the vertices up here would cost two cache misses
// per contact and step).
double contactLength(const Model& model, int corner, const FeatureHit& hit, bool onOutline);

// Where a contact acts on a deformable block: one gridpoint (a corner of its outline), or the
// two ends of an outline edge in proportion to a point's place along it (1.3.3.4.2). No
// gridpoint: a rigid block.
struct BlockPoint {
  int gridpoint[2] = {-1, -1};
  double weight[2] = {0.0, 0.0};
  bool onGridpoints() const { return gridpoint[0] >= 0; }
};
// The gridpoint of A's corner, if A is deformable.
BlockPoint cornerPoint(const Model& model, int corner);
// B's contacted corner's gridpoint, or its contacted edge's two gridpoints weighted by the place
// of `where` along it, if B is deformable.
BlockPoint featurePoint(const Model& model, const FeatureHit& hit, Vec2 where);

// A contact's geometry at the blocks' present positions: normal (from B towards A), the point
// where its force acts (midway between the two surfaces) and the overlap. The contact stage
// forms the same from the positions at the start of each step; outputs use this.
inline FeatureHit contactGeometry(const Model& model, const Contact& c) {
  return followFeature(model, c.corner, c.blockB, c.feature, c.featureKind);
}

}  // namespace vdec
