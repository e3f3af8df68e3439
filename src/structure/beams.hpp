#pragma once
// Beams (NUREG/CR-5429 1.2.6, 1.4.4): co-rotational 2D frame elements between nodes of three
// degrees of freedom, masses lumped at the nodes, integrated by the same central differences as
// the blocks; ties (normal and shear springs, Coulomb slip, tensile strength) to the rock.
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

}  // namespace vdec
