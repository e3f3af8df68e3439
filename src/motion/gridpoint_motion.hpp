#pragma once
// Law of motion for the gridpoints of deformable blocks (NUREG/CR-5429 1.4-117, with
// inertial and gravitational masses apart for density scaling, 1.3-32 to 1.3-34) and mass-
// proportional damping (1.3-21).
#include "core/model.hpp"
#include "motion/motion_totals.hpp"

namespace vdec {


// Boundary tractions of the step: each loaded edge's stress times its current outward normal
// and length, half to each end (Gridpoints::tractionForce).
void applyEdgeTractions(Model& model);

// Driven components with a time history take their velocity for the coming half step.
void applyDrivenVelocities(Model& model, double dt);

// Advances every gridpoint one step: gathers its zone forces in a fixed order, adds gravity and
// tractions, integrates free components by 1.3-21 and holds driven ones at their velocity.
MotionStepTotals integrateGridpoints(Model& model, double dt, double massDamping, double localDamping = 0.0);

}  // namespace vdec
