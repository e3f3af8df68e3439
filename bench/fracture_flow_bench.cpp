// Cost of the fracture-flow stages on lattices of fixed square blocks with water in the joints.
//
// Each lattice is columns x rows rigid blocks of 1 m x 1 m, all held (the mechanics does no work,
// so the step's time is contact upkeep and the flow), touching in a plain grid: joints of aperture
// a0 (100 um, or 3 um for a single sub-step a step; residual a0 / 10),
// water (K_w = 2e9 Pa, mu = 1e-3 Pa s), pressure held at 1e5 Pa on the left side's mouths and 0
// on the right's, the explicit scheme at its default step fraction. The cycle's step is the rigid
// blocks' (1.3-28), far above the fluid's (1.4-11), so each mechanical step runs many fluid
// sub-steps: the figures separate the network's upkeep (built from the contacts every step) from
// the sub-steps.
//
// Counters:
//   knots, domains               of the network at the end
//   sub_steps_per_cycle          NSFDT, fluid sub-steps per mechanical step
//   ns_fluid_pressures_per_cycle the pressure forces stage
//   ns_fluid_flow_per_cycle      the flow stage: the network built again, then the sub-steps
//   ns_flow_per_knot_cycle       the flow stage per knot and mechanical step
//   ns_flow_per_knot_substep     the flow stage per knot and sub-step (upkeep included)
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <string>

#include "core/model.hpp"
#include "run/cycle.hpp"
#include "scene/scene_builder.hpp"

namespace {

constexpr long long kSettleCycles = 20;

vdec::Scene buildWetLattice(int columns, int rows, double aperture) {
  vdec::SceneDefinition s;
  s.title = "fluid lattice " + std::to_string(columns) + " x " + std::to_string(rows);
  s.model.rounding = 0.01;
  s.settings.frac = 0.1;
  vdec::BlockMaterial& rock = s.blockMaterials.emplace_back().material;
  rock.name = "rock";
  rock.density = 2500.0;
  vdec::JointMaterial joint;
  joint.name = "joint";
  joint.law = vdec::JointLaw::CoulombSlip;
  joint.kn = joint.ks = 1e9;
  joint.tanFriction = std::tan(vdec::radians(30.0));
  joint.aperture = aperture;
  joint.residualAperture = 0.1 * aperture;
  s.jointMaterials.push_back({joint, {}});
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      vdec::BlockDefinition& b = s.blocks.emplace_back();
      b.name = "b" + std::to_string(c) + "_" + std::to_string(r);
      b.material = "rock";
      b.vertices = {{1.0 * c, 1.0 * r}, {c + 1.0, 1.0 * r}, {c + 1.0, r + 1.0}, {1.0 * c, r + 1.0}};
      b.fix = vdec::DriveAll;
      b.origin.prefix = "block '" + b.name + "'";
    }
  vdec::FluidDefinition fluid;
  fluid.fluid.bulkModulus = 2e9;
  fluid.fluid.viscosity = 1e-3;
  s.fluid = fluid;
  vdec::FlowBoundaryDefinition left, right;
  left.boundary.lo = {-0.1, -0.1};
  left.boundary.hi = {0.1, rows + 0.1};
  left.boundary.value = 1e5;
  right.boundary.lo = {columns - 0.1, -0.1};
  right.boundary.hi = {columns + 0.1, rows + 0.1};
  s.flowBoundaries = {left, right};
  return vdec::buildScene(std::move(s));
}

void RunWetLattice(benchmark::State& state) {
  const int columns = static_cast<int>(state.range(0)), rows = static_cast<int>(state.range(1));
  const long long cycles = state.range(2);
  // Micrometres: a0 = 100 um, the fluid step far below the mechanical one; 3 um: one sub-step, so
  // that the step's cost is the network's upkeep and a single sub-step.
  const double aperture = 1e-6 * static_cast<double>(state.range(3));
  const vdec::Scene scene = buildWetLattice(columns, rows, aperture);
  vdec::Model model;
  std::optional<vdec::Cycle> cycle;
  std::map<std::string, double> stageSeconds;
  double subSteps = 0.0;
  long long iterations = 0;
  for (auto _ : state) {
    model = scene.model;
    vdec::RunSettings run = scene.settings;
    run.stop = {};
    run.stop.cycles = kSettleCycles;
    run.profile = true;
    cycle.emplace(model, run, std::vector<vdec::HistorySpec>{});
    const vdec::RunReport settled = cycle->run();
    const long long subStepsBefore = model.flow.totals.subSteps;
    vdec::StopCriteria window;
    window.cycles = cycles;
    cycle->setStop(window);
    const auto t0 = std::chrono::steady_clock::now();
    const vdec::RunReport report = cycle->run();
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (!report.error.empty()) {
      state.SkipWithError(report.error.c_str());
      break;
    }
    subSteps += static_cast<double>(model.flow.totals.subSteps - subStepsBefore);
    for (std::size_t i = 0; i < report.profile.size(); ++i)
      stageSeconds[report.profile[i].name] += report.profile[i].seconds - settled.profile[i].seconds;
    ++iterations;
  }
  if (iterations == 0) return;
  const double totalCycles = static_cast<double>(iterations) * static_cast<double>(cycles);
  const double knots = static_cast<double>(model.flow.knots.size());
  state.counters["knots"] = knots;
  state.counters["domains"] = static_cast<double>(model.flow.domains.size());
  state.counters["sub_steps_per_cycle"] = subSteps / totalCycles;
  state.counters["ns_fluid_pressures_per_cycle"] = 1e9 * stageSeconds["fluid-pressures"] / totalCycles;
  state.counters["ns_fluid_flow_per_cycle"] = 1e9 * stageSeconds["fluid-flow"] / totalCycles;
  state.counters["ns_flow_per_knot_cycle"] = 1e9 * stageSeconds["fluid-flow"] / (knots * totalCycles);
  state.counters["ns_flow_per_knot_substep"] = 1e9 * stageSeconds["fluid-flow"] / (knots * subSteps);
  for (const auto& [name, s] : stageSeconds) state.counters["ns_" + name + "_per_cycle"] = 1e9 * s / totalCycles;
  state.SetLabel(std::to_string(columns) + "x" + std::to_string(rows));
}

void FractureFlowLattice(benchmark::State& state) {
  try {
    RunWetLattice(state);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

BENCHMARK(FractureFlowLattice)
    ->Args({10, 10, 200, 100})
    ->Args({30, 30, 40, 100})
    ->Args({30, 30, 400, 3})
    ->ArgNames({"columns", "rows", "cycles", "aperture_um"})
    ->Iterations(3)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
