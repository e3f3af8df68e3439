#include "run/cycle.hpp"

#include "motion/strain_modes.hpp"
#include "flow/fracture_flow.hpp"
#include "structure/beams.hpp"
#include "structure/bolts.hpp"
#include "structure/cables.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "bem/far_field.hpp"
#include "boundary/boundary_conditions.hpp"
#include "boundary/free_field.hpp"
#include "boundary/initial_wave.hpp"
#include "core/errors.hpp"
#include "core/shown.hpp"
#include "core/interrupt.hpp"
#include "motion/rigid_motion.hpp"
#include "thermal/heat.hpp"
#include "zone/cst.hpp"
#include "zone/direct_solve.hpp"

namespace vdec {

namespace {
using Clock = std::chrono::steady_clock;
// A stable explicit run cannot hold more mechanical energy than it was given, up to how the
// discrete energies are measured: for a linear mode x_n = A cos(n theta), cos(theta) = 1 - (w dt)^2/2,
// the time-centred kinetic plus strain energy exceeds the conserved energy by at most
// (1 - cos theta)/2 of it, which stays below 1 for every stable step (w dt < 2). An unstable mode
// either grows without bound or, on a frictional contact, is clipped by slip into a chatter that
// holds two to three times the energy supplied. The alarm at 1.5 lies between the two.
constexpr double kEnergyExcessLimit = 1.5;
// The largest step, as a fraction of the critical step of a grown joint stiffness, a run may
// keep; the margin covers the several contacts and modes one block can have.
constexpr double kGrownStiffnessLimit = 0.5;
// Adaptive damping: alpha moves by this factor every other step towards R = 0.5, between
// 1e-4 / dt (little damping) and 1 / dt (alpha dt / 2 = 0.5, the most 1.3-21 takes before it
// reverses velocities; past critical for every mode with w dt < 0.5).
constexpr double kAdaptiveTarget = 0.5;
constexpr double kAdaptiveGain = 1.05;
constexpr double kAdaptiveStart = 1e-4;
constexpr double kAdaptiveMax = 1.0;
// Motion reversing every step: the lag-one correlation of the velocities, L / K = cos(theta) for
// a single mode advancing theta per step, below this (theta > 120 degrees, w dt > sqrt(3)).
constexpr double kReversingCorrelation = -0.5;
// Its kinetic energy is watched until damping would have taken a mode of ordinary frequency down
// by e^-4, and over at least kReversingMinimumSteps steps; if it has kept half of it instead,
// the integration is feeding it. The step count matters under heavy damping: mass damping acts
// on the mid-step velocity, which a mode just below the critical step nearly cancels, so such a
// stable mode decays slowly, by 1 - |lambda| per step; over 200 steps only modes within about
// 0.05 % of the critical step (in FRAC) decay too slowly to tell from a fed one.
constexpr double kReversingDampingExponent = 4.0;
constexpr long long kReversingMinimumSteps = 200;
constexpr double kReversingKept = 0.5;
constexpr int kReversingPause = 20;
// Below this share of the largest energy supplied, motion is round-off, whose sign pattern means
// nothing.
constexpr double kReversingFloor = 1e-10;
}  // namespace

Cycle::Cycle(Model& model, RunSettings settings, std::vector<HistorySpec> histories)
    : model_(model), settings_(settings), historySpecs_(std::move(histories)),
      run_{model_, settings_, dt_, alpha_, step_, energy_, detection_, motionClock_, largestStepDisplacement_,
           [this](const ContactStepTotals& t) { checkStiffnessGrowth(t); }} {
  histories_.resize(historySpecs_.size());
  for (std::size_t i = 0; i < historySpecs_.size(); ++i) histories_[i].every = historySpecs_[i].every;
  const Blocks& bl = model_.blocks;
  hasZones_ = model_.zones.size() > 0;
  for (int b = 0; b < bl.size(); ++b) hasRigidBlocks_ = hasRigidBlocks_ || !bl.deformable[b];
  hasContacts_ = bl.size() > 1;
  if (hasContacts_) detection_.initialise(model_);
  if (model_.flow.on && model_.cycle == 0) startFlow(model_);
  components_ = sceneComponents(run_);
  // 1.3-30: the step is the smallest of the components' limits. The rigid blocks' (1.3-28, blocks
  // that move, through their joints) is formed first: density scaling sets the zones' to it.
  bool anyFreeRigid = false;
  for (int b = 0; b < bl.size(); ++b) anyFreeRigid = anyFreeRigid || bl.movesFreely(b);
  const double dtBlocks = stepLimitOf("rigid-block-motion");
  if (hasZones_) {
    prepareZones(model_);
    if (settings_.staticSolve) {
      if (hasRigidBlocks_)
        throw SceneError("solver.static_solve: the direct solve covers deformable blocks only; this scene has rigid blocks");
      for (const JointMaterial& j : model_.jointMaterials)
        if (j.law == JointLaw::ContinuouslyYielding)
          throw SceneError("solver.static_solve: the direct solve takes joints as linear springs, and joint material '" +
                           j.name + "' is continuously yielding (its stiffness grows with the normal stress); relax "
                           "the scene with explicit cycles instead");
      const DirectSolveReport solved = solveStaticDirect(model_);
      staticSolveSeconds_ = solved.seconds;
      staticSolveResidual_ = solved.relativeResidual;
      staticSolvePasses_ += solved.solves;
      staticSolveFactorisations_ += solved.factorisations;
      staticSolveUnknowns_ = solved.unknowns;
      staticSolvePlasticIterations_ += solved.plasticIterations;
      staticSolvePlasticFailed_ = staticSolvePlasticFailed_ || !solved.plasticConverged;
      // The solve moved the blocks without the detection's motion bounds: look again everywhere.
      if (hasContacts_) {
        std::vector<int> all(bl.size());
        for (int b = 0; b < bl.size(); ++b) all[b] = b;
        detection_.requestRescan(all);
      }
    }
    if (settings_.densityScaling) {
      // 1.3-32 to 1.3-34: inertial masses chosen so that every gridpoint is at the same stable
      // step, the unit step where blocks do not need a smaller one; weights stay exact.
      const double step = std::isfinite(dtBlocks) ? dtBlocks : 1.0;
      densityStep_ = step;
      for (int i = 0; i < model_.gridpoints.size(); ++i)
        model_.gridpoints.mass[i] = 0.25 * model_.gridpoints.stiffness[i] * step * step;
    }
  }
  dt_ = INFINITY;
  for (const Component& c : components_)
    if (c.stepLimit) dt_ = std::min(dt_, c.stepLimit());
  // Local damping lowers the critical step of central differences from w dt = 2 to
  // 2 / sqrt(1 + alpha_L) (the damping force, a fraction of the out-of-balance force, acts with
  // it whenever the motion runs against the force): the step shrinks by that factor, so that the
  // estimates of 1.3-25 and 1.3-28 keep their margins; stiffness-proportional damping by the
  // factor of formStiffnessDampingFactor.
  formStiffnessDampingFactor();
  undampedStep_ = dt_;
  dt_ = dampedStep(dt_);
  // The step as a fraction of the critical step of the stiffest joint spring on the lightest
  // free block (kinematic tests, with every block driven, have no such mode).
  contactStepFraction_ = anyFreeRigid ? settings_.frac * dt_ / dtBlocks : 0.0;
  for (const JointMaterial& j : model_.jointMaterials)
    if (j.law != JointLaw::PointContact) stepStiffness_ = std::max({stepStiffness_, j.kn, j.ks});
  alpha_ = settings_.adaptiveDamping ? kAdaptiveStart / dt_ : settings_.massDamping;
  checkDamping(alpha_, "solver.mass_damping");
  // Each phase's mass damping against the step, before the first step rather than when it starts.
  for (const Phase& phase : settings_.phases)
    if (phase.changes.massDamping) checkDamping(*phase.changes.massDamping, "phase '" + phase.name + "': mass_damping");

  // Waves in the model at the start, their velocities at -dt/2 where the scheme starts them.
  if (model_.cycle == 0) placeInitialWaves(model_, dt_);
  // Driven velocities as the run starts, f(0) times the input, which the first history sample
  // shows; every step then sets them to f(t + dt/2).
  for (int b = 0; b < bl.size(); ++b)
    if (!bl.deformable[b]) setDrivenVelocities(model_, b, model_.time);
  double initial = 0.0, scale = 0.0;
  for (int b = 0; b < bl.size(); ++b) {
    if (!bl.movesFreely(b)) continue;
    // Driven components are not counted: the kinetic energy the monitor measures is that of
    // the free ones, and a driver's work enters as external work.
    const Vec2 v = bl.velocity[b];
    const double vx = (bl.driven[b] & DriveX) ? 0.0 : v.x, vy = (bl.driven[b] & DriveY) ? 0.0 : v.y;
    const double w = (bl.driven[b] & DriveRotation) ? 0.0 : bl.angularVelocity[b];
    initial += 0.5 * (bl.mass[b] * (vx * vx + vy * vy) + bl.inertia[b] * w * w);
    scale += (bl.mass[b] * norm(model_.gravity) + norm(bl.appliedForce[b])) * model_.roundingLength;
  }
  const Gridpoints& g = model_.gridpoints;
  for (int i = 0; i < g.size(); ++i) {
    const double vx = (g.driven[i] & DriveX) ? 0.0 : g.velocity[i].x, vy = (g.driven[i] & DriveY) ? 0.0 : g.velocity[i].y;
    initial += 0.5 * g.mass[i] * (vx * vx + vy * vy);
  }
  // Stress present at the start (in situ, or joints set by the direct solve) is energy the model
  // was given.
  for (const Contact& c : model_.contacts) initial += c.springEnergy;
  const Structures& st = model_.structures;
  for (int e = 0; e < st.cableElements.size(); ++e) {
    const CableMaterial& mat = st.cableMaterials[st.cables[st.cableElements.cable[e]].material];
    const double force = st.cableElements.axialForce[e];
    initial += 0.5 * force * force * st.cableElements.restLength[e] / (mat.young * mat.area);
  }
  const Zones& zn = model_.zones;
  for (int z = 0; z < zn.size(); ++z) {
    const BlockMaterial& mat = model_.blockMaterials[zn.material[z]];
    const auto& n = zn.gridpoint[z];
    const double area = 0.5 * cross(g.position[n[1]] - g.position[n[0]], g.position[n[2]] - g.position[n[0]]);
    initial += area * elasticEnergyDensity(zn.sxx[z], zn.syy[z], zn.sxy[z], zn.szz[z], mat.bulk, mat.shear);
  }
  if (hasZones_) {
    // The energy a load does over the elastic displacement it causes: load^2 / stiffness.
    double gridScale = 0.0;
    for (int i = 0; i < g.size(); ++i) {
      const double load = g.gravityMass[i] * norm(model_.gravity);
      gridScale += load * load / std::max(g.stiffness[i], 1e-300);
    }
    for (const LoadedEdge& e : model_.loadedEdges) {
      const double length = norm(g.position[e.to] - g.position[e.from]);
      const double load = std::max({std::abs(e.sxx), std::abs(e.syy), std::abs(e.sxy)}) * length;
      gridScale += load * load / std::max(g.stiffness[e.from], 1e-300);
    }
    scale += gridScale;
  }
  energy_.open(initial, 1e-9 * std::max(scale + initial, 1e-200));
  buildStages();
}

double Cycle::dampedStep(double step) const {
  if (settings_.localDamping > 0.0) step /= std::sqrt(1.0 + settings_.localDamping);
  return step * stiffnessDampingStepFactor_;
}

void Cycle::checkDamping(double alpha, const std::string& where) const {
  // 1.3-21 multiplies v(t - dt/2) by (1 - alpha dt/2) / (1 + alpha dt/2): past alpha dt = 2 that
  // factor turns negative and every step reverses the motion instead of damping it.
  if (alpha * dt_ <= 2.0) return;
  std::ostringstream s;
  s << where << " = " << alpha << " 1/s times the time step " << dt_ << " s is " << alpha * dt_
    << ": above 2 the damping term of 1.3-21 reverses the velocities every step instead of damping them; give "
    << "at most " << 2.0 / dt_ << " 1/s (critical damping of a mode of frequency w is alpha = 2 w)";
  throw SceneError(s.str());
}

void Cycle::resumeAt(int firstPhase) {
  firstPhase_ = firstPhase;
  buildStages();
}

void Cycle::buildStages() {
  // Only the components and stages the scene needs. The step's force sums start from zero, in
  // one place. Built again when a phase changes what is needed; the profile's times carry over
  // by name.
  std::vector<Stage> before = std::move(stages_);
  stages_.clear();
  components_ = sceneComponents(run_);
  stages_.push_back({"start-of-step", [this] { model_.clearStepForces(); }, StepPart::Forces, 0.0, false});
  for (const StepPart part : {StepPart::Forces, StepPart::Motion})
    for (const Component& c : components_)
      for (const Stage& stage : c.stages)
        if (stage.part == part) stages_.push_back(stage);
  stages_.push_back({"end-of-step", [this] { finishStep(); }, StepPart::Motion, 0.0, false});
  if (!historySpecs_.empty()) stages_.push_back({"histories", [this] { recordHistories(false); }, StepPart::Motion});
  for (Stage& stage : stages_)
    for (const Stage& old : before)
      if (old.name == stage.name) stage.seconds = old.seconds;
}

void Cycle::finishStep() {
  const StepTotals t = step_;
  step_ = {};
  energy_.setMechanical(t.kineticEnergy, t.strainEnergy);
  largestUnbalanced_ = t.largestUnbalancedForce;
  largestStepDisplacement_ = t.largestDisplacement;
  meanContactForce_ = t.forceCount ? t.forceScaleSum / t.forceCount : 0.0;
  // Centred in time like the kinetic energy: half of this step's work belongs before the check,
  // half after.
  energy_.supplyHalf(t.externalWork);
  checkEnergy();
  energy_.closeStep(t.externalWork, t.dampingDissipation, t.boundaryDissipation);
  checkReversingMotion(t);
  if (settings_.adaptiveDamping) adaptDamping(t);
  model_.time += dt_;
  ++model_.cycle;
}

void Cycle::adaptDamping(const StepTotals& t) {
  // 1.3-23 (Cundall 1982): R = power absorbed by mass damping / rate of change of kinetic
  // energy, held near 0.5 by a servo on alpha, which then damps close to critically. R is
  // formed every other step from the two steps' sums, as in the reference.
  servoPower_ += alpha_ * t.dampingPower;
  servoRate_ += t.kineticRate;
  if (model_.cycle % 2 == 0) return;
  const double rate = std::abs(servoRate_);
  // At rest (nothing moving, nothing changing) there is nothing to measure: alpha stays.
  if (rate > 0.0 || servoPower_ > 0.0) {
    const double ratio = rate > 0.0 ? servoPower_ / rate : INFINITY;
    alpha_ *= ratio < kAdaptiveTarget ? kAdaptiveGain : 1.0 / kAdaptiveGain;
  }
  alpha_ = std::clamp(alpha_, kAdaptiveStart / dt_, kAdaptiveMax / dt_);
  servoPower_ = servoRate_ = 0.0;
}

void Cycle::checkEnergy() {
  const double mechanical = energy_.mechanical();
  monitors_.kineticEnergy = energy_.kinetic();
  monitors_.strainEnergy = energy_.strain();
  monitors_.largestUnbalancedForce = largestUnbalanced_;
  monitors_.unbalancedRatio = meanContactForce_ > 0.0 ? largestUnbalanced_ / meanContactForce_
                              : (largestUnbalanced_ > 0.0 ? 1.0 : 0.0);
  // With fluid flowing, equilibrium is steady flow too.
  if (model_.flow.on) monitors_.unbalancedRatio = std::max(monitors_.unbalancedRatio, model_.flow.unbalancedRatio);
  const double excess = energy_.measureExcess();
  monitors_.energyRatio = mechanical / energy_.largestSupplied();
  if (!(excess <= kEnergyExcessLimit * energy_.largestSupplied())) {
    std::ostringstream s;
    s << "numerical instability at cycle " << model_.cycle << ", time " << model_.time << " s: the mechanical "
      << "energy (kinetic " << energy_.kinetic() << " + strain " << energy_.strain() << " J/m) "
      << (std::isfinite(mechanical) ? "exceeds the energy supplied (" + shown(energy_.supplied()) +
                                          " J/m) by more than " + shown(kEnergyExcessLimit) +
                                          " times the largest energy supplied so far"
                                    : "is not a number")
      << ". The time step " << dt_ << " s" << (settings_.localDamping > 0.0 ? " (reduced for local damping)" : "")
      << " is above the stability limit of the stiffest ";
    const bool dashpots = !model_.viscousEdges.empty() || !model_.rigidViscousEdges.empty() || !model_.freeFields.empty();
    if (hasZones_)
      s << "zone or contact" << (dashpots ? " or dashpot" : "") << ": lower solver.zone_fraction (now "
        << settings_.zoneFraction << "; 1, the estimate of 1.3-25, is the usual value) or solver.frac (now "
        << settings_.frac << ")";
    else
      s << "contact" << (dashpots ? " or dashpot" : "") << ": lower solver.frac (now " << settings_.frac
        << "; 0.1 is the usual value)";
    s << ", or check for a joint stiffness far above the others"
      << (dashpots ? " (run.step_limits shows which limit set the step)" : "") << ".";
    throw InstabilityError(s.str());
  }
}

void Cycle::checkReversingMotion(const StepTotals& t) {
  // Just above the critical step (0.1 to 3 % in FRAC on a stack of blocks) the highest mode
  // grows, contacts that open and slip clip it, and damping takes what it gains: the blocks
  // chatter, the mechanical energy stays below the monitor's bound, and the run ends wrong. That
  // mode is the step's Nyquist motion, reversing every step; a stable mode so fast decays under
  // damping, an unstable one is fed. So, while the motion reverses, watch its kinetic energy.
  ReversingWindow& w = reversing_;
  const bool reversing = t.kineticEnergy > kReversingFloor * energy_.largestSupplied() &&
                         t.kineticLag < kReversingCorrelation * t.kineticEnergy;
  const double damping = alpha_ * dt_ + settings_.localDamping;
  if (damping <= 0.0) return;
  if (!reversing) {
    // Chatter on contacts that open and close reverses in bursts: a short pause keeps the window.
    if (w.open && ++w.pause > kReversingPause) w.open = false;
    return;
  }
  w.pause = 0;
  if (!w.open) {
    w = {true, t.kineticEnergy, 0.0, 0, 0};
    return;
  }
  w.damping += damping;
  ++w.steps;
  if (w.damping < kReversingDampingExponent || w.steps < kReversingMinimumSteps) return;
  if (t.kineticEnergy < kReversingKept * w.startEnergy) {
    w = {true, t.kineticEnergy, 0.0, 0, 0};  // decaying as a stable mode does: watch on
    return;
  }
  std::ostringstream s;
  s << "numerical instability at cycle " << model_.cycle << ", time " << model_.time << " s: motion reversing "
    << "every step (the step's highest frequency) has persisted under damping for " << w.steps << " steps, its kinetic "
    << "energy going from " << w.startEnergy << " to " << t.kineticEnergy << " J/m where damping would have taken a "
    << "stable mode below " << kReversingKept * w.startEnergy << ". The time step " << dt_ << " s is just above the "
    << "stability limit of the stiffest ";
  if (hasZones_)
    s << "zone or contact: lower solver.zone_fraction (now " << settings_.zoneFraction << ") or solver.frac (now "
      << settings_.frac << ")";
  else
    s << "contact: lower solver.frac (now " << settings_.frac << "; 0.1 is the usual value)";
  s << ".";
  throw InstabilityError(s.str());
}

void Cycle::checkStiffnessGrowth(const ContactStepTotals& t) const {
  // The step was set from the joints' zero-stress stiffness (1.4.7.9); a stiffness grown with
  // the normal stress shrinks the critical step by its square root. Stop at half of it, before
  // the energy monitor would see the growth, with the cause named.
  const double growth = t.largestGrownStiffness / stepStiffness_;
  if (t.stiffestContact < 0 || growth <= 1.0) return;  // the step is as FRAC set it
  const double fraction = contactStepFraction_ * std::sqrt(growth);
  if (fraction <= kGrownStiffnessLimit) return;
  const Contact& c = model_.contacts[t.stiffestContact];
  const JointMaterial& j = model_.jointMaterials[c.joint];
  std::ostringstream s;
  s << "joint stiffness grown beyond the time step at cycle " << model_.cycle << ", time " << model_.time
    << " s: contact " << t.stiffestContact << " between blocks '" << model_.blocks.name[c.blockA] << "' and '"
    << model_.blocks.name[c.blockB] << "' (joint material '" << j.name << "') carries a normal stress of "
    << c.normalStress << " Pa, where its stiffness, " << t.largestGrownStiffness << " Pa/m, is " << growth
    << " times the largest zero-stress kn or ks the step was set from. The step is now " << fraction
    << " of the critical step (the limit is " << kGrownStiffnessLimit << "): lower solver.frac below "
    << settings_.frac * kGrownStiffnessLimit / fraction << " (further if the normal stress is still rising), "
    << "or raise kn and ks of '" << j.name << "' towards the stiffness reached.";
  throw InstabilityError(s.str());
}

void Cycle::recordHistories(bool initial) {
  // Block positions are those just reached, at `time`; joint and model measures were formed in
  // this step's contact and motion stages, at the start of the step, so they carry that time.
  // Before the first step joints have not been evaluated yet, so only blocks are sampled.
  for (std::size_t i = 0; i < historySpecs_.size(); ++i) {
    const HistorySpec& h = historySpecs_[i];
    HistorySeries& series = histories_[i];
    if (isAcceleration(h.quantity)) {
      // (v(t + dt/2) - v(t - dt/2)) / dt, the acceleration the step's forces gave, at t.
      const double v = accelerationBaseVelocity(model_, h);
      const bool due = !initial && series.hasLastVelocity && model_.cycle % series.every == 0;
      const double a = (v - series.lastVelocity) / dt_;
      series.lastVelocity = v;
      series.hasLastVelocity = true;
      if (due && appendHistorySample(series, model_.time - dt_, a) && series.halvings == 1) warnHalved(h, series);
      continue;
    }
    if (model_.cycle % series.every != 0) continue;
    const HistorySubject subject = findHistorySubject(h.quantity);
    // Positions are those just reached; zone stresses, joints and model measures were formed in
    // this step from the positions at its start.
    // The fluid's state is that the step's flow stage left, after the motion, at `time` too.
    const bool beamPosition = h.quantity == HistoryQuantity::BeamDisplacementX ||
                              h.quantity == HistoryQuantity::BeamDisplacementY || h.quantity == HistoryQuantity::BeamRotation ||
                              h.quantity == HistoryQuantity::CableDisplacement;
    const bool block = subject == HistorySubject::Block || subject == HistorySubject::Gridpoint ||
                       subject == HistorySubject::Fluid || beamPosition;
    if (initial && !block) continue;
    if (initial) series.sampledAtCycleZero = true;
    const bool halved = appendHistorySample(series, block || initial ? model_.time : model_.time - dt_,
                                            sampleHistory(model_, h, monitors_));
    if (halved && series.halvings == 1) warnHalved(h, series);
  }
}

void Cycle::warnHalved(const HistorySpec& h, const HistorySeries& series) const {
  std::fprintf(stderr, "%svdec: warning: history '%s' reached %zu samples at cycle %lld: it now keeps every "
               "other sample and samples every %lld cycles, doubling again each time it fills "
               "(results.json histories.%s.every); give it a larger every to choose the interval yourself\n",
               settings_.progress && isatty(STDERR_FILENO) ? "\n" : "", h.name.c_str(), kHistorySampleLimit,
               model_.cycle, series.every, h.name.c_str());
}

void Cycle::restartAccelerations() {
  for (std::size_t i = 0; i < historySpecs_.size(); ++i)
    if (isAcceleration(historySpecs_[i].quantity))
      histories_[i].lastVelocity = accelerationBaseVelocity(model_, historySpecs_[i]);
}

bool Cycle::stopReached(const StopCriteria& s, long long startCycle, double startTime, std::string& reason) const {
  // The ratio first: a run that reaches it on the step its limit falls due did reach it. A
  // phase takes at least one step before its ratio counts: the last one measured the state
  // before the phase's changes.
  if (s.ratio > 0 && model_.cycle > startCycle && monitors_.unbalancedRatio <= s.ratio) { reason = "ratio"; return true; }
  if (s.cycles >= 0 && model_.cycle - startCycle >= s.cycles) { reason = "cycles"; return true; }
  // Half a step of slack so that a time that is a multiple of dt is reached, not overshot.
  if (s.time >= 0 && model_.time - startTime >= s.time - 0.5 * dt_) { reason = "time"; return true; }
  return false;
}

void Cycle::beginPhase(const PhaseChanges& changes, const std::string& phaseName) {
  if (changes.gravity) model_.gravity = *changes.gravity;
  for (const JointStrengthChange& change : changes.joints) {
    JointMaterial& j = model_.jointMaterials[change.material];
    if (change.tanFriction) j.tanFriction = *change.tanFriction;
    if (change.cohesion) j.cohesion = *change.cohesion;
    if (change.tension) j.tension = *change.tension;
  }
  if (changes.localDamping) {
    settings_.localDamping = *changes.localDamping;
    if (settings_.localDamping > 0.0) {
      settings_.adaptiveDamping = false;
      alpha_ = servoPower_ = servoRate_ = 0.0;
    }
    // Local damping lowers the critical step (dampedStep); the step may only shrink.
    dt_ = std::min(dt_, dampedStep(undampedStep_));
  }
  if (changes.adaptiveDamping || changes.massDamping) settings_.localDamping = 0.0;
  if (changes.adaptiveDamping) {
    settings_.adaptiveDamping = *changes.adaptiveDamping;
    alpha_ = settings_.adaptiveDamping ? kAdaptiveStart / dt_ : 0.0;
    servoPower_ = servoRate_ = 0.0;
  }
  if (changes.massDamping) {
    settings_.adaptiveDamping = false;
    alpha_ = *changes.massDamping;
  }
  for (const auto& [material, strength] : changes.blockStrengths) {
    model_.blockMaterials[material].mohrCoulomb = strength;
    model_.blockMaterials[material].plastic = true;
  }
  if (!changes.blocks.empty()) changeRigidBlocks(changes.blocks);
  for (const ExcavationRegion& region : changes.excavations) excavate(region);
  const bool loaded = !model_.loadedEdges.empty(), driven = !model_.drivenVelocities.empty(),
             viscous = !model_.viscousEdges.empty(), freeField = !model_.freeFields.empty(),
             rigidViscous = !model_.rigidViscousEdges.empty();
  const bool flowing = model_.flow.on;
  for (const std::string& name : changes.freeBoundaries) {
    const auto flow = std::find_if(model_.flow.boundaries.begin(), model_.flow.boundaries.end(),
                                   [&name](const FlowBoundary& b) { return b.active && b.name == name; });
    if (flow != model_.flow.boundaries.end()) flow->active = false;
    else energy_.withdraw(-freeBoundaryCondition(model_, name));
  }
  for (FlowBoundary b : changes.flowBoundaries) {
    b.timeOrigin = model_.time;
    model_.flow.boundaries.push_back(b);
  }
  // Beams: those freed taken out (their energy leaves without work), then those installed placed
  // where the rock is now, then the loads and holds; their step may only shrink the step.
  for (const int beam : changes.freeBeams) energy_.withdraw(removeBeam(model_, beam));
  for (const int beam : changes.installBeams) installBeam(model_, beam, "phase '" + phaseName + "'");
  for (const PhaseChanges::BeamNodeChange& change : changes.beamNodes) {
    BeamNodes& nd = model_.structures.nodes;
    nd.appliedForce[change.node] += change.force;
    nd.appliedMoment[change.node] += change.moment;
    nd.fixed[change.node] |= change.fix;
  }
  // Cables and bolts likewise: those freed let go (a cable's energy leaves without work), then
  // those installed, stress-free where the rock is now.
  for (const int cable : changes.freeCables) energy_.withdraw(removeCable(model_, cable));
  for (const int bolt : changes.freeBolts) removeBolt(model_, bolt);
  // A pretension's elastic energy comes without work: supplied as a negative removal.
  for (const int cable : changes.installCables)
    energy_.withdraw(-installCable(model_, cable, "phase '" + phaseName + "'"));
  for (const int bolt : changes.installBolts) installBolt(model_, bolt, "phase '" + phaseName + "'");
  if (changes.boundaryElements) {
    // In place as the model stands after the phase's excavations and free: its nodes where they
    // are, holding the zones' stress there; its stiffness may shorten the step.
    model_.boundaryElements = *changes.boundaryElements;
    holdPresentStress(model_);
    buildStages();
    undampedStep_ = std::min(undampedStep_, stepLimitOf("boundary-elements"));
    dt_ = std::min(dt_, dampedStep(undampedStep_));
  }
  if (!changes.installBeams.empty() || !changes.installCables.empty() || !changes.installBolts.empty()) {
    undampedStep_ = std::min(undampedStep_, stepLimitOf("structures"));
    dt_ = std::min(dt_, dampedStep(undampedStep_));
  }
  if (changes.flow && *changes.flow != flowing) {
    model_.flow.on = *changes.flow;
    if (model_.flow.on) {
      startFlow(model_);
    } else {
      // The fluid the network held leaves the account with it.
      model_.flow.totals.removed += flowContent(model_);
      model_.flow.knots.clear();
      model_.flow.sides.clear();
      model_.flow.domains.clear();
    }
  }
  const int added = static_cast<int>(model_.boundaryConditions.size());
  for (const BoundaryCondition& b : changes.boundaries) energy_.withdraw(addBoundaryCondition(model_, b, model_.time));
  for (FreeFieldColumn& c : model_.freeFields)
    if (c.source >= added) keepStaticReactions(model_, c);
  // A stage for tractions or driven velocities where there were none before, or none where they all went.
  if (loaded != !model_.loadedEdges.empty() || driven != !model_.drivenVelocities.empty() ||
      viscous != !model_.viscousEdges.empty() || freeField != !model_.freeFields.empty() ||
      rigidViscous != !model_.rigidViscousEdges.empty() || flowing != model_.flow.on)
    buildStages();
  if (!changes.boundaries.empty() || model_.flow.on != flowing) {
    // Dashpots, free-field columns and fluid brought on may need a shorter step.
    formStiffnessDampingFactor();
    undampedStep_ = std::min({undampedStep_, stepLimitOf("boundaries"), stepLimitOf("free-field"), stepLimitOf("fracture-flow")});
    dt_ = std::min(dt_, dampedStep(undampedStep_));
  }
  Blocks& bl = model_.blocks;
  Gridpoints& g = model_.gridpoints;
  if (changes.resetVelocities) {
    // The kinetic energy taken away did no work: it leaves the energy supplied with it.
    double removed = 0.0;
    for (int b = 0; b < bl.size(); ++b) {
      if (!bl.movesFreely(b)) continue;
      if (model_.strainModes.holds(b)) removed += stopStrainRates(model_, b);
      removed += 0.5 * (bl.mass[b] * dot(bl.velocity[b], bl.velocity[b]) + bl.inertia[b] * bl.angularVelocity[b] * bl.angularVelocity[b]);
      bl.velocity[b] = {0.0, 0.0};
      bl.angularVelocity[b] = 0.0;
    }
    for (int i = 0; i < g.size(); ++i) {
      Vec2& v = g.velocity[i];
      const Vec2 kept{(g.driven[i] & DriveX) ? v.x : 0.0, (g.driven[i] & DriveY) ? v.y : 0.0};
      removed += 0.5 * g.mass[i] * (dot(v, v) - dot(kept, kept));
      v = kept;
    }
    BeamNodes& nd = model_.structures.nodes;
    for (int i = 0; i < nd.size(); ++i) {
      removed += 0.5 * (nd.mass[i] * dot(nd.velocity[i], nd.velocity[i]) +
                        nd.rotaryInertia[i] * nd.angularVelocity[i] * nd.angularVelocity[i]);
      nd.velocity[i] = {};
      nd.angularVelocity[i] = 0.0;
    }
    energy_.withdraw(removed);
  }
  if (changes.resetDisplacements) {
    // A rigid block's rotation counts from here: its shape's local frame turns to where the block
    // stands, so that the block itself does not move (and ties held in that frame turn with it).
    Vertices& vx = model_.vertices;
    for (int b = 0; b < bl.size(); ++b) {
      bl.initialCentroid[b] = bl.centroid[b];
      if (bl.deformable[b] || bl.rotation[b] == 0.0) continue;
      const double c = std::cos(bl.rotation[b]), s = std::sin(bl.rotation[b]);
      for (int v = bl.firstVertex[b]; v < bl.firstVertex[b] + bl.vertexCount[b]; ++v) {
        vx.localPosition[v] = rotated(vx.localPosition[v], c, s);
        vx.localArcCentre[v] = rotated(vx.localArcCentre[v], c, s);
        vx.localEdgeDirection[v] = rotated(vx.localEdgeDirection[v], c, s);
      }
      for (BeamTie& t : model_.structures.ties)
        if (t.zone < 0 && t.block == b) t.local = rotated(t.local, c, s);
      for (RockHold& hold : model_.structures.cableNodes.hold)
        if (hold.zone < 0 && hold.block == b) hold.local = rotated(hold.local, c, s);
      for (std::array<RockHold, 2>& sides : model_.structures.crossings.side)
        for (RockHold& hold : sides)
          if (hold.zone < 0 && hold.block == b) hold.local = rotated(hold.local, c, s);
      if (model_.strainModes.holds(b)) turnStrainFrame(model_, b);
      bl.rotation[b] = 0.0;
    }
    for (int i = 0; i < g.size(); ++i) g.initialPosition[i] = g.position[i];
    // Beam nodes' displacements from here; their rotations stay measured from the input (the
    // elements' bending is reckoned from them).
    BeamNodes& nd = model_.structures.nodes;
    for (int i = 0; i < nd.size(); ++i) nd.initialPosition[i] = nd.position[i];
  }
  advanceThermalClock(changes.heatTime);
  if (changes.staticSolve) solveDirectly();
}

double Cycle::storedElasticEnergy() const {
  const Gridpoints& g = model_.gridpoints;
  const Zones& zn = model_.zones;
  double stored = 0.0;
  for (const Contact& c : model_.contacts) stored += c.springEnergy;
  for (int z = 0; z < zn.size(); ++z) {
    const BlockMaterial& mat = model_.blockMaterials[zn.material[z]];
    const auto& n = zn.gridpoint[z];
    const double area = 0.5 * cross(g.position[n[1]] - g.position[n[0]], g.position[n[2]] - g.position[n[0]]);
    stored += area * elasticEnergyDensity(zn.sxx[z], zn.syy[z], zn.sxy[z], zn.szz[z], mat.bulk, mat.shear);
  }
  return stored;
}

void Cycle::solveDirectly() {
  // The solve leaves the gridpoints at rest: their kinetic energy leaves without work. The
  // elastic energy it sets up is supplied without its work being counted (the loads' work over
  // the solve's displacement exceeds it by what relaxation would have dissipated).
  const Gridpoints& g = model_.gridpoints;
  double kinetic = 0.0;
  for (int i = 0; i < g.size(); ++i) kinetic += 0.5 * g.mass[i] * dot(g.velocity[i], g.velocity[i]);
  energy_.withdraw(kinetic);
  const double before = storedElasticEnergy();
  const DirectSolveReport solved = solveStaticDirect(model_);
  staticSolveSeconds_ = std::max(staticSolveSeconds_, 0.0) + solved.seconds;
  staticSolveResidual_ = solved.relativeResidual;
  staticSolvePasses_ += solved.solves;
  staticSolveFactorisations_ += solved.factorisations;
  staticSolveUnknowns_ = solved.unknowns;
  staticSolvePlasticIterations_ += solved.plasticIterations;
  staticSolvePlasticFailed_ = staticSolvePlasticFailed_ || !solved.plasticConverged;
  energy_.supplyByDirectSolve(storedElasticEnergy() - before);
  // The solve moved the blocks without the detection's motion bounds: look again everywhere.
  if (hasContacts_) {
    std::vector<int> all(model_.blocks.size());
    for (int b = 0; b < model_.blocks.size(); ++b) all[b] = b;
    detection_.requestRescan(all);
  }
}

void Cycle::advanceThermalClock(double duration) {
  if (!model_.heat.on || !(duration > 0.0)) return;
  advanceHeat(model_, duration);
  bool expands = false;
  for (const BlockMaterial& mat : model_.blockMaterials) expands = expands || mat.expansion > 0.0;
  if (!expands) return;
  // The thermal stress is a change of the zones' stress without a load's work: its elastic
  // energy enters the account as supplied, as the direct solve's does.
  const double before = storedElasticEnergy();
  applyThermalStress(model_);
  energy_.supplyByThermalStress(storedElasticEnergy() - before);
}

void Cycle::closePhase(PhaseReport& done, Clock::time_point started) const {
  done.cycles = model_.cycle - done.startCycle;
  done.time = model_.time - done.startTime;
  done.unbalancedRatio = monitors_.unbalancedRatio;
  done.wallSeconds = std::chrono::duration<double>(Clock::now() - started).count();
}

void Cycle::changeRigidBlocks(const std::vector<RigidBlockChange>& changes) {
  Blocks& bl = model_.blocks;
  // The kinetic energy of a component counts while it is free: one that becomes driven takes
  // its energy out of the account, one that is released brings its present motion in.
  auto kinetic = [&](int b, std::uint8_t dofs) {
    double e = 0.0;
    if (dofs & DriveX) e += 0.5 * bl.mass[b] * bl.velocity[b].x * bl.velocity[b].x;
    if (dofs & DriveY) e += 0.5 * bl.mass[b] * bl.velocity[b].y * bl.velocity[b].y;
    if (dofs & DriveRotation)
      e += model_.strainModes.holds(b)
               ? rotationKineticEnergy(model_, b)
               : 0.5 * bl.inertia[b] * bl.angularVelocity[b] * bl.angularVelocity[b];
    return e;
  };
  bool released = false;
  for (const RigidBlockChange& c : changes) {
    const int b = c.block;
    const std::uint8_t before = bl.driven[b];
    const std::uint8_t newlyDriven = c.fix & ~before, newlyFree = c.free & before;
    energy_.withdraw(kinetic(b, newlyDriven) - kinetic(b, newlyFree));
    bl.driven[b] = static_cast<std::uint8_t>((before | c.fix) & ~c.free);
    released = released || newlyFree;
    if (c.fix) {
      bl.velocityHistory[b] = -1;  // a phase's drive is constant
      if (c.fix & DriveX) bl.velocity[b].x = c.velocity.x;
      if (c.fix & DriveY) bl.velocity[b].y = c.velocity.y;
      if (c.fix & DriveRotation) bl.angularVelocity[b] = c.angularVelocity;
    }
    if (c.force) bl.appliedForce[b] = *c.force;
    if (c.moment) bl.appliedMoment[b] = *c.moment;
  }
  if (!released) return;
  // A released block may be lighter than those the rigid-block step was formed from: form it again
  // over the blocks now free; the step may only shrink.
  components_ = sceneComponents(run_);  // the rigid blocks' limit now counts the released one
  formStiffnessDampingFactor();
  const double dtBlocks = stepLimitOf("rigid-block-motion");
  undampedStep_ = std::min(undampedStep_, dtBlocks);
  dt_ = std::min({dt_, dampedStep(dtBlocks), dampedStep(undampedStep_)});
  contactStepFraction_ = settings_.frac * dt_ / dtBlocks;
}

void Cycle::excavate(const ExcavationRegion& region) {
  excavateRigidBlocks(region);
  if (model_.zones.size() == 0) return;
  const ZoneExcavation done = excavateZones(model_, [&](Vec2 p) { return region.contains(p); }, region.where);
  if (done.removed == 0) return;
  // The removed zones' elastic energy and the motion of the gridpoints left without a zone leave
  // the model without work.
  energy_.withdraw(done.strainEnergy + done.kineticEnergy);
  for (HistorySpec& h : historySpecs_) {
    if (h.zone < 0) continue;
    if (done.newIndex[h.zone] < 0)
      throw SceneError(region.where + " excavates the zone of history '" + h.name +
                       "': give the history a point in a zone that stays");
    h.zone = done.newIndex[h.zone];
  }
  // A cable node whose zone is dug out is ungrouted from then on; the others follow their zone.
  for (CableNodes::Hold& hold : model_.structures.cableNodes.hold) {
    if (hold.zone < 0) continue;
    hold.zone = done.newIndex[hold.zone];
    if (hold.zone < 0) hold.block = -1;
  }
  for (std::size_t i = 0; i < model_.structures.cableNodes.hold.size(); ++i)
    if (model_.structures.cableNodes.hold[i].block < 0) model_.structures.cableNodes.bondForce[i] = 0.0;
  // A bolt's reinforcement with the zone on either side dug out holds nothing from then on.
  BoltCrossings& crossings = model_.structures.crossings;
  for (int i = 0; i < crossings.size(); ++i)
    for (RockHold& hold : crossings.side[i]) {
      if (hold.zone < 0) continue;
      hold.zone = done.newIndex[hold.zone];
      if (hold.zone < 0) breakCrossing(crossings, i);
    }
  // A tie whose zone is dug out holds nothing any more; the others follow their zone's new number.
  for (BeamTie& t : model_.structures.ties) {
    if (t.zone < 0 || t.broken) continue;
    t.zone = done.newIndex[t.zone];
    if (t.zone < 0) {
      t.broken = true;
      t.force = {};
    }
  }
  if (settings_.densityScaling) {
    Gridpoints& g = model_.gridpoints;
    for (int i = 0; i < g.size(); ++i)
      if (!(g.driven[i] & Excavated)) g.mass[i] = 0.25 * g.stiffness[i] * densityStep_ * densityStep_;
  } else if (model_.zones.size() > 0) {
    // A gridpoint that lost zones may have lost more mass than stiffness: the step may only shrink.
    formStiffnessDampingFactor();
    undampedStep_ = std::min(undampedStep_, stepLimitOf("deformable-blocks"));
    dt_ = std::min(dt_, dampedStep(undampedStep_));
  }
}

void Cycle::excavateRigidBlocks(const ExcavationRegion& region) {
  Blocks& bl = model_.blocks;
  std::vector<int> gone;
  for (int b = 0; b < bl.size(); ++b)
    if (!bl.deformable[b] && !bl.excavated(b) && region.contains(bl.centroid[b])) gone.push_back(b);
  if (gone.empty()) return;
  bool anyLeft = model_.zones.size() > 0;
  for (int b = 0; b < bl.size() && !anyLeft; ++b)
    anyLeft = !bl.deformable[b] && !bl.excavated(b) && std::find(gone.begin(), gone.end(), b) == gone.end();
  if (!anyLeft)
    throw SceneError(region.where + " removes every block when the phase starts (the blocks have moved into it): "
                                    "the model would be empty; give the excavation a smaller region");
  for (BeamTie& t : model_.structures.ties)
    if (t.zone < 0 && !t.broken && std::find(gone.begin(), gone.end(), t.block) != gone.end()) {
      t.broken = true;
      t.force = {};
    }
  CableNodes& cables = model_.structures.cableNodes;
  for (int i = 0; i < cables.size(); ++i)
    if (cables.hold[i].zone < 0 && std::find(gone.begin(), gone.end(), cables.hold[i].block) != gone.end()) {
      cables.hold[i].block = -1;
      cables.bondForce[i] = 0.0;
    }
  BoltCrossings& crossings = model_.structures.crossings;
  for (int i = 0; i < crossings.size(); ++i)
    for (const RockHold& hold : crossings.side[i])
      if (hold.zone < 0 && std::find(gone.begin(), gone.end(), hold.block) != gone.end()) breakCrossing(crossings, i);
  // Its motion and the elastic energy of its joints leave the model without work; its contacts
  // go with a rescan, which no longer pairs it with anything.
  double removed = 0.0;
  for (const int b : gone) {
    // The strain modes' energy, with their coupling to the rotation, before the motion stops.
    const bool strained = model_.strainModes.holds(b);
    if (strained) removed += releaseStrainModes(model_, b);
    const Vec2 v = bl.velocity[b];
    const double vx = (bl.driven[b] & DriveX) ? 0.0 : v.x, vy = (bl.driven[b] & DriveY) ? 0.0 : v.y;
    const double w = (bl.driven[b] & DriveRotation) ? 0.0 : bl.angularVelocity[b];
    removed += 0.5 * (bl.mass[b] * (vx * vx + vy * vy) + bl.inertia[b] * w * w);
    bl.driven[b] = DriveAll | Excavated;
    bl.velocity[b] = bl.inputVelocity[b] = {0.0, 0.0};
    bl.angularVelocity[b] = bl.inputAngularVelocity[b] = 0.0;
    bl.velocityHistory[b] = -1;
    bl.appliedForce[b] = {0.0, 0.0};
    bl.appliedMoment[b] = 0.0;
    if (strained) placeBlockVertices(model_, b);
  }
  for (const Contact& c : model_.contacts)
    if (bl.excavated(c.blockA) || bl.excavated(c.blockB)) removed += c.springEnergy;
  energy_.withdraw(removed);
  if (hasContacts_) detection_.rescanNow(model_, gone);
}

void Cycle::formStiffnessDampingFactor() {
  // Stiffness-proportional damping lowers the critical step of a mode of frequency w from 2 / w to
  // (2 / w) (sqrt(1 + xi^2) - xi), xi = beta w / 2 (Belytschko, after 1.3-22). The rigid-block
  // step is FRAC times the undamped critical step, so w = 2 FRAC / dt_b; the zones' estimate
  // 2 sqrt(m / k) (1.3-25) is at most their critical step, so w <= 2 / dt_z; the stiffest is
  // damped the most. Formed again when a phase raises w (a lighter block released, zones
  // excavated): the factor, like the step, may only shrink.
  if (!(settings_.stiffnessDamping > 0.0)) return;
  const double wZones = hasZones_ ? 2.0 / (stepLimitOf("deformable-blocks") / settings_.zoneFraction) : 0.0;
  const double w = std::max({2.0 * settings_.frac / stepLimitOf("rigid-block-motion"), wZones,
                             2.0 / stepLimitOf("free-field")});
  const double xi = 0.5 * settings_.stiffnessDamping * w;
  stiffnessDampingStepFactor_ = std::min(stiffnessDampingStepFactor_, std::sqrt(1.0 + xi * xi) - xi);
}

double Cycle::stepLimitOf(std::string_view component) const {
  for (const Component& c : components_)
    if (c.name == component && c.stepLimit) return c.stepLimit();
  return INFINITY;
}

void Cycle::stepUntil(const StopCriteria& stop, std::string& reason) {
  const bool progress = settings_.progress && isatty(STDERR_FILENO);
  const auto started = Clock::now();
  auto lastPrint = started;
  const long long startCycle = model_.cycle;
  const double startTime = model_.time;
  // The share of the way to a cycle or time limit done, whichever comes first; a ratio gives none.
  auto done = [&]() {
    double share = 0.0;
    if (stop.cycles > 0) share = std::max(share, static_cast<double>(model_.cycle - startCycle) / static_cast<double>(stop.cycles));
    if (stop.time > 0) share = std::max(share, (model_.time - startTime) / stop.time);
    return share;
  };
  while (!stopReached(stop, startCycle, startTime, reason)) {
    // Between two steps, where the state is whole: a signal ends the run here (core/interrupt).
    if (const int requested = interruptSignal(); requested != 0) {
      reason = "interrupted";
      return;
    }
    for (Stage& stage : stages_) {
      if (settings_.profile) {
        const auto t0 = Clock::now();
        stage.step();
        stage.seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      } else {
        stage.step();
      }
    }
    if (settings_.snapshotEvery > 0 && settings_.snapshot && model_.cycle % settings_.snapshotEvery == 0)
      settings_.snapshot(model_);
    if (progress && (model_.cycle & 255) == 0) {
      const auto now = Clock::now();
      if (now - lastPrint > std::chrono::milliseconds(250)) {
        const double share = done(), elapsed = std::chrono::duration<double>(now - started).count();
        printProgress(false, share > 0.0 ? elapsed * (1.0 - share) / share : -1.0);
        lastPrint = now;
      }
    }
  }
}

void Cycle::printProgress(bool final, double left) const {
  char estimate[48] = "";
  if (left >= 0.0) std::snprintf(estimate, sizeof estimate, "  left %.0f s", std::ceil(left));
  // Padded, so that a shorter line rewritten in place leaves nothing of the longer one before it.
  std::fprintf(stderr, "\rcycle %lld  time %.6g s  ratio %.3e  energy error %.1e  contacts %zu%s    %s", model_.cycle,
               model_.time, monitors_.unbalancedRatio, energy_.balanceError(), model_.contacts.size(), estimate,
               final ? "\n" : "");
  std::fflush(stderr);
}

RunReport Cycle::run() {
  const auto start = Clock::now();
  const bool progress = settings_.progress && isatty(STDERR_FILENO);
  const bool resumed = firstPhase_ > 0;
  if (!historySpecs_.empty() && !resumed) recordHistories(true);
  RunReport report;
  report.phases = donePhases_;
  const bool snapshots = settings_.snapshotEvery > 0 && settings_.snapshot;
  try {
    if (snapshots && !resumed) settings_.snapshot(model_);
    if (settings_.phases.empty()) {
      advanceThermalClock(settings_.heatTime);
      stepUntil(settings_.stop, report.stopReason);
    } else {
      for (std::size_t k = firstPhase_; k < settings_.phases.size(); ++k) {
        const Phase& phase = settings_.phases[k];
        phaseStart_ = Clock::now();
        PhaseReport& done = report.phases.emplace_back();
        done.name = phase.name;
        done.startCycle = model_.cycle;
        done.startTime = model_.time;
        beginPhase(phase.changes, phase.name);
        restartAccelerations();
        checkDamping(alpha_, "phase '" + phase.name + "': mass_damping");
        stepUntil(phase.stop, done.stopReason);
        closePhase(done, phaseStart_);
        report.stopReason = done.stopReason;
        if (done.stopReason == "interrupted") break;
        if (phase.requireEquilibrium && done.stopReason != "ratio") {
          std::ostringstream s;
          s << "phase '" << phase.name << "' has require_equilibrium = true but ended on its " << done.stopReason
            << " limit with the unbalanced-force ratio at " << done.unbalancedRatio << ", above its stop.ratio "
            << phase.stop.ratio << ": give the phase more cycles or time, more damping, or a larger ratio";
          done.stopReason = "error";
          throw EquilibriumError(s.str());
        }
        donePhases_ = report.phases;
        if (afterPhase) {
          // The report so far, for a state saved here to continue from.
          report.histories = histories_;
          afterPhase(phase.name, report);
        }
      }
    }
    if (report.stopReason == "interrupted") {
      report.interruptSignal = interruptSignal();
      report.errorCode = static_cast<int>(ExitCode::Interrupted);
    }
    if (snapshots && model_.cycle % settings_.snapshotEvery != 0) settings_.snapshot(model_);
  } catch (const Error& e) {
    if (!report.phases.empty() && report.phases.back().stopReason.empty()) {
      report.phases.back().stopReason = "error";
      closePhase(report.phases.back(), phaseStart_);
    }
    report.stopReason = "error";
    report.error = e.what();
    report.errorCode = static_cast<int>(e.code());
  }
  if (progress) printProgress(true);
  report.cycles = model_.cycle;
  report.time = model_.time;
  report.dt = dt_;
  report.stages = stageNames();
  for (const Stage& s : stages_)
    if (s.listed) report.profile.push_back({s.name, s.seconds});
  report.histories = histories_;
  report.energy = energy_.report();
  report.lastMonitors = monitors_;
  report.detectionScans = detection_.scans();
  report.staticSolveSeconds = staticSolveSeconds_;
  report.staticSolveResidual = staticSolveResidual_;
  report.staticSolvePasses = staticSolvePasses_;
  report.staticSolveFactorisations = staticSolveFactorisations_;
  report.staticSolveUnknowns = staticSolveUnknowns_;
  report.staticSolvePlasticIterations = staticSolvePlasticIterations_;
  report.staticSolvePlasticFailed = staticSolvePlasticFailed_;
  report.stiffnessDampingStepFactor = stiffnessDampingStepFactor_;
  report.stepLimits = stepLimits();
  report.wallSeconds = std::chrono::duration<double>(Clock::now() - start).count();
  return report;
}

std::vector<std::string> Cycle::stageNames() const {
  std::vector<std::string> names;
  for (const Stage& s : stages_)
    if (s.listed) names.push_back(s.name);
  return names;
}

std::vector<std::pair<std::string, double>> Cycle::stepLimits() const {
  std::vector<std::pair<std::string, double>> limits;
  for (const Component& c : components_)
    if (c.stepLimit && std::isfinite(c.stepLimit())) limits.emplace_back(c.name, c.stepLimit());
  return limits;
}

}  // namespace vdec
