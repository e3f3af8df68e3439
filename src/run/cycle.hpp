#pragma once
// The time loop: one step is a fixed sequence of named stages chosen once from the scene.
// A stage is one indirect call per step; inside it, loops run over plain arrays.
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "contact/contact_detection.hpp"
#include "contact/contact_forces.hpp"
#include "run/energy_ledger.hpp"
#include "run/history.hpp"
#include "core/model.hpp"
#include "motion/motion_totals.hpp"
#include "zone/excavation.hpp"

namespace vdec {

struct StopCriteria {
  long long cycles = -1;  // < 0: not set
  double time = -1.0;
  double ratio = -1.0;
};

// A joint material's strength changed at the start of a phase (Coulomb laws only).
struct JointStrengthChange {
  int material = -1;
  std::optional<double> tanFriction, cohesion, tension;
};

// A rigid block's degrees of freedom and loads changed at the start of a phase.
struct RigidBlockChange {
  int block = -1;
  std::uint8_t fix = 0;             // DriveX / DriveY / DriveRotation bits driven from now on
  std::uint8_t free = 0;            // bits released, moving on from their present velocity
  Vec2 velocity;                    // of the components in `fix` (zero: held still)
  double angularVelocity = 0.0;
  std::optional<Vec2> force;        // replaces the applied force
  std::optional<double> moment;     // replaces the applied moment
};

// What a phase changes before its first step. Unset members keep the state of the phase before.
struct PhaseChanges {
  std::optional<Vec2> gravity;
  std::vector<JointStrengthChange> joints;
  std::optional<double> massDamping;     // switches adaptive damping off
  std::optional<bool> adaptiveDamping;
  std::vector<RigidBlockChange> blocks;
  std::vector<std::pair<int, MohrCoulombProperties>> blockStrengths;  // block material -> its new strength
  std::vector<ExcavationRegion> excavations;     // zones removed first, in order
  std::vector<std::string> freeBoundaries;       // names of active boundary conditions taken off
  std::vector<BoundaryCondition> boundaries;      // then applied, their histories from the phase's start
  bool resetDisplacements = false;       // displacement histories and outputs measured from here
  bool resetVelocities = false;
};

struct Phase {
  std::string name;
  StopCriteria stop;                 // counted from the phase's start
  bool requireEquilibrium = false;   // ending on cycles or time is then an error
  PhaseChanges changes;
};

struct PhaseReport {
  std::string name;
  std::string stopReason;
  long long startCycle = 0, cycles = 0;
  double startTime = 0.0, time = 0.0;
  double unbalancedRatio = 0.0;
  double wallSeconds = 0.0;
};

template <class A>
void visitState(A& a, PhaseReport& p) {
  a(p.name), a(p.stopReason), a(p.startCycle), a(p.cycles), a(p.startTime), a(p.time), a(p.unbalancedRatio);
  a(p.wallSeconds);
}

struct RunSettings {
  double frac = 0.1;          // FRAC of 1.3-28
  // The zone step as a fraction of 1.3-25's estimate of the critical one (the estimate already
  // has a margin); for stability studies.
  double zoneFraction = 1.0;
  double massDamping = 0.0;   // alpha of 1.3-21, 1/s
  double stiffnessDamping = 0.0;  // beta of 1.3-22 on the joints' springs, s (Rayleigh with alpha)
  bool adaptiveDamping = false;  // alpha by the servo of 1.3-23 instead
  double localDamping = 0.0;     // alpha_L of local damping (motion_totals.hpp), instead of mass damping
  bool densityScaling = false;   // gridpoint inertial masses scaled to one step (1.3-32 to 1.3-34)
  bool staticSolve = false;      // start from the direct solution of the elastic zones (zone/direct_solve)
  StopCriteria stop;
  // Run in order; empty: one stage of the run, to `stop`.
  std::vector<Phase> phases;
  bool profile = false;
  bool progress = false;
  // Snapshots: the caller's writer is called at the start, every `snapshotEvery` cycles and at
  // the end (0: never).
  long long snapshotEvery = 0;
  std::function<void(const Model&)> snapshot;
};

struct StageTiming {
  std::string name;
  double seconds = 0.0;
};

struct RunReport {
  long long cycles = 0;
  double time = 0.0;
  double dt = 0.0;
  std::string stopReason;
  std::vector<std::string> stages;
  std::vector<StageTiming> profile;
  std::vector<HistorySeries> histories;
  EnergyReport energy;
  std::vector<PhaseReport> phases;  // one per [[phase]] begun
  Monitors lastMonitors;
  int detectionScans = 0;
  double staticSolveSeconds = -1.0;  // < 0: no direct solve
  // The direct solve's last right-hand side over the force scale: near round-off when it
  // converged; larger when joints slipped or opened during it (the cycles then finish the job).
  double staticSolveResidual = -1.0;
  double stiffnessDampingStepFactor = 1.0;  // sqrt(1 + xi^2) - xi when stiffness damping is on
  double wallSeconds = 0.0;
  // Set when a numerical error stopped the run; the report then holds the state up to it.
  std::string error;
  int errorCode = 0;
  // The signal that interrupted the run (stopReason "interrupted", errorCode Interrupted), else 0.
  int interruptSignal = 0;
};

class Cycle {
 public:
  Cycle(Model& model, RunSettings settings, std::vector<HistorySpec> histories);
  // Runs to a stop criterion. Numerical trouble (instability, overlap) ends the run early with
  // report.error and report.errorCode set, so that the histories up to it can still be written.
  RunReport run();
  double timeStep() const { return dt_; }
  // Continue a saved run: the phases before `firstPhase` are done and the state (visitState)
  // has been loaded; run() then starts at that phase, without the initial history sample.
  void resumeAt(int firstPhase) { firstPhase_ = firstPhase; }
  // After each phase, before the next begins (the state is then whole): the caller may save it.
  std::function<void(const std::string& phase, const RunReport& soFar)> afterPhase;
  // Everything of the run that carries from step to step, besides the model (core/state_archive.hpp).
  template <class A>
  void visitState(A& a) {
    a(dt_), a(contactStepFraction_), a(stepStiffness_), a(largestStepDisplacement_), a(motionClock_);
    a(meanContactForce_), a(largestUnbalanced_), a(step_), a(reversing_), a(alpha_), a(servoPower_), a(servoRate_);
    a(staticSolveSeconds_), a(staticSolveResidual_), a(energy_), a(monitors_), a(histories_);
    a(settings_.adaptiveDamping), a(settings_.massDamping), a(donePhases_), a(densityStep_), a(historySpecs_),
      a(stiffnessDampingStepFactor_);
    detection_.visitState(a);
  }
  double massDamping() const { return alpha_; }

 private:
  struct Stage {
    std::string name;
    std::function<void()> step;
    double seconds = 0.0;
    bool listed = true;  // false for the step's own bookkeeping, which is no model stage
  };
  // Sums the stages of one step contribute to, closed by finishStep.
  struct StepTotals : MotionStepTotals {
    double strainEnergy = 0.0;
  };
  void buildStages();
  void finishStep();
  void adaptDamping(const StepTotals& totals);
  void checkEnergy();
  void checkReversingMotion(const StepTotals& totals);
  void checkStiffnessGrowth(const ContactStepTotals& totals) const;
  void recordHistories(bool initial);
  bool stopReached(const StopCriteria& s, long long startCycle, double startTime, std::string& reason) const;
  void stepUntil(const StopCriteria& stop, std::string& reason);
  void beginPhase(const PhaseChanges& changes);
  void checkDamping(double alpha, const std::string& where) const;
  // A step formed without damping, reduced for local and stiffness-proportional damping.
  double dampedStep(double step) const;
  void excavate(const ExcavationRegion& region);
  void changeRigidBlocks(const std::vector<RigidBlockChange>& changes);
  void closePhase(PhaseReport& done, std::chrono::steady_clock::time_point started) const;
  void printProgress(bool final) const;

  Model& model_;
  RunSettings settings_;
  std::vector<HistorySpec> historySpecs_;
  std::vector<HistorySeries> histories_;
  std::vector<Stage> stages_;
  ContactDetection detection_;
  double dt_ = 0.0;
  double contactStepFraction_ = 0.0;
  double stepStiffness_ = 0.0;  // the largest joint stiffness (Pa/m) the rigid-block step was set from
  double largestStepDisplacement_ = 0.0;
  double motionClock_ = 0.0;  // running sum of largestStepDisplacement_, for skipping open contacts
  double meanContactForce_ = 0.0;
  double largestUnbalanced_ = 0.0;
  StepTotals step_;
  bool hasZones_ = false, hasRigidBlocks_ = false, hasContacts_ = false;
  // The window over which motion reversing every step is watched (checkReversingMotion).
  struct ReversingWindow {
    bool open = false;
    double startEnergy = 0.0;  // kinetic energy when it opened
    double damping = 0.0;      // the exponent by which damping would reduce an ordinary mode's energy since
    long long steps = 0;
    int pause = 0;  // steps since the motion last reversed
  } reversing_;
  double alpha_ = 0.0;                       // mass damping in use, 1/s
  double densityStep_ = 0.0;                 // the step density scaling formed the masses for
  double stiffnessDampingStepFactor_ = 1.0;
  double servoPower_ = 0.0, servoRate_ = 0.0;
  double staticSolveSeconds_ = -1.0;
  double staticSolveResidual_ = -1.0;
  EnergyLedger energy_;
  std::chrono::steady_clock::time_point phaseStart_;
  int firstPhase_ = 0;
  std::vector<PhaseReport> donePhases_;  // restored with the state: the phases before firstPhase_
  Monitors monitors_;
};

}  // namespace vdec
