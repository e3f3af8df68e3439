#pragma once
// The boundary-element far field coupled to the blocks (NUREG/CR-5429 1.4.5, 1.4-103, 1.4-104):
// each step the region's forces on the interface's points, f = f0 - K u from the nodes'
// displacements since installation; its stiffness in the gridpoints' stable step.
#include "core/model.hpp"

namespace vdec {

// Puts the region in place as the model stands: its nodes where their points are now, holding the
// stress the zones beside its edges have now, or on a rigid block's edge the in-situ stress
// (sigma n over each edge, half to each end).
void holdPresentStress(Model& model);
// The nodes' displacements since installation: each the mean of its points' (gridpoints, rigid blocks' vertices).
Vec2 boundaryElementNodeDisplacement(const Model& model, int node);
// f = f0 - K u onto the gridpoints' traction forces and the rigid blocks' boundary forces and
// moments (a node's shared equally by its points); keeps each node's force for output.
void applyBoundaryElementForces(Model& model);
// The gridpoints' step with the region's stiffness added (Gershgorin's row sums of K), and the
// rigid blocks' under it.
double boundaryElementTimeStep(const Model& model, double frac, double zoneFraction);

}  // namespace vdec
