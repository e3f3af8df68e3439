#pragma once
// Boundary conditions of deformable blocks put on a model and taken off it again: the scene's
// [[boundary]] tables before the run, and a phase's at its start (docs/user-manual/
// scene-format.md#boundary and #phase).
#include <string>

#include "core/model.hpp"

namespace vdec {

// Appends `condition` to model.boundaryConditions and applies it: its gridpoints driven (fixed
// components at rest, velocity components at their velocity), its edges loaded. Its histories
// run from `timeOrigin`. Returns the kinetic energy the new drives took from the gridpoints
// (negative when they gave some), which the energy account must hear of.
double addBoundaryCondition(Model& model, BoundaryCondition condition, double timeOrigin);

// Takes the active condition named `name` off (the phase builder has checked that there is one):
// its loaded edges, driven velocities, dashpots and free-field columns go, and its gridpoints keep
// only the drives of the conditions still active, moving on freely from their present velocity
// where none is left. Returns the kinetic energy of the components set free, which the energy
// account must be given (driven components carry none in it).
double freeBoundaryCondition(Model& model, const std::string& name);

}  // namespace vdec
