#pragma once
// The builder's parts, shared by its files: name lookups that fail on a definition's origin,
// boundary selection and phases.
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/model.hpp"
#include "run/cycle.hpp"
#include "scene/scene_definition.hpp"

namespace vdec {

// The block named `name`, or an error on `key` of `origin`.
int blockNamed(const Model& model, const Origin& origin, std::string_view key, const std::string& name);
int blockMaterialNamed(const Model& model, const Origin& origin, std::string_view key, const std::string& name);
int jointMaterialNamed(const Model& model, const Origin& origin, std::string_view key, const std::string& name);

// A boundary definition resolved to the gridpoints and edges of its block in `model` (its
// history, if any, appended to model.timeFunctions).
BoundaryCondition resolveBoundary(const BoundaryDefinition& definition, Model& model);
// The gridpoints of the flagged deformable blocks whose initial positions lie in the ranges (r and
// angle about `centre`), and the vertices of the flagged rigid blocks whose positions when the
// scene is built do, to a round-off slack of 1e-9 of the blocks' size, which it gives too.
struct GridpointSelection {
  std::vector<char> selected;
  std::vector<char> selectedVertex;
  double slack = 0.0;
  int count = 0;
};
GridpointSelection selectGridpoints(const Model& model, const std::vector<char>& inBlocks, const CoordinateRange& x,
                                    const CoordinateRange& y, const CoordinateRange& r, const CoordinateRange& angle,
                                    Vec2 centre);
// The boundary-element far field on the outer edges the definition selects (its stiffness
// formed; bem/far_field.hpp's holdPresentStress puts it in place).
BoundaryElementField boundaryElementField(const Model& model, const BoundaryElementsDefinition& definition);
// The in-situ stress a far field's rigid blocks' edges hold ([initial_stress]'s sxx, syy, sxy).
void holdInSitu(BoundaryElementField& field, const InitialStressDefinition& definition);

// The thermal solution of [heat] on the model's zones (thermal/heat_state.hpp), ready to advance.
void buildHeat(Model& model, const SceneDefinition& scene);

// A phase resolved against the model. `geometry` is the model as the phase will find it
// (excavated by the phases before; made on the first excavation), on which its boundaries select
// gridpoints and edges; `active` holds the names of the boundaries active when it starts.
Phase buildPhase(const PhaseDefinition& definition, Model& model, std::optional<Model>& geometry,
                 std::set<std::string>& active);

// The fluid and its flow boundaries into the model (after the blocks); each joint material's
// fluid keys checked against the presence of [fluid].
void addFluid(Model& model, const SceneDefinition& scene);
// A flow boundary resolved: its history appended to model.timeFunctions; a water table needs
// `gravity`, the gravity in force when it comes on.
FlowBoundary flowBoundary(Model& model, const FlowBoundaryDefinition& definition, Vec2 gravity);

// The beams, their materials, nodes and ties to the rock into the model (after the blocks).
void addStructures(Model& model, const SceneDefinition& scene);
// A beam's nodes and elements into the model, not installed (installBeam puts it in); its index.
int addBeam(Model& model, const BeamDefinition& definition);
// The beam named `name`, or an error on `beam` of `origin`; the node of a beam nearest a point
// (at the positions displacements are measured from).
int beamNamed(const Model& model, const Origin& origin, const std::string& name);
int cableNamed(const Model& model, const Origin& origin, const std::string& name);
int nearestCableNode(const Model& model, int cable, Vec2 point);
int nearestBeamNode(const Model& model, int beam, Vec2 point);
// A [[beam_node]] resolved to the node of its beam nearest its point.
PhaseChanges::BeamNodeChange beamNodeChange(const Model& model, const BeamNodeDefinition& definition);
void applyBeamNodeChange(Model& model, const PhaseChanges::BeamNodeChange& change);
// A cable's nodes and elements, or a bolt, into the model, not installed; its index.
int addCable(Model& model, const CableDefinition& definition);
int addBolt(Model& model, const BoltDefinition& definition);

// History subjects by position (initial configuration): the block's gridpoint nearest `point`,
// and the zone of the block that holds `point` (-1 when none does).
int nearestGridpoint(const Model& model, int block, Vec2 point);
int zoneAt(const Model& model, int block, Vec2 point);

}  // namespace vdec
