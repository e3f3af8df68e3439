#pragma once
// The scene file's sections, each parsed into its definitions (scene/scene_definition.hpp) by its
// own file: read_materials, read_run_settings, read_blocks, read_boundaries, read_histories and
// read_phases. Each checks the values of its tables one by one and refuses unknown keys; what
// needs other sections (names, positions) is the builder's to check.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/table_reader.hpp"
#include "scene/scene_definition.hpp"

namespace vdec {

// Limits of a CSV table file (a `table` history or a `stress_table`), checked before it is read.
inline constexpr std::uintmax_t kTableFileBytes = 64u << 20;
inline constexpr std::size_t kTableRows = 1000000;

// [model], [[block_material]], [[joint_material]].
void readMaterials(TableReader& top, SceneDefinition& scene);
// `young` and `poisson`, or `bulk` and `shear`, or none (a material for rigid blocks only).
void readElasticConstants(TableReader& r, BlockMaterial& material);
// The Mohr-Coulomb keys friction, cohesion, [dilation], [tension]; nullopt when none is there.
// Warns of dilation above friction without cohesion.
std::optional<MohrCoulombProperties> readMohrCoulomb(TableReader& r, std::vector<std::string>& warnings);

// [solver], [stop], [output].
void readRunSettings(TableReader& top, SceneDefinition& scene);
StopCriteria readStop(TableReader& r);

// A rigid block's degrees of freedom named in the array `key`: "x", "y", "rotation" as DrivenDof bits.
std::uint8_t degreesOfFreedom(TableReader& r, std::string_view key);

// [[block]], [[region]], [[excavation]].
void readBlocks(TableReader& top, SceneDefinition& scene);
// The region of an [[excavation]] or [[phase.excavation]]: circle = { centre, radius } or a
// convex polygon.
ExcavationDefinition readExcavation(TableReader& r);

// [[boundary]] and [initial_stress].
void readBoundaries(TableReader& top, SceneDefinition& scene);
BoundaryDefinition readBoundary(TableReader& r);
// A selection range [low, high] under `key`; absent: everything.
CoordinateRange readRange(TableReader& r, std::string_view key);
// The ranges x, y, r, angle and the point centre of a table that selects gridpoints by their
// initial positions ([[boundary]], [boundary_elements], [[heat_boundary]]).
template <class Selection>
void readSelection(TableReader& r, Selection& d) {
  d.x = readRange(r, "x");
  d.y = readRange(r, "y");
  d.r = readRange(r, "r");
  d.angle = readRange(r, "angle");
  d.centre = r.vec2("centre", {0.0, 0.0});
}
// A time history table under `key`, e.g. history = { kind = "sine", frequency = 10.0 }.
TimeFunction readTimeFunction(TableReader& r, std::string_view key);

// [[history]] and [[joint_assignment]].
void readHistories(TableReader& top, SceneDefinition& scene);

// [fluid] and [[flow_boundary]]; the fluid keys of a [[joint_material]].
void readFluid(TableReader& top, SceneDefinition& scene);

// [[beam_material]], [[beam]], [[beam_node]] (read_structures.cpp); a [[beam]] or [[beam_node]]
// table alone, for a phase's.
void readStructures(TableReader& top, SceneDefinition& scene);
BeamDefinition readBeam(TableReader& r);
BeamNodeDefinition readBeamNode(TableReader& r);
CableDefinition readCable(TableReader& r);
BoltDefinition readBolt(TableReader& r);
BoundaryElementsDefinition readBoundaryElements(TableReader& r);
FlowBoundaryDefinition readFlowBoundary(TableReader& r);
void readJointFlowKeys(TableReader& r, JointMaterial& joint);

// [heat], [[heat_boundary]], [[heat_source]] (read_heat.cpp); the thermal keys of a
// [[block_material]].
void readHeat(TableReader& top, SceneDefinition& scene);
void readThermalKeys(TableReader& r, BlockMaterial& material);

// [[phase]].
void readPhases(TableReader& top, SceneDefinition& scene);

}  // namespace vdec
