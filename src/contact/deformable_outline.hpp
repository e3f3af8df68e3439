#pragma once
// The contact vertices of deformable blocks (1.3.3.3, 1.3.3.4.2): the gridpoints of each block's
// outer outline, in counter-clockwise order. A gridpoint where the outline turns by a real
// corner is rounded like a rigid block's corner; the others (the outline runs on nearly
// straight, or turns inwards) are point corners.
#include "core/model.hpp"

namespace vdec {

// The interior angle (degrees) below which an outline gridpoint is a rounded corner. A
// rounded corner's arc radius is d tan(alpha / 2): beyond this the arc grows past 3.7 d and
// deformation could turn it reflex, where no rounding exists.
inline constexpr double kRoundedCornerMaxAngleDegrees = 160.0;

// Rebuilds model.vertices so that each deformable block has its outer outline as its vertices
// (block order and each rigid block's vertices unchanged), and sizes the gridpoints' contact
// forces. Holes in a deformable block carry no contacts. Throws GeometryError naming the block
// when the outline touches itself at a gridpoint, when the block is in several pieces, or when
// an outline segment is too short for the rounding of the corners at its ends.
void attachDeformableOutlines(Model& model);

// World geometry of a deformable block's vertices from its gridpoints' present positions.
void placeOutlineVertices(Model& model, int block);

}  // namespace vdec
