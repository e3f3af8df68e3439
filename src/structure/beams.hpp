#pragma once
// Beams (NUREG/CR-5429 1.2.6, 1.4.4): co-rotational 2D frame elements between nodes of three
// degrees of freedom, masses lumped at the nodes, integrated by the same central differences as
// the blocks; ties (normal and shear springs, Coulomb slip, tensile strength) to the rock.
#include <string>

#include "core/model.hpp"
#include "motion/motion_totals.hpp"

namespace vdec {

struct BeamStepTotals {
  double strainEnergy = 0.0;  // of the elements, at the positions the step starts from
};

// The elements' forces on their nodes and the ties' forces on nodes and rock, from the positions
// at the step's start; dt is the step the velocities moved them over (0 before the first motion).
BeamStepTotals computeBeamForces(Model& model, double dt);
// Central differences for the nodes (as integrateRigidBlocks: mass damping alpha or local damping).
MotionStepTotals integrateBeamNodes(Model& model, double dt, double alpha, double localDamping);
// The largest stable step of the nodes (Gershgorin's bound on the mass-scaled stiffness of the
// elements and ties) and of the rock the ties hold (frac for rigid blocks, as 1.3-28).
double beamTimeStep(const Model& model, double frac, double zoneFraction);

// Puts beam `index` into the model (at the run's start, or a phase's): a tied beam's nodes are
// placed on the points of the rock that hold their input positions (in the configuration
// displacements are measured from), as the rock is now, and tied there; the elements are
// stress-free as placed. A node on no block within the rounding length is a SceneError naming
// `when` and the beam.
void installBeam(Model& model, int index, const std::string& when);
// Takes beam `index` out of the model (a phase's free): its ties let go, its nodes stop. Returns
// the kinetic and strain energy it took with it (J/m).
double removeBeam(Model& model, int index);

}  // namespace vdec
