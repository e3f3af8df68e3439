#pragma once
// Viscous (absorbing) boundaries of deformable blocks, Lysmer and Kuhlemeyer (1969), 1.3-35 and
// 1.3-36: normal and shear dashpots on outline edges. docs/models/boundaries.md.
#include "core/model.hpp"

namespace vdec {

// Adds to gridpoints.dashpotForce, for each viscous edge, the tractions -rho C_p v_n and
// -rho C_s v_s of its two end gridpoints' velocities (those of the half step just ended), each
// over half the edge's present length.
void applyViscousBoundaries(Model& model);

// The same dashpots and incoming wave on viscous edges of rigid blocks: each edge's traction,
// linear along it with the block's velocity v + w x r (of the half step just ended), integrated
// exactly into a force and a moment about the centroid (Simpson's rule), added to
// blocks.dashpotForce/Moment; the incoming wave's constant traction to blocks.boundaryForce/Moment.
void applyRigidViscousBoundaries(Model& model);

// The largest stable step of rigid blocks with viscous edges, times FRAC as the rigid-block step
// of 1.3-28 is: the condition of dashpotTimeStep, (w dt)^2 + 2 lambda dt < 4, with w^2 the joint
// springs' k / m of 1.3-28 and lambda = c_t / m + c_r / I, a bound on the fastest decay rate of the
// edges' dashpots on the block's coupled translation and rotation (c_t the largest eigenvalue of
// their matrix on the translation, c_r their entry on the rotation). Infinite without such edges.
double rigidDashpotTimeStep(const Model& model, double frac);

// The largest stable step of the gridpoints that dashpots act on (viscous edges and the side
// edges of free-field columns). A dashpot on the velocity of the half step before, with the
// central-difference update of a mass m, spring k and dashpot c, is stable for
// (w dt)^2 + 2 c dt / m < 4, w^2 = k / m (the characteristic roots of
// x+ = (2 - w^2 dt^2 - c dt / m) x - (1 - c dt / m) x-): dt = 4 m / (c + sqrt(c^2 + 4 k m)), the
// zone step 2 sqrt(m / k) of 1.3-25 when c = 0. k is the gridpoint's stiffness of 1.3-26, c the
// larger of its normal and shear dashpots. Infinite without dashpots.
double dashpotTimeStep(const Model& model);

}  // namespace vdec
