#pragma once
// The time loop: one step is the stages of the scene's components (run/component.hpp), their
// force stages and then their motion stages, between the step's own bookkeeping; the time step
// is the smallest of the components' limits.
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "contact/contact_detection.hpp"
#include "contact/contact_forces.hpp"
#include "core/model.hpp"
#include "run/component.hpp"
#include "run/energy_ledger.hpp"
#include "run/history.hpp"
#include "run/run_settings.hpp"
#include "zone/excavation.hpp"

namespace vdec {

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
  int staticSolvePasses = 0;   // linear solves of the direct solve, over all its uses
  int staticSolveFactorisations = 0;
  int staticSolveUnknowns = 0;
  int staticSolvePlasticIterations = 0;  // iterations of the plastic zones' equilibrium in the direct solves
  bool staticSolvePlasticFailed = false;  // a direct solve found no equilibrium of its plastic zones
  double stiffnessDampingStepFactor = 1.0;  // sqrt(1 + xi^2) - xi when stiffness damping is on
  // Each component's largest stable step (s) at the end of the run, before the damping reductions:
  // the step is the smallest of them times those reductions.
  std::vector<std::pair<std::string, double>> stepLimits;
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
  // The components' stages hold references into the cycle (run_).
  Cycle(const Cycle&) = delete;
  Cycle& operator=(const Cycle&) = delete;
  // Runs to a stop criterion. Numerical trouble (instability, overlap) ends the run early with
  // report.error and report.errorCode set, so that the histories up to it can still be written.
  RunReport run();
  double timeStep() const { return dt_; }
  // The stages of a step as the scene needs them, in order (the step's own bookkeeping left out).
  std::vector<std::string> stageNames() const;
  // Each component's largest stable step (s) on the present state, before the damping reductions.
  std::vector<std::pair<std::string, double>> stepLimits() const;
  // The stop of the next run() of a scene without phases, counted from where that run starts: a
  // caller that runs on in windows (the benchmarks) sets each window's length.
  void setStop(const StopCriteria& stop) { settings_.stop = stop; }
  // Continue a saved run: the phases before `firstPhase` are done and the state (visitState)
  // has been loaded; run() then starts at that phase, without the initial history sample.
  // The stages are formed again from the loaded model: the phases before may have added or freed
  // the boundary conditions that need them.
  void resumeAt(int firstPhase);
  // After each phase, before the next begins (the state is then whole): the caller may save it.
  std::function<void(const std::string& phase, const RunReport& soFar)> afterPhase;
  // Everything of the run that carries from step to step, besides the model (core/state_archive.hpp).
  template <class A>
  void visitState(A& a) {
    a(dt_), a(contactStepFraction_), a(stepStiffness_), a(largestStepDisplacement_), a(motionClock_);
    a(meanContactForce_), a(largestUnbalanced_), a(step_), a(reversing_), a(alpha_), a(servoPower_), a(servoRate_);
    a(staticSolveSeconds_), a(staticSolveResidual_), a(staticSolvePasses_), a(staticSolveFactorisations_), a(staticSolveUnknowns_), a(staticSolvePlasticIterations_), a(staticSolvePlasticFailed_), a(energy_), a(monitors_), a(histories_);
    a(settings_.adaptiveDamping), a(settings_.massDamping), a(donePhases_), a(densityStep_), a(historySpecs_),
      a(stiffnessDampingStepFactor_), a(undampedStep_), a(settings_.localDamping);
    detection_.visitState(a);
  }
  double massDamping() const { return alpha_; }

 private:
  void buildStages();
  void finishStep();
  void adaptDamping(const StepTotals& totals);
  void checkEnergy();
  void checkReversingMotion(const StepTotals& totals);
  void checkStiffnessGrowth(const ContactStepTotals& totals) const;
  void recordHistories(bool initial);
  // Acceleration histories start again from the velocities a phase's start left (resets,
  // excavations, a direct solve change them without a step's forces).
  void restartAccelerations();
  bool stopReached(const StopCriteria& s, long long startCycle, double startTime, std::string& reason) const;
  void stepUntil(const StopCriteria& stop, std::string& reason);
  void beginPhase(const PhaseChanges& changes, const std::string& phaseName);
  void checkDamping(double alpha, const std::string& where) const;
  void warnHalved(const HistorySpec& h, const HistorySeries& series) const;
  // A step formed without damping, reduced for local and stiffness-proportional damping.
  double dampedStep(double step) const;
  void formStiffnessDampingFactor();
  // The named component's limit on the step (s); infinite when it has none or is not in the scene.
  double stepLimitOf(std::string_view component) const;
  void excavate(const ExcavationRegion& region);
  void excavateRigidBlocks(const ExcavationRegion& region);
  // A phase's direct solve of the elastic zones (zone/direct_solve), with its energy account.
  void solveDirectly();
  // Advances the thermal clock, then loads the zones with the thermal stress of the change.
  void advanceThermalClock(double duration);
  double storedElasticEnergy() const;
  void changeRigidBlocks(const std::vector<RigidBlockChange>& changes);
  void closePhase(PhaseReport& done, std::chrono::steady_clock::time_point started) const;
  // The status line; `left` the wall seconds estimated to the stop (negative: none to give).
  void printProgress(bool final, double left = -1.0) const;

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
  double undampedStep_ = 0.0;  // the smallest of the components' limits, before dampedStep
  double servoPower_ = 0.0, servoRate_ = 0.0;
  double staticSolveSeconds_ = -1.0;
  double staticSolveResidual_ = -1.0;
  int staticSolvePasses_ = 0, staticSolveFactorisations_ = 0, staticSolveUnknowns_ = 0, staticSolvePlasticIterations_ = 0;
  bool staticSolvePlasticFailed_ = false;
  EnergyLedger energy_;
  std::chrono::steady_clock::time_point phaseStart_;
  int firstPhase_ = 0;
  std::vector<PhaseReport> donePhases_;  // restored with the state: the phases before firstPhase_
  Monitors monitors_;
  // What the components' stages see of the run (after the members it refers to), and the
  // components themselves.
  RunContext run_;
  std::vector<Component> components_;
};

}  // namespace vdec
