#pragma once
// Viscous (absorbing) boundaries of deformable blocks, Lysmer and Kuhlemeyer (1969), 1.3-35 and
// 1.3-36: normal and shear dashpots on outline edges. docs/models/boundaries.md.
#include "core/model.hpp"

namespace vdec {

// Adds to gridpoints.dashpotForce, for each viscous edge, the tractions -rho C_p v_n and
// -rho C_s v_s of its two end gridpoints' velocities (those of the half step just ended), each
// over half the edge's present length.
void applyViscousBoundaries(Model& model);

}  // namespace vdec
