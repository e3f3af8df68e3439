#pragma once
// The thermal solution (NUREG/CR-5429 1.4.3): the conductance of the zones, the explicit scheme's
// stable step, and the theta scheme that advances the temperatures on their own clock.
#include <vector>

#include "core/model.hpp"

namespace vdec {

// K of the zones (A B^T k B per triangle) and the lumped capacities, on the scene's positions.
void assembleHeat(Model& model);
// 2 / max_i(sum_j |K_ij| + h_i) / C_i over the free nodes: Gershgorin's bound on the explicit
// scheme's limit 2 / lambda_max(C^-1 (K + H)); infinity when no free node conducts.
double heatStableStep(const Model& model);
// Advances the temperatures by `duration` seconds of thermal time in steps of heat.step (the last
// one shorter if it does not divide), keeping the heat balance.
void advanceHeat(Model& model, double duration);

// The thermal stress of the temperature change since it was last applied (1.4-17): each zone's
// mean temperature change dT adds -K beta dT (beta = 3 alpha) to sxx, syy and szz, as the
// restrained isotropic expansion; the mechanical cycles then find the new equilibrium.
void applyThermalStress(Model& model);

// The zone edges along a segment: each as zone * 3 + the corner it starts at, with the share of
// its zone's flux in the flow through it (1 / the number of zones on the edge, so that an edge
// between two zones takes the mean of their fluxes).
struct HeatLine {
  std::vector<int> edge;
  std::vector<double> share;
};
HeatLine heatLine(const Model& model, Vec2 from, Vec2 to);
// The heat flow (W per metre of thickness) through the line's edges towards the right of the
// direction from `from` to `to`: the zones' conducted flux -k grad T on each edge, times its length.
double heatFlowAcross(const Model& model, const HeatLine& line, Vec2 from, Vec2 to);

}  // namespace vdec
