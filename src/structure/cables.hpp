#pragma once
// Grouted cables (NUREG/CR-5429 1.4.4.3, Fig. 1.4-14): axial elements along a straight cable, its
// nodes moving along it with masses lumped at them, each bonded to the rock by the grout, a
// spring-slider per unit length (1.4-42 to 1.4-44); the elements yield in tension and compression.
#include <string>

#include "core/model.hpp"
#include "motion/motion_totals.hpp"

namespace vdec {

struct CableStepTotals {
  double strainEnergy = 0.0;    // of the elements
  double plasticWork = 0.0;     // the elements' yield over the step
};

// The elements' and the grout's forces from the motion of the step before (dt; 0 at the first).
CableStepTotals computeCableForces(Model& model, double dt);
MotionStepTotals integrateCableNodes(Model& model, double dt, double alpha, double localDamping);
// Gershgorin's bound on the nodes' axial chain with the grout, and the limits of the rock it holds.
double cableTimeStep(const Model& model, double frac, double zoneFraction);
// Puts cable `index` into the model: each node beyond the free length is grouted to the rock at
// its point (none outside the rock: an ungrouted length), the node placed where that point is now;
// a head plate holds the first node to the rock there; the free length's elements carry the
// pretension. Returns the elastic energy the pretension puts in (J/m). A head on no rock is a
// SceneError naming `when` and the cable.
double installCable(Model& model, int index, const std::string& when);
// Takes cable `index` out (a phase's free): its nodes stop, its grout lets go. Returns the kinetic
// and strain energy it took with it (J/m).
double removeCable(Model& model, int index);

}  // namespace vdec
