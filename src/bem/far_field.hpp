#pragma once
// The boundary-element far field coupled to the zones (NUREG/CR-5429 1.4.5, 1.4-103, 1.4-104):
// each step the region's forces on the interface's gridpoints, f = f0 - K u from the nodes'
// displacements since installation; its stiffness in the gridpoints' stable step.
#include "core/model.hpp"

namespace vdec {

// Puts the region in place as the model stands: its nodes where their gridpoints are now, holding
// the stress the zones beside its edges have now (sigma n over each edge, half to each end).
void holdPresentStress(Model& model);
// The nodes' displacements since installation: each the mean of its gridpoints'.
Vec2 boundaryElementNodeDisplacement(const Model& model, int node);
// f = f0 - K u onto the gridpoints' traction forces (a node's shared equally by its gridpoints);
// keeps each node's force for output.
void applyBoundaryElementForces(Model& model);
// The gridpoints' step with the region's stiffness added (Gershgorin's row sums of K).
double boundaryElementTimeStep(const Model& model, double zoneFraction);

}  // namespace vdec
