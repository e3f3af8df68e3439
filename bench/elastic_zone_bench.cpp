// Throughput of the deformable-block (zone) cycle on one elastic square block.
//
// The block is 10 m x 10 m, E = 10 GPa, nu = 0.25, density 2500 kg/m^3, no gravity, zoned with
// zoning = { nx = n, ny = n }: n x n crossed cells, 4 n^2 constant-strain triangles (zones) and
// (n + 1)^2 + n^2 gridpoints. The bottom edge is fixed in x and y, the top edge carries
// syy = -1 MPa, and mass damping is 400 1/s (about twice the block's lowest angular frequency;
// the value does not change the cost of a cycle). The scene is defined in code and made by
// vdec::buildScene, the builder the scene reader uses, so the benchmark runs the same model
// set-up as the vdec executable. The cycle's stages are zone-forces, boundary-tractions and gridpoint-motion, then
// the step's bookkeeping (energy sums, monitors, time).
//
// One change to the model as built: the free gridpoint components start with a slow rigid
// rotation about the block's centre (kSpin, at most 0.07 m/s), so that every zone is moving from
// the first cycle. A zone whose spin is exactly zero skips the stress rotation, and the load of
// the top edge alone reaches the lower rows only after its wave has crossed the block (about
// 600 cycles at 1e5 zones and 2 000 at 1e6, more than the timed windows), so without the spin
// the largest mesh would be timed with most zones at rest (measured: 37 ns per zone-cycle
// instead of 42).
//
// Each size and thread count (ThreadTeam::setThreadCount) gets one vdec::Cycle, which first runs
// warm-up cycles (not timed: the thread team is started, the arrays are paged in and the caches
// warm) and then a timed window of a fixed number of cycles per iteration (manual time: only that
// Cycle::run() call). The zones are all moving throughout, so the cost of a cycle does not
// depend on how far the run has gone: the iterations continue the same run and each does the
// same work.
//
// Counters:
//   zones, gridpoints, cycles, threads
//   ns_per_zone_cycle       run() wall time / (zones x cycles): the whole step
//   best_ns_per_zone_cycle  the same for the fastest iteration (less sensitive to a busy host)
//   ns_per_gridpoint_cycle  run() wall time / (gridpoints x cycles)
//   share_<stage>           that stage's fraction of the timed windows' wall time
//                           (RunSettings::profile); share_other is the rest: the step's
//                           bookkeeping, the stage calls and the profiling clock reads
//   ns_<stage>_per_zone_cycle  that stage's time per zone-cycle
//   vector_unit             the version of the zone and gridpoint loops that ran (VectorUnit:
//                           0 baseline, 1 AVX2, 2 AVX-512); ElasticZones runs the widest
//                           supported, ZoneVectorUnits each in turn
#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <string>

#include "core/thread_team.hpp"
#include "core/vector_unit.hpp"
#include "run/cycle.hpp"
#include "core/model.hpp"
#include "elastic_block.hpp"

namespace {

constexpr int kIterations = 3;
constexpr double kSpin = 0.01;  // rad/s, initial rigid rotation of the free gridpoint components

// The scene of each size is built once and shared by its thread counts (building the 1e6-zone
// block takes seconds: mesh generation, boundary edges, mesh quality).
const vdec::Scene& sceneOfSize(int n) {
  static std::map<int, vdec::Scene> scenes;
  if (auto it = scenes.find(n); it != scenes.end()) return it->second;
  scenes.clear();  // one size at a time: the 1e6-zone model is about 150 MB
  return scenes.emplace(n, vdec::bench::elasticBlock(n)).first->second;
}

void RunBlock(benchmark::State& state, vdec::VectorUnit unit) {
  const int n = static_cast<int>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const long long cycles = state.range(2);
  if (!vdec::setVectorUnit(unit)) {
    state.SkipWithError((std::string("this processor has no ") + vdec::vectorUnitName(unit)).c_str());
    return;
  }
  const long long warmup = std::max<long long>(10, cycles / 10);
  const vdec::Scene& scene = sceneOfSize(n);

  vdec::ThreadTeam::instance().setThreadCount(threads);
  struct Restore {
    ~Restore() {
      vdec::ThreadTeam::instance().setThreadCount(1);
      vdec::setVectorUnit(vdec::widestVectorUnit());
    }
  } restore;
  const int teamSize = vdec::ThreadTeam::instance().threadCount();

  vdec::Model model = scene.model;
  {
    vdec::Gridpoints& g = model.gridpoints;
    const double c = 0.5 * vdec::bench::kElasticBlockSide;
    for (int i = 0; i < g.size(); ++i) {
      const vdec::Vec2 r = g.position[i] - vdec::Vec2{c, c};
      if (!(g.driven[i] & vdec::DriveX)) g.velocity[i].x = -kSpin * r.y;
      if (!(g.driven[i] & vdec::DriveY)) g.velocity[i].y = kSpin * r.x;
    }
  }
  const double zones = static_cast<double>(model.zones.size());
  const double gridpoints = static_cast<double>(model.gridpoints.size());
  vdec::RunSettings run = scene.settings;
  run.stop = {};
  run.stop.cycles = warmup;
  run.profile = true;
  vdec::Cycle cycle(model, run, std::vector<vdec::HistorySpec>{});
  // A run's stop counts from where the run starts: the warm-up, then windows of `cycles` each.
  vdec::RunReport previous = cycle.run();
  vdec::StopCriteria window;
  window.cycles = cycles;
  cycle.setStop(window);
  if (!previous.error.empty()) {
    state.SkipWithError(("warm-up: " + previous.error).c_str());
    return;
  }

  std::map<std::string, double> stageSeconds;
  double seconds = 0.0, best = 0.0;
  long long iterations = 0;
  for (auto _ : state) {
    const long long before = model.cycle;
    const auto t0 = std::chrono::steady_clock::now();
    const vdec::RunReport report = cycle.run();
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(elapsed);
    if (!report.error.empty()) {
      state.SkipWithError(report.error.c_str());
      return;
    }
    if (model.cycle - before != cycles) {
      state.SkipWithError(("the run stopped early: " + report.stopReason).c_str());
      return;
    }
    seconds += elapsed;
    if (iterations == 0 || elapsed < best) best = elapsed;
    // The stage clocks run on across the Cycle's runs: take this run's part.
    for (std::size_t i = 0; i < report.profile.size(); ++i)
      stageSeconds[report.profile[i].name] += report.profile[i].seconds - previous.profile[i].seconds;
    previous = report;
    ++iterations;
  }
  if (iterations == 0) return;

  const double totalCycles = static_cast<double>(iterations) * static_cast<double>(cycles);
  state.counters["n"] = n;
  state.counters["zones"] = zones;
  state.counters["gridpoints"] = gridpoints;
  state.counters["cycles"] = static_cast<double>(cycles);
  state.counters["warmup_cycles"] = static_cast<double>(warmup);
  state.counters["threads"] = teamSize;
  state.counters["ns_per_zone_cycle"] = 1e9 * seconds / (zones * totalCycles);
  state.counters["best_ns_per_zone_cycle"] = 1e9 * best / (zones * static_cast<double>(cycles));
  state.counters["ns_per_gridpoint_cycle"] = 1e9 * seconds / (gridpoints * totalCycles);
  double profiled = 0.0;
  for (const auto& [name, s] : stageSeconds) {
    profiled += s;
    state.counters["share_" + name] = s / seconds;
    state.counters["ns_" + name + "_per_zone_cycle"] = 1e9 * s / (zones * totalCycles);
  }
  state.counters["share_other"] = (seconds - profiled) / seconds;
  state.counters["ns_other_per_zone_cycle"] = 1e9 * (seconds - profiled) / (zones * totalCycles);
  state.counters["dt"] = previous.dt;
  state.counters["vector_unit"] = static_cast<double>(unit);
  state.SetLabel(std::to_string(n) + "x" + std::to_string(n) + " crossed, " + std::to_string(teamSize) +
                 (teamSize == 1 ? " thread" : " threads"));
}

void ElasticZones(benchmark::State& state) {
  try {
    RunBlock(state, vdec::widestVectorUnit());
  } catch (const std::exception& e) {  // scene or geometry errors: report, go on with the next size
    state.SkipWithError(e.what());
  }
}

// n x n crossed cells: 4 n^2 = 1 024, 10 000, 99 856 and 1 000 000 zones, each at 1 and 2
// threads, and between 1 024 and 1e5 the sizes where a second thread starts to pay (2 116, 4 096,
// 6 400, 20 164 and 40 000 zones), from which the automatic thread count's threshold
// (kWorkForThreads in core/parallel.hpp) was set. Cycles per iteration: about 4e7 zone-cycles,
// 1-2 s of one thread per timed window at 25-40 ns per zone-cycle.
BENCHMARK(ElasticZones)
    ->Args({16, 1, 40000})
    ->Args({16, 2, 40000})
    ->Args({23, 1, 19000})
    ->Args({23, 2, 19000})
    ->Args({32, 1, 10000})
    ->Args({32, 2, 10000})
    ->Args({40, 1, 6250})
    ->Args({40, 2, 6250})
    ->Args({50, 1, 4000})
    ->Args({50, 2, 4000})
    ->Args({71, 1, 2000})
    ->Args({71, 2, 2000})
    ->Args({100, 1, 1000})
    ->Args({100, 2, 1000})
    ->Args({158, 1, 400})
    ->Args({158, 2, 400})
    ->Args({500, 1, 40})
    ->Args({500, 2, 40})
    ->ArgNames({"n", "threads", "cycles"})
    ->Iterations(kIterations)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// The 99 856-zone block on one thread with each vector unit's version of the zone and gridpoint
// loops (core/vector_unit.hpp): 0 the SSE2 baseline, 1 AVX2, 2 AVX-512. A unit this processor
// lacks is skipped with an error naming it.
void ZoneVectorUnits(benchmark::State& state) {
  try {
    RunBlock(state, static_cast<vdec::VectorUnit>(state.range(3)));
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

BENCHMARK(ZoneVectorUnits)
    ->Args({158, 1, 400, 0})
    ->Args({158, 1, 400, 1})
    ->Args({158, 1, 400, 2})
    ->ArgNames({"n", "threads", "cycles", "unit"})
    ->Iterations(kIterations)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
