#pragma once
// The outline of a simply-deformable block (docs/models/simply-deformable.md) as the contacts see
// it: its corners placed from its rigid motion and uniform strain, the body point and velocity
// of a contact point, and a contact force's share in its strains. The strain modes themselves
// (mass, stress, law of motion) are motion/strain_modes.hpp's.
#include "core/model.hpp"

namespace vdec {

// For a contact's hot loop these take k, the block's index among the simply-deformable blocks
// (StrainModes::of[block]).
// The body point X of a point at r = x - c from the centroid: X = (I + E)^-1 R^T r, with the
// rotation and strain of the block as last placed (placeStrainedVertices).
Vec2 bodyPoint(const StrainModes& modes, int k, Vec2 r);
// R dE/dt X, the velocity the strain rate gives body point X.
Vec2 strainVelocityAt(const StrainModes& modes, int k, Vec2 X);
// Adds a force f acting at body point X to the block's generalised strain force.
void addStrainForceAt(StrainModes& modes, int k, Vec2 X, Vec2 f);

// The velocity the strain rate gives the point at r = x - c from block b's centroid, R dE/dt X
// (besides v_c + omega k x r).
Vec2 strainVelocity(const Model& model, int block, Vec2 r);

// World positions, arc centres, edge directions and lengths of block b's vertices from its
// centroid, rotation and strain; keeps the rotation's cosine and sine and (I + E)^-1 for the
// contacts of the next step.
void placeStrainedVertices(Model& model, int block);

}  // namespace vdec
