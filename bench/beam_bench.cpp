// Cost of the beams' stages: a long beam of frame elements lying on a fixed rigid base, tied to it
// at every node (a beam on an elastic foundation), under gravity.
//
// Counters:
//   elements, ties                  of the beam
//   ns_beam_forces_per_element      the force stage (elements and ties) per element and step
//   ns_beam_motion_per_element      the motion stage (the nodes' central differences) per element and step
//   ns_beams_per_element            both
#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <optional>
#include <string>

#include "core/model.hpp"
#include "run/cycle.hpp"
#include "scene/scene_builder.hpp"

namespace {

vdec::Scene buildTiedBeam(int elements) {
  vdec::SceneDefinition s;
  s.title = "tied beam of " + std::to_string(elements) + " elements";
  s.model.rounding = 0.01;
  s.model.gravity = {0.0, -9.81};
  s.settings.frac = 0.1;
  s.settings.localDamping = 0.8;
  vdec::BlockMaterial& rock = s.blockMaterials.emplace_back().material;
  rock.name = "rock";
  rock.density = 2500.0;
  vdec::JointMaterial joint;
  joint.name = "joint";
  joint.law = vdec::JointLaw::CoulombSlip;
  joint.kn = joint.ks = 1e9;
  s.jointMaterials.push_back({joint, {}});
  const double length = 0.1 * elements;
  vdec::BlockDefinition& base = s.blocks.emplace_back();
  base.name = "base";
  base.material = "rock";
  base.vertices = {{-1.0, -1.0}, {length + 1.0, -1.0}, {length + 1.0, 0.0}, {-1.0, 0.0}};
  base.fix = vdec::DriveAll;
  base.origin.prefix = "block 'base'";
  vdec::BeamMaterialDefinition& steel = s.beamMaterials.emplace_back();
  steel.material.name = "steel";
  steel.material.young = 200e9;
  steel.material.area = 0.01;
  steel.material.inertia = 1e-5;
  steel.material.density = 7850.0;
  steel.material.tieNormalStiffness = steel.material.tieShearStiffness = 1e8;
  vdec::BeamDefinition& beam = s.beams.emplace_back();
  beam.name = "beam";
  beam.material = "steel";
  beam.points = {{0.0, 0.0}, {length, 0.0}};
  beam.elements = elements;
  beam.tied = true;
  return vdec::buildScene(std::move(s));
}

void RunTiedBeam(benchmark::State& state) {
  const int elements = static_cast<int>(state.range(0));
  const long long cycles = state.range(1);
  const vdec::Scene scene = buildTiedBeam(elements);
  vdec::Model model;
  std::optional<vdec::Cycle> cycle;
  std::map<std::string, double> stageSeconds;
  long long iterations = 0;
  for (auto _ : state) {
    model = scene.model;
    vdec::RunSettings run = scene.settings;
    run.stop = {};
    run.stop.cycles = cycles;
    run.profile = true;
    cycle.emplace(model, run, std::vector<vdec::HistorySpec>{});
    const auto t0 = std::chrono::steady_clock::now();
    const vdec::RunReport report = cycle->run();
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (!report.error.empty()) {
      state.SkipWithError(report.error.c_str());
      break;
    }
    for (const auto& stage : report.profile) stageSeconds[stage.name] += stage.seconds;
    ++iterations;
  }
  if (iterations == 0) return;
  const double steps = static_cast<double>(iterations) * static_cast<double>(cycles) * elements;
  state.counters["elements"] = elements;
  state.counters["ties"] = static_cast<double>(model.structures.ties.size());
  state.counters["ns_beam_forces_per_element"] = 1e9 * stageSeconds["beam-forces"] / steps;
  state.counters["ns_beam_motion_per_element"] = 1e9 * stageSeconds["beam-motion"] / steps;
  state.counters["ns_beams_per_element"] = 1e9 * (stageSeconds["beam-forces"] + stageSeconds["beam-motion"]) / steps;
}

void TiedBeam(benchmark::State& state) {
  try {
    RunTiedBeam(state);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

BENCHMARK(TiedBeam)
    ->Args({1000, 2000})
    ->Args({10000, 200})
    ->ArgNames({"elements", "cycles"})
    ->Iterations(3)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
