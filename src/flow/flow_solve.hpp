#pragma once
// The domain pressures by a sparse linear solve over the network (Eigen's LDLT), instead of the
// explicit sub-steps: backward Euler over the step (implicit; unconditionally stable, one solve a
// step) or the steady flow of the present apertures (no storage); a Bingham fluid by Newton's
// method on the domains' balance, damped by a line search.
#include <vector>

#include "core/model.hpp"

namespace vdec {

// The flow over the step h from the pressures the motion left, through knots of the given
// conductances (knotConductance): implicit when `steady` is false,
// else the steady state. Moves the fluid through the knots and the held mouths as the explicit
// flow does, so that the balance stays closed.
void solveFlow(Model& model, const std::vector<double>& conductance, double h, bool steady);

}  // namespace vdec
