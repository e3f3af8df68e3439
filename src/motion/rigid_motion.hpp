#pragma once
// Law of motion for rigid blocks (NUREG/CR-5429 1.3-10 to 1.3-15) with mass-proportional
// damping (1.3-20, 1.3-21), and the rigid-block time step (1.3-28 to 1.3-30).
#include "core/model.hpp"

namespace vdec {

struct MotionStepTotals {
  double kineticEnergy = 0.0;       // time-centred: mean of the energies at t - dt/2 and t + dt/2
  double externalWork = 0.0;        // by gravity, applied loads and driven blocks over the step
  double dampingDissipation = 0.0;  // by mass damping over the step: alpha m vbar^2 dt
  double largestUnbalancedForce = 0.0;
  double largestDisplacement = 0.0; // of any vertex over the step (bounds contact detection)
  double dampingPower = 0.0;        // sum m vbar^2, for adaptive damping (1.3-23)
  double kineticRate = 0.0;         // sum m vbar (v1 - v0) / dt
};

// Advances every block by one step: free degrees of freedom by 1.3-21 (translation and
// rotation damped alike), driven ones at their prescribed velocity. Clears the force sums.
MotionStepTotals integrateRigidBlocks(Model& model, double dt, double massDamping);

// dt_b = FRAC * 2 sqrt(M_min / K_max), K_max = max(Kn, Ks) for point contacts and
// max(kn, ks) * l_typ for joints (1.3-28, 1.3-29). M_min and l_typ (the longest edge) are over
// the blocks with a free degree of freedom, or over all blocks when all are driven.
double rigidBlockTimeStep(const Model& model, double frac);

}  // namespace vdec
