#pragma once
// Local reinforcement across joints (NUREG/CR-5429 1.4.4.2, 1.4-36 to 1.4-51): at each joint a
// bolt crosses, an axial spring along its active length and a shear spring across its original
// direction, each with the continuously-yielding law, the shear bound depending on the bolt's
// angle to the joint and the sense of shear, and the crushing reduction of the axial increments
// that come from the active length turning. Their forces act on the two blocks at the joint.
#include <string>

#include "core/model.hpp"

namespace vdec {

struct BoltStepTotals {
  double sumForceMagnitude = 0.0;  // of the reinforcements acting (for the unbalanced ratio)
  int acting = 0;
};

// The continuously-yielding update (1.4-48, 1.4-49) of a force F by a displacement increment d
// against the bound +-bound (the sign of d's): dF = K |d| |F_b - F| (F_b - F) / bound^2,
// integrated exactly over the increment (F approaches F_b and never passes it). An infinite bound
// is a linear spring; a bound of 0 holds no force.
double yieldingSpringForce(double force, double stiffness, double increment, double bound);

// The reinforcements' forces from the motion of the step before (dt; 0 at the first), on the rock.
BoltStepTotals computeBoltForces(Model& model, double dt);
// The reinforcements' stiffness added to the blocks' and gridpoints' own (1.4.4.7: the largest
// reinforcement stiffness counts as an interface stiffness of the blocks it joins).
double boltTimeStep(const Model& model, double frac, double zoneFraction);
// Puts bolt `index` into the model: a reinforcement at each joint its segment crosses between two
// blocks, in the geometry as it is now, stress-free. No joint crossed is a SceneError naming
// `when` and the bolt.
void installBolt(Model& model, int index, const std::string& when);
// A reinforcement whose rock on one side was excavated: no force from then on.
void breakCrossing(BoltCrossings& crossings, int crossing);
// Takes bolt `index` out (a phase's free): its reinforcements hold nothing from then on.
void removeBolt(Model& model, int index);

}  // namespace vdec
