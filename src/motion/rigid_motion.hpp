#pragma once
// Law of motion for rigid blocks (NUREG/CR-5429 1.3-10 to 1.3-15) with mass-proportional
// damping (1.3-20, 1.3-21), and the rigid-block time step (1.3-28 to 1.3-30).
#include "core/model.hpp"
#include "motion/motion_totals.hpp"

namespace vdec {

// Sets block b's driven components to their velocity scaled by its velocity history at time t
// (nothing without a history).
void setDrivenVelocities(Model& model, int b, double t);

// Advances every block by one step: free degrees of freedom by 1.3-21 (translation and
// rotation damped alike), driven ones at their prescribed velocity, from the step's force sums
// (Model::clearStepForces zeroes them at the start of the step).
MotionStepTotals integrateRigidBlocks(Model& model, double dt, double massDamping, double localDamping = 0.0);

// dt_b = FRAC * 2 sqrt(M_min / K_max), K_max = max(Kn, Ks) for point contacts and
// max(kn, ks) * l_typ for joints (1.3-28, 1.3-29). M_min and l_typ (the longest edge) are over
// the blocks with a free degree of freedom, or over all blocks when all are driven.
double rigidBlockTimeStep(const Model& model, double frac);

}  // namespace vdec
