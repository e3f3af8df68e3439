#pragma once
// A component model as the cycle sees it: the stages it runs each step, and the largest stable step
// it allows. A step first runs every component's force stages, then every component's motion
// stages, each in the order of the components. The cycle knows the components only through this; a scene gets only the
// components it needs, and a component only the stages it needs (sceneComponents). A stage is one
// indirect call per step; inside it, loops run over plain arrays.
#include <functional>
#include <string>
#include <vector>

#include "contact/contact_detection.hpp"
#include "contact/contact_forces.hpp"
#include "core/model.hpp"
#include "motion/motion_totals.hpp"
#include "run/energy_ledger.hpp"
#include "run/run_settings.hpp"

namespace vdec {

// The sums the stages of one step contribute to; the cycle closes them into the energy ledger and
// the monitors at the step's end and starts the next step's from zero.
struct StepTotals : MotionStepTotals {
  double strainEnergy = 0.0;
};

// Forces: a stage that sums this step's forces from the positions at its start. Motion: one that
// integrates the motion from them.
enum class StepPart { Forces, Motion };

struct Stage {
  std::string name;
  std::function<void()> step;
  StepPart part = StepPart::Forces;
  double seconds = 0.0;
  bool listed = true;  // false for the step's own bookkeeping, which is no model stage
};

// What the stages of a component may use besides the model: the run's settings and clock, this
// step's sums and the energy ledger. References into the cycle, valid while it lives.
struct RunContext {
  Model& model;
  const RunSettings& settings;
  const double& dt;
  const double& massDamping;  // alpha in use (1/s), adaptive or given
  StepTotals& step;
  EnergyLedger& energy;
  ContactDetection& detection;
  double& motionClock;                     // running sum of the steps' largest displacements
  const double& largestStepDisplacement;   // of the step before
  // Stops the run when a joint's stiffness has grown past what the step allows.
  std::function<void(const ContactStepTotals&)> checkStiffnessGrowth;
};

struct Component {
  std::string name;  // as in qa/traceability/requirements.toml's component table
  std::vector<Stage> stages;
  // The largest stable step the component allows (s), before the damping reductions; empty when
  // it sets none of its own.
  std::function<double()> stepLimit;
};

// The components the model needs, in order: contacts, rigid-block-motion, deformable-blocks,
// boundaries, free-field, fracture-flow.
std::vector<Component> sceneComponents(RunContext& run);

}  // namespace vdec
