// Cost of the support's stages.
// TiedBeam: a long beam of frame elements lying on a fixed rigid base, tied to it at every node (a
// beam on an elastic foundation), under gravity.
//   elements, ties                  of the beam
//   ns_beam_forces_per_element      the force stage (elements and ties) per element and step
//   ns_beam_motion_per_element      the motion stage (the nodes' central differences) per element and step
//   ns_beams_per_element            both
// GroutedCable: one long cable grouted along its length in a fixed rigid block, pulled at its head.
//   ns_cable_forces_per_element, ns_cable_motion_per_element, ns_cables_per_element   as the beam's
// BoltedBlocks: a row of free rigid blocks resting on a fixed base, each held by a vertical bolt
// across its joint with the base, under gravity.
//   reinforcements                  one per block
//   ns_bolt_forces_per_reinforcement    the bolt stage per reinforcement and step
#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <optional>
#include <string>

#include "core/model.hpp"
#include "run/cycle.hpp"
#include "scene/scene_builder.hpp"

namespace {

vdec::SceneDefinition rockScene(const std::string& title) {
  vdec::SceneDefinition s;
  s.title = title;
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
  return s;
}

vdec::BlockDefinition& addBox(vdec::SceneDefinition& s, const std::string& name, vdec::Vec2 low, vdec::Vec2 high) {
  vdec::BlockDefinition& b = s.blocks.emplace_back();
  b.name = name;
  b.material = "rock";
  b.vertices = {low, {high.x, low.y}, high, {low.x, high.y}};
  b.origin.prefix = "block '" + name + "'";
  return b;
}

vdec::Scene buildTiedBeam(int elements) {
  vdec::SceneDefinition s = rockScene("tied beam of " + std::to_string(elements) + " elements");
  const double length = 0.1 * elements;
  addBox(s, "base", {-1.0, -1.0}, {length + 1.0, 0.0}).fix = vdec::DriveAll;
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

// Runs `scene` for `cycles` steps per iteration and returns the seconds each stage took, summed.
std::map<std::string, double> stageSeconds(benchmark::State& state, const vdec::Scene& scene, long long cycles,
                                           long long& iterations) {
  std::map<std::string, double> seconds;
  for (auto _ : state) {
    vdec::Model model = scene.model;
    vdec::RunSettings run = scene.settings;
    run.stop = {};
    run.stop.cycles = cycles;
    run.profile = true;
    vdec::Cycle cycle(model, run, std::vector<vdec::HistorySpec>{});
    const auto t0 = std::chrono::steady_clock::now();
    const vdec::RunReport report = cycle.run();
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (!report.error.empty()) {
      state.SkipWithError(report.error.c_str());
      break;
    }
    for (const auto& stage : report.profile) seconds[stage.name] += stage.seconds;
    ++iterations;
  }
  return seconds;
}

void RunTiedBeam(benchmark::State& state) {
  const int elements = static_cast<int>(state.range(0));
  const long long cycles = state.range(1);
  const vdec::Scene scene = buildTiedBeam(elements);
  long long iterations = 0;
  std::map<std::string, double> seconds = stageSeconds(state, scene, cycles, iterations);
  if (iterations == 0) return;
  const double steps = static_cast<double>(iterations) * static_cast<double>(cycles) * elements;
  state.counters["elements"] = elements;
  state.counters["ties"] = static_cast<double>(scene.model.structures.ties.size());
  state.counters["ns_beam_forces_per_element"] = 1e9 * seconds["beam-forces"] / steps;
  state.counters["ns_beam_motion_per_element"] = 1e9 * seconds["beam-motion"] / steps;
  state.counters["ns_beams_per_element"] = 1e9 * (seconds["beam-forces"] + seconds["beam-motion"]) / steps;
}

void RunGroutedCable(benchmark::State& state) {
  const int elements = static_cast<int>(state.range(0));
  const long long cycles = state.range(1);
  vdec::SceneDefinition s = rockScene("grouted cable of " + std::to_string(elements) + " elements");
  const double length = 0.1 * elements;
  addBox(s, "rock", {0.0, -0.5}, {length + 1.0, 0.5}).fix = vdec::DriveAll;
  vdec::CableMaterialDefinition& strand = s.cableMaterials.emplace_back();
  strand.material.name = "strand";
  strand.material.young = 200e9;
  strand.material.area = 5e-4;
  strand.material.density = 7850.0;
  strand.material.bondStiffness = 1e8;
  vdec::CableDefinition& cable = s.cables.emplace_back();
  cable.name = "cable";
  cable.material = "strand";
  cable.from = {0.0, 0.0};
  cable.to = {length, 0.0};
  cable.elements = elements;
  vdec::CableNodeDefinition& head = s.cableNodes.emplace_back();
  head.cable = "cable";
  head.force = -1e4;
  const vdec::Scene scene = vdec::buildScene(std::move(s));
  long long iterations = 0;
  std::map<std::string, double> seconds = stageSeconds(state, scene, cycles, iterations);
  if (iterations == 0) return;
  const double steps = static_cast<double>(iterations) * static_cast<double>(cycles) * elements;
  state.counters["elements"] = elements;
  state.counters["ns_cable_forces_per_element"] = 1e9 * seconds["cable-forces"] / steps;
  state.counters["ns_cable_motion_per_element"] = 1e9 * seconds["cable-motion"] / steps;
  state.counters["ns_cables_per_element"] = 1e9 * (seconds["cable-forces"] + seconds["cable-motion"]) / steps;
}

void RunBoltedBlocks(benchmark::State& state) {
  const int blocks = static_cast<int>(state.range(0));
  const long long cycles = state.range(1);
  vdec::SceneDefinition s = rockScene(std::to_string(blocks) + " bolted blocks");
  addBox(s, "base", {-1.0, -1.0}, {1.5 * blocks + 1.0, 0.0}).fix = vdec::DriveAll;
  vdec::BoltMaterialDefinition& bar = s.boltMaterials.emplace_back();
  bar.material.name = "bar";
  bar.material.axialStiffness = 1e8;
  bar.material.shearStiffness = 2e7;
  bar.material.axialStrength = 1e5;
  bar.material.shearStrength = 8e4;
  bar.material.activeLength = 0.2;
  for (int i = 0; i < blocks; ++i) {
    const double x = 1.5 * i;
    addBox(s, "b" + std::to_string(i), {x, 0.0}, {x + 1.0, 1.0});
    vdec::BoltDefinition& bolt = s.bolts.emplace_back();
    bolt.name = "bolt" + std::to_string(i);
    bolt.material = "bar";
    bolt.from = {x + 0.5, -0.5};
    bolt.to = {x + 0.5, 0.5};
  }
  const vdec::Scene scene = vdec::buildScene(std::move(s));
  long long iterations = 0;
  std::map<std::string, double> seconds = stageSeconds(state, scene, cycles, iterations);
  if (iterations == 0) return;
  const double steps = static_cast<double>(iterations) * static_cast<double>(cycles) * blocks;
  state.counters["reinforcements"] = static_cast<double>(scene.model.structures.crossings.size());
  state.counters["ns_bolt_forces_per_reinforcement"] = 1e9 * seconds["bolt-forces"] / steps;
  state.counters["ns_contact_forces_per_block"] = 1e9 * seconds["contact-forces"] / steps;
}

template <void (*Run)(benchmark::State&)>
void Guarded(benchmark::State& state) {
  try {
    Run(state);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
}

void TiedBeam(benchmark::State& state) { Guarded<RunTiedBeam>(state); }
void GroutedCable(benchmark::State& state) { Guarded<RunGroutedCable>(state); }
void BoltedBlocks(benchmark::State& state) { Guarded<RunBoltedBlocks>(state); }

BENCHMARK(TiedBeam)
    ->Args({1000, 2000})
    ->Args({10000, 200})
    ->ArgNames({"elements", "cycles"})
    ->Iterations(3)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(GroutedCable)
    ->Args({1000, 2000})
    ->Args({10000, 200})
    ->ArgNames({"elements", "cycles"})
    ->Iterations(3)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BoltedBlocks)
    ->Args({1000, 200})
    ->ArgNames({"blocks", "cycles"})
    ->Iterations(3)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
