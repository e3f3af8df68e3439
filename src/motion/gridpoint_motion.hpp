#pragma once
// Law of motion for the gridpoints of deformable blocks (NUREG/CR-5429 1.4-117, with
// inertial and gravitational masses apart for density scaling, 1.3-32 to 1.3-34) and mass-
// proportional damping (1.3-21).
#include "core/model.hpp"

namespace vdec {

struct GridpointStepTotals {
  double kineticEnergy = 0.0;        // time-centred, as for blocks
  double externalWork = 0.0;         // gravity, boundary tractions and driven gridpoints
  double dampingDissipation = 0.0;   // alpha m vbar^2 dt
  double largestUnbalancedForce = 0.0;
  double sumForceMagnitude = 0.0;    // of the zone forces on each free gridpoint, for the ratio
  int freeGridpoints = 0;
  double largestDisplacement = 0.0;
  double dampingPower = 0.0;         // sum m vbar^2 (times alpha: the power mass damping absorbs; 1.3-23)
  double kineticRate = 0.0;          // sum m vbar (v1 - v0) / dt, the rate of change of kinetic energy
};

// Boundary tractions of the step: each loaded edge's stress times its current outward normal
// and length, half to each end (Gridpoints::appliedForce).
void applyEdgeTractions(Model& model);

// Driven components with a time history take their velocity for the coming half step.
void applyDrivenVelocities(Model& model, double dt);

// Advances every gridpoint one step: gathers its zone forces in a fixed order, adds gravity and
// tractions, integrates free components by 1.3-21 and holds driven ones at their velocity.
GridpointStepTotals integrateGridpoints(Model& model, double dt, double massDamping);

}  // namespace vdec
