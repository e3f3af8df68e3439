#pragma once
// Free-field boundaries (1.3.6.3, 1.3-37 to 1.3-43): a one-dimensional column beside each vertical
// lateral boundary, run in step with the model, coupled to the side by the column's stress and
// dashpots on the relative velocity. docs/models/boundaries.md#derivation.
#include "core/model.hpp"

namespace vdec {

// Keeps, as constant loads on the column's side gridpoints, the forces that held them in the
// model's present state and that the loads now in force no longer give: minus the sum of the
// zones' and joints' forces of the step just taken, gravity, and the tractions of the loaded edges
// in force (so that a support or load the phase takes off is replaced, and one it adds, such as
// the base's weight, is not counted twice). Components still driven are left to their support.
// Called once the phase's boundary changes are all made; before the first step there is no state
// to hold.
void keepStaticReactions(const Model& model, FreeFieldColumn& column);

// One step of every column in force: its element stresses from the node velocities of the half
// step just ended, the side's loads (the column's stress on the edges, dashpots on the velocity
// relative to the column's, the kept reactions), then the column's own motion to t + dt/2 under
// the same mass (alpha) and stiffness-proportional (beta) damping as the model.
void stepFreeFields(Model& model, double dt, double alpha, double beta);

// The largest stable step of the columns: a lumped-mass chain's highest frequency is at most
// sqrt(max_j (sum_k |K_jk|) / m_j) (Gershgorin), which for a uniform column gives dt = h / C_p;
// less at the base, whose dashpot acts on the lagged velocity (viscous_boundary.hpp).
double freeFieldTimeStep(const Model& model);

}  // namespace vdec
