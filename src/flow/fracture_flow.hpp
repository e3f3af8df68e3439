#pragma once
// Fracture flow's two stages (1.2, Fig. 1.2-5; 1.4.2): the domain pressures as forces on the
// blocks' edges, and, after the motion, the flow through the knots over the mechanical step in
// fluid sub-steps within the stability limit 1.4-11.
#include <vector>

#include "core/model.hpp"

namespace vdec {

// The flow coming on: the network from the present contacts, every domain at the initial field.
void startFlow(Model& model);

// Each domain's pressure on the boundary of the blocks around it, as forces on rigid blocks and
// on the gridpoints of deformable ones (a partial edge's force shared as a uniform traction's).
void applyDomainPressures(Model& model);

// The network formed again from the contacts the motion left, then the flow over the step dt.
// Stops the run (InstabilityError) when a domain's pressure oscillates without decaying.
void stepFlow(Model& model, double dt);

// The flow rate through a knot (m^2/s, from its domain[0] side to its domain[1] side) for the
// piezometric pressure difference dp across it (1.4-7, 1.4-8; Bingham: the linear law or
// Buckingham's).
double knotFlow(const Model& model, const FlowKnot& knot, double conductance, double dp);
// Moves `volume` (m^2) through the knot from its domain[0] side to its domain[1] side: between
// the domains' contents, or in or out of the model at a mouth (the fluid account).
void passThroughKnot(FlowState& flow, const FlowKnot& knot, double volume);
// Scales the knots' flows (m^2/s, over a step h) out of each partly saturated domain so that it
// passes on at most the fluid it holds.
void limitDrainage(FlowState& flow, double h);
// Sets the content a drained domain has left below zero by round-off to zero (the account's `created`).
void emptied(FlowState& flow, FlowDomain& domain);
// Its conductance, flow over pressure difference for a Newtonian fluid (m^2/(Pa s)).
double knotConductance(const Model& model, const FlowKnot& knot);

// 1.4-11: the largest stable fluid step (s) of the network with the knots' conductances.
double fluidTimeStep(const Model& model, const std::vector<double>& conductance);

// The largest mechanical step (s) the fluid's stiffness allows: a domain's pressure rises by
// K_w dA / A when the blocks around it close it, a spring on their motion. Rigid blocks: FRAC
// times 1.3-28 with it; gridpoints: half the critical step of it alone.
double fluidMechanicalTimeStep(const Model& model, double frac);

// The fluid balance now: inflow - outflow + created - removed - (content - initial) (m^2).
double flowImbalance(const Model& model);
double flowContent(const Model& model);

}  // namespace vdec
