#pragma once
// The contact-force stage: per contact, update the geometry from the blocks' new positions,
// form the relative displacement increments of the step, apply the joint law and add the
// force and moment to both blocks.
#include <vector>

#include "core/model.hpp"

namespace vdec {

struct ContactStepTotals {
  double strainEnergy = 0.0;        // elastic energy stored in the contact springs
  // Elastic energy the joints gave up without the blocks doing work for it: springs broken in
  // tension, shear stress lost with cohesion (model 5), stress carried over a changed length.
  double jointRelease = 0.0;
  double sumForceMagnitude = 0.0;   // over closed contacts, for the unbalanced-force ratio
  double slipDissipation = 0.0;     // by slip in the step, net of dilation (J/m)
  double viscousDissipation = 0.0;  // by stiffness-proportional damping of the joints' springs (J/m)
  int closedContacts = 0;
  // The largest stress-dependent stiffness (continuously yielding law, Pa/m) of a closed contact
  // on a block that moves freely, and that contact's index (-1 when there is none).
  double largestGrownStiffness = 0.0;
  int stiffestContact = -1;
  // Blocks of corner-corner contacts whose corners passed each other in the step: each corner
  // may now rest on the other block's face, but the contact followed only one of them.
  std::vector<int> passedCorners;
};

// Throws OverlapError naming the contact when an overlap exceeds half the rounding length.
// motionClock: the running sum of each step's largest vertex displacement so far. An open
// contact whose gap is too wide to close before the clock reaches its closableAt is skipped:
// it carries no force, and its joint state, kept in displacement differences, is brought up to
// date whenever it is next evaluated (the shear displacement it records accrues only then).
// beta > 0: stiffness-proportional damping, a viscous stress beta k du/dt on the elastic
// increment of each closed contact's springs (normal and shear; shear dropped while it slips).
ContactStepTotals computeContactForces(Model& model, double dt, double motionClock, double beta = 0.0);

}  // namespace vdec
