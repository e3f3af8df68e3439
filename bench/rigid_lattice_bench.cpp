// Throughput of the rigid-block cycle on lattices of square blocks resting on a fixed base, and of
// the same lattices of simply-deformable blocks (SimplyDeformableLattice: the rock elastic, E = 10
// GPa, nu = 0.25; docs/models/simply-deformable.md), whose cost per block-cycle the rigid one's
// measures.
//
// Each lattice is columns x rows blocks of 1 m x 1 m (density 2500 kg/m^3), stacked in a plain
// grid (no bond), touching, on a fixed base block 1 m thick spanning the width; Coulomb-slip joints
// kn = ks = 1e9 Pa/m, friction 30 deg, rounding 0.01 m, gravity -9.81 m/s^2, no damping. The scene
// is defined in code and made by vdec::buildScene, the builder the scene reader uses, so the
// benchmark runs the same model set-up as the vdec executable.
//
// Every iteration starts from the scene as built, constructs a vdec::Cycle, lets it settle for
// kSettleCycles cycles (contacts formed, buffers grown, caches warm; not timed) and then times a
// fixed number of further cycles of the same Cycle (manual time: only that Cycle::run() call), so
// each iteration does exactly the same work.
//
// Counters, all per lattice block (the fixed base excluded) or per contact in the contact list:
//   ns_per_block_cycle    run() wall time / (blocks x cycles)
//   ns_per_contact_cycle  run() wall time / (contacts x cycles)
//   best_ns_per_...       the same for the fastest iteration (less sensitive to a busy host)
//   contacts              contacts in the list (open and closed), mean of start and end of a run
//   closed_contacts       contacts carrying force at the end of a run
//   cycles                cycles per iteration
//   detection_scans       full contact scans in the timed cycles
//   share_<stage>         that stage's fraction of the profiled step time (RunSettings::profile)
//   ns_<stage>_per_cycle  that stage's time per cycle
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <string>

#include "run/cycle.hpp"
#include "core/model.hpp"
#include "io/build_info.hpp"
#include "scene/scene_builder.hpp"

namespace {

constexpr long long kSettleCycles = 200;
constexpr int kIterations = 5;

vdec::BlockDefinition square(const std::string& name, vdec::Vec2 low, vdec::Vec2 high) {
  vdec::BlockDefinition b;
  b.name = name;
  b.material = "rock";
  b.vertices = {low, {high.x, low.y}, high, {low.x, high.y}};
  b.origin.prefix = "block '" + name + "'";
  return b;
}

vdec::Scene buildLattice(int columns, int rows, bool strained) {
  vdec::SceneDefinition s;
  s.title = "benchmark lattice " + std::to_string(columns) + " x " + std::to_string(rows);
  s.model.gravity = {0.0, -9.81};
  s.model.rounding = 0.01;
  s.settings.frac = 0.1;
  s.settings.stop.cycles = kSettleCycles;
  vdec::BlockMaterial& rock = s.blockMaterials.emplace_back().material;
  rock.name = "rock";
  rock.density = 2500.0;
  if (strained) rock.bulk = 10e9 / 1.5, rock.shear = 4e9;
  vdec::JointMaterial joint;
  joint.name = "joint";
  joint.law = vdec::JointLaw::CoulombSlip;
  joint.kn = joint.ks = 1e9;
  joint.tanFriction = std::tan(vdec::radians(30.0));
  s.jointMaterials.push_back({joint, {}});
  s.blocks.push_back(square("base", {0.0, -1.0}, {static_cast<double>(columns), 0.0}));
  s.blocks.back().fix = vdec::DriveAll;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      s.blocks.push_back(square("b" + std::to_string(c) + "_" + std::to_string(r), {static_cast<double>(c), 1.0 * r},
                                {c + 1.0, r + 1.0}));
      s.blocks.back().simplyDeformable = strained;
    }
  return vdec::buildScene(std::move(s));
}

int closedContacts(const vdec::Model& m) {
  int n = 0;
  for (const vdec::Contact& c : m.contacts) n += c.open ? 0 : 1;
  return n;
}

void RunLattice(benchmark::State& state, bool strained) {
  const int columns = static_cast<int>(state.range(0)), rows = static_cast<int>(state.range(1));
  const long long blocks = static_cast<long long>(columns) * rows;
  const long long cycles = state.range(2);
  const vdec::Scene scene = buildLattice(columns, rows, strained);

  vdec::Model model;
  std::optional<vdec::Cycle> cycle;
  std::map<std::string, double> stageSeconds;
  double seconds = 0.0, contactCycles = 0.0, best = 0.0, bestContacts = 0.0;
  long long closed = 0, scans = 0, iterations = 0;
  for (auto _ : state) {
    // One Cycle settles and then runs the timed window, so that its energy monitor has seen the
    // whole run. A run's stop counts from where the run starts: the settling run, then the window.
    model = scene.model;
    vdec::RunSettings run = scene.settings;
    run.stop = {};
    run.stop.cycles = kSettleCycles;
    run.profile = true;
    cycle.emplace(model, run, std::vector<vdec::HistorySpec>{});  // first detection, at cycle 0
    const vdec::RunReport settled = cycle->run();
    if (!settled.error.empty()) {
      state.SkipWithError(("settling: " + settled.error).c_str());
      break;
    }
    vdec::StopCriteria window;
    window.cycles = cycles;
    cycle->setStop(window);
    const double contactsBefore = static_cast<double>(model.contacts.size());

    const auto t0 = std::chrono::steady_clock::now();
    const vdec::RunReport report = cycle->run();
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(elapsed);

    if (!report.error.empty()) {
      state.SkipWithError(report.error.c_str());
      break;
    }
    if (report.cycles != kSettleCycles + cycles) {
      state.SkipWithError(("the run stopped early: " + report.stopReason).c_str());
      break;
    }
    const double contacts = 0.5 * (contactsBefore + static_cast<double>(model.contacts.size()));
    seconds += elapsed;
    contactCycles += contacts * static_cast<double>(cycles);
    if (iterations == 0 || elapsed < best) {
      best = elapsed;
      bestContacts = contacts;
    }
    closed += closedContacts(model);
    scans += report.detectionScans - settled.detectionScans;
    // The stage clocks run on across both runs of the Cycle: take the timed run's part.
    for (std::size_t i = 0; i < report.profile.size(); ++i)
      stageSeconds[report.profile[i].name] += report.profile[i].seconds - settled.profile[i].seconds;
    ++iterations;
  }
  if (iterations == 0) return;

  const double n = static_cast<double>(iterations);
  const double totalCycles = n * static_cast<double>(cycles);
  state.counters["blocks"] = static_cast<double>(blocks);
  state.counters["cycles"] = static_cast<double>(cycles);
  state.counters["contacts"] = contactCycles / totalCycles;
  state.counters["closed_contacts"] = static_cast<double>(closed) / n;
  state.counters["detection_scans"] = static_cast<double>(scans) / n;
  state.counters["ns_per_block_cycle"] = 1e9 * seconds / (static_cast<double>(blocks) * totalCycles);
  state.counters["ns_per_contact_cycle"] = 1e9 * seconds / contactCycles;
  state.counters["best_ns_per_block_cycle"] = 1e9 * best / (static_cast<double>(blocks) * static_cast<double>(cycles));
  state.counters["best_ns_per_contact_cycle"] = 1e9 * best / (bestContacts * static_cast<double>(cycles));
  double profiled = 0.0;
  for (const auto& [name, s] : stageSeconds) profiled += s;
  for (const auto& [name, s] : stageSeconds) {
    state.counters["share_" + name] = profiled > 0.0 ? s / profiled : 0.0;
    state.counters["ns_" + name + "_per_cycle"] = 1e9 * s / totalCycles;
  }
  state.SetLabel(std::to_string(columns) + "x" + std::to_string(rows));
}

void RigidLattice(benchmark::State& state) {
  try {
    RunLattice(state, false);
  } catch (const std::exception& e) {  // scene or geometry errors: report, go on with the next size
    state.SkipWithError(e.what());
  }
}

void SimplyDeformableLattice(benchmark::State& state) {
  try {
    RunLattice(state, true);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

// columns x rows: 100, 1 000 and 10 000 blocks, four to two and a half times wider than tall so that
// the base joint's load (rows x 24.5 kN per metre) keeps its overlap well inside the limit of half
// the rounding length even with the dynamic overshoot of gravity applied at once. Cycles per
// iteration: a tenth of a second to a second or two each, and few enough that every timed window
// (settling plus one iteration) stays early in the undamped run.
void LatticeSizes(benchmark::internal::Benchmark* b) {
  b->Args({20, 5, 2000})
      ->Args({50, 20, 500})
      ->Args({200, 50, 200})
      ->ArgNames({"columns", "rows", "cycles"})
      ->Iterations(kIterations)
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond);
}

// The same lattices and cycles for both kinds of block, so that their costs per block-cycle
// compare directly.
BENCHMARK(RigidLattice)->Apply(LatticeSizes);
BENCHMARK(SimplyDeformableLattice)->Apply(LatticeSizes);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("vdec_version", vdec::build::version);
  benchmark::AddCustomContext("vdec_commit", vdec::build::gitCommit);
  benchmark::AddCustomContext("vdec_build_type", vdec::build::buildType);
  benchmark::AddCustomContext("vdec_compiler", vdec::build::compiler);
  benchmark::AddCustomContext("vdec_settle_cycles", std::to_string(kSettleCycles));
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
