#pragma once
// A scene as plain definitions, one struct per section of the scene file
// (docs/user-manual/scene-format.md), before any model exists: what the reader (io/) parses a
// TOML scene into, and what tests and benchmarks write in code. Values are checked one by one
// where they are read; names are not yet resolved and nothing is placed or zoned. The builder
// (scene/scene_builder.hpp) resolves, checks against each other and makes the model.
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "boundary/time_function.hpp"
#include "core/model.hpp"
#include "geometry/block_cutting.hpp"
#include "geometry/polygon.hpp"
#include "geometry/zoning.hpp"
#include "run/cycle.hpp"
#include "scene/origin.hpp"
#include "zone/excavation.hpp"

namespace vdec {

struct ModelDefinition {
  Vec2 gravity;
  double rounding = 0.0;          // d of 1.3.3.2, m
  double contactTolerance = 0.0;  // 0: the rounding length
  std::string defaultJoint;       // "": the only joint material, if there is one
  Origin origin;
};

struct BlockMaterialDefinition {
  BlockMaterial material;
  Origin origin;
};

struct JointMaterialDefinition {
  JointMaterial material;
  Origin origin;
};

// How a block is zoned; Rigid: not at all.
struct ZoningDefinition {
  enum class Kind { Rigid, Structured, Unstructured, Annulus };
  Kind kind = Kind::Rigid;
  int nx = 0, ny = 0;     // Structured: cells along the first and second side
  double maxEdge = 0.0;   // Unstructured
  AnnulusSpec annulus;    // Annulus: the block's outline too
  Origin origin;          // the zoning or annulus table
};

struct BlockDefinition {
  std::string name;
  std::string material;
  Polygon vertices;  // counter-clockwise; empty for an annulus
  ZoningDefinition zoning;
  // A rigid block's driven degrees of freedom (DrivenDof bits), their velocity, its loads.
  std::uint8_t fix = 0;
  Vec2 velocity, force;
  double angularVelocity = 0.0, moment = 0.0;
  std::optional<TimeFunction> velocityHistory;  // scales the velocity of the fixed components
  bool simplyDeformable = false;  // kind = "simply-deformable": rigid motion and uniform strain
  Origin origin;
};

struct RegionDefinition {
  RegionSpec region;  // cut into blocks named region.1, region.2, ...
  std::string material;
  bool simplyDeformable = false;  // kind = "simply-deformable" for every block cut from it
  Origin origin;
};

// [[excavation]] before the run, or [[phase.excavation]] at a phase's start.
struct ExcavationDefinition {
  ExcavationRegion region;
  Origin origin;
};

// A closed range [lo, hi] of a coordinate, or everything.
struct CoordinateRange {
  double lo = -INFINITY, hi = INFINITY;
  bool holds(double v, double slack) const { return v >= lo - slack && v <= hi + slack; }
};

// A boundary stress tabulated against the polar angle (degrees, about the boundary's centre).
struct StressTable {
  std::string file;
  std::vector<double> angle;  // increasing
  std::vector<std::array<double, 3>> stress;  // sxx, syy, sxy
  // Linear between rows; an angle outside the table is an error on `origin`'s stress_table.
  std::array<double, 3> at(double angleDegrees, const Origin& origin) const;
};

// One [[boundary]] (or [[phase.boundary]]) table: which gridpoints of which deformable block, and
// what it does to them: drives them (fix, velocities), loads their edges (stress, pressure,
// stress table) or absorbs waves there (viscous).
struct BoundaryDefinition {
  std::string name;  // "": cannot be freed by a phase
  std::string block;
  CoordinateRange x, y, r, angle;  // on the initial positions; r and angle about `centre`
  Vec2 centre;
  bool viscous = false;
  bool freeField = false;  // a free-field column beside the selected (vertical) side; `block` optional
  Vec2 inputVelocity;  // viscous, free field: the incident particle velocity of a wave entering at the base
  std::string material;  // viscous, free field: the medium beyond the boundary, whose impedances the dashpots take
  std::uint8_t fix = 0;           // DriveX / DriveY
  std::uint8_t velocityBits = 0;  // components driven at `velocity`
  Vec2 velocity;
  bool loaded = false;  // stress, pressure (stress -p, -p, 0) or a stress table
  std::array<double, 3> stress{}, gradientX{}, gradientY{};  // sxx, syy, sxy and their gradients
  std::optional<StressTable> stressTable;
  std::optional<TimeFunction> history;  // scales the velocities or the stress
  Origin origin;
};

// A [boundary_elements] table: the elastic region beyond the outer boundary the selection picks.
struct BoundaryElementsDefinition {
  double young = 0.0, poisson = 0.0;
  bool halfPlane = false;
  double surfaceY = 0.0;
  std::string block;                 // "": every deformable block
  CoordinateRange x, y, r, angle;    // on the initial positions, as a [[boundary]]'s
  Vec2 centre;
  Origin origin;
};

// [heat]: the thermal solution's settings (1.4.3).
struct HeatDefinition {
  double initialTemperature = 0.0;
  double theta = 0.0;   // 0 explicit, 0.5 Crank-Nicolson, 1 backward Euler
  double step = 0.0;    // s; 0: the explicit default, 0.95 of its stable step
  double time = 0.0;    // s of thermal time before the cycles of a run without phases
  Origin origin;
};

// [[heat_boundary]]: a fixed temperature on the selected gridpoints, or a flux or convection on
// the outline edges between them.
struct HeatBoundaryDefinition {
  enum class Kind { Temperature, Flux, Convection, Radiation } kind = Kind::Temperature;
  double value = 0.0;    // the temperature, the flux (W/m^2 into the body), h (W/(m^2 K)) or the emissivity
  double ambient = 0.0;  // convection's or radiation's ambient temperature
  HeatDecay decay;       // flux only
  std::optional<TimeFunction> history;  // temperature or flux: the value times f(t), t the thermal time
  std::string block;     // "": every deformable block
  CoordinateRange x, y, r, angle;
  Vec2 centre;
  Origin origin;
};

// [[heat_source]]: a line source at a gridpoint, or a volumetric source over a block.
struct HeatSourceDefinition {
  bool atPoint = true;
  Vec2 point;
  std::string block;
  double power = 0.0;    // W/m at a point, W/m^3 over a block
  HeatDecay decay;
  Origin origin;
};

struct InitialStressDefinition {
  std::array<double, 4> stress{};  // sxx, syy, sxy, szz at the origin
  std::array<double, 4> gradientX{}, gradientY{};
  Origin origin;
};

// A plane P or S wave already in the model at the start: a Gaussian pulse travelling along
// `direction`, for wave problems whose input is no boundary's (oblique incidence).
struct InitialWaveDefinition {
  bool shear = false;      // "S": particle motion across the direction of travel; "P": along it
  double directionDegrees = 0.0;
  Vec2 centre;
  double amplitude = 0.0;  // peak particle velocity, m/s
  double width = 0.0;      // Gaussian half-width along the direction of travel, m
  double frontWidth = INFINITY;  // along the front, m (infinite: a plane wave without envelope)
  std::string block;       // "": every deformable block
  Origin origin;
};

// [fluid]: the fluid in the joints (1.4.2).
struct FluidDefinition {
  FluidProperties fluid;    // minDomainArea 0: the builder's default
  bool flowing = true;      // from the start; a phase's `flow` switches it
  Origin origin;
};

// A [[flow_boundary]] (or [[phase.flow_boundary]]).
struct FlowBoundaryDefinition {
  FlowBoundary boundary;
  std::optional<TimeFunction> history;
  Origin origin;
};

// A [[beam_material]]: the section's properties as given (per support); the builder divides
// them by the spacing.
struct BeamMaterialDefinition {
  BeamMaterial material;
  double spacing = 1.0;
  Origin origin;
};

// A [[beam]]: a polyline (or an arc) cut into frame elements.
struct BeamDefinition {
  std::string name;
  std::string material;
  std::vector<Vec2> points;   // the polyline's corners, or the arc's nodes
  int elements = 1;           // per segment of the polyline; for an arc, in all
  bool closed = false;
  bool tied = false;
  Vec2 load;                  // uniform, N/m per m of beam (per unit thickness)
  Origin origin;
};

// A [[cable_material]]: as given (per cable); the builder divides area, bond stiffness and bond
// strength by the spacing.
struct CableMaterialDefinition {
  CableMaterial material;
  double spacing = 1.0;
  Origin origin;
};

// A [[cable]]: a straight cable between two points, cut into equal elements.
struct CableDefinition {
  std::string name;
  std::string material;
  Vec2 from, to;
  int elements = 1;
  double freeLength = 0.0;   // m from the first point left ungrouted
  double pretension = 0.0;   // N per cable, on the free length, reacted by the head plate
  bool head = false;         // a plate holds the first node to the rock there
  Origin origin;
};

// A [[cable_node]]: the node of a cable nearest a point, loaded along the cable or held.
struct CableNodeDefinition {
  std::string cable;
  Vec2 point;
  double force = 0.0;
  bool fix = false;
  Origin origin;
};

// A [[bolt_material]]: as given (per bolt); the builder divides stiffnesses and strengths by the
// spacing.
struct BoltMaterialDefinition {
  BoltMaterial material;
  double spacing = 1.0;
  Origin origin;
};

// A [[bolt]]: a straight segment; a reinforcement at each joint it crosses.
struct BoltDefinition {
  std::string name;
  std::string material;
  Vec2 from, to;
  Origin origin;
};

// A [[beam_node]]: the node of a beam nearest a point, loaded or held.
struct BeamNodeDefinition {
  std::string beam;
  Vec2 point;
  Vec2 force;
  double moment = 0.0;
  std::uint8_t fix = 0;
  Origin origin;
};

struct JointAssignmentDefinition {
  std::array<std::string, 2> blocks;
  std::string joint;
  Origin origin;
};

struct HistoryDefinition {
  std::string name;
  std::string quantity;              // as in docs/user-manual/histories.md, e.g. "block.x"
  std::string block;                 // block, gridpoint and zone quantities
  std::string beam;                  // beam quantities
  std::string cable;                 // cable quantities
  std::string bolt;                  // bolt quantities
  std::array<std::string, 2> blocks; // joint quantities
  std::optional<Vec2> point;         // gridpoint and zone quantities
  Vec2 from, to;                     // line quantities (heat.flow)
  int every = 1;
  Origin origin;
};

struct JointStrengthDefinition {
  std::string material;
  std::optional<double> frictionDegrees, cohesion, tension;
  Origin origin;
};

struct BlockStrengthDefinition {
  std::string material;
  MohrCoulombProperties strength;
  Origin origin;
};

struct RigidBlockChangeDefinition {
  std::string block;
  RigidBlockChange change;  // change.block is resolved by the builder
  Origin origin;
};

struct PhaseDefinition {
  std::string name;
  StopCriteria stop;
  bool requireEquilibrium = false;
  std::optional<Vec2> gravity;
  std::optional<double> massDamping;
  std::optional<bool> adaptiveDamping;
  std::optional<double> localDamping;  // 0: off
  bool resetDisplacements = false, resetVelocities = false;
  bool staticSolve = false;
  std::vector<JointStrengthDefinition> jointStrengths;
  std::vector<std::string> free;  // names of active boundaries taken off
  std::vector<BlockStrengthDefinition> blockStrengths;
  std::vector<RigidBlockChangeDefinition> blocks;
  std::vector<ExcavationDefinition> excavations;
  std::vector<BoundaryDefinition> boundaries;
  std::optional<bool> flow;  // fluid flow on or off from the phase's start
  std::vector<FlowBoundaryDefinition> flowBoundaries;
  std::vector<BeamDefinition> beams;          // installed at the phase's start
  std::vector<BeamNodeDefinition> beamNodes;  // loads and holds on beams, from the phase's start
  std::vector<CableDefinition> cables;        // installed at the phase's start
  std::vector<BoltDefinition> bolts;          // installed at the phase's start
  std::optional<BoundaryElementsDefinition> boundaryElements;  // put in place at the phase's start
  std::optional<double> heatTime;  // s of thermal time advanced at the phase's start
  Origin origin;
};

struct SceneDefinition {
  std::string title;
  ModelDefinition model;
  std::vector<BlockMaterialDefinition> blockMaterials;
  std::vector<JointMaterialDefinition> jointMaterials;
  // [solver], [stop] and [output]; its phases are made from `phases` below.
  RunSettings settings;
  Origin solver;
  std::vector<BlockDefinition> blocks;
  std::vector<RegionDefinition> regions;  // cut after the blocks, their pieces listed after them
  std::vector<ExcavationDefinition> excavations;
  std::vector<BoundaryDefinition> boundaries;
  std::optional<InitialStressDefinition> initialStress;
  std::optional<BoundaryElementsDefinition> boundaryElements;
  std::vector<InitialWaveDefinition> initialWaves;
  std::optional<HeatDefinition> heat;
  std::vector<HeatBoundaryDefinition> heatBoundaries;
  std::vector<HeatSourceDefinition> heatSources;
  std::optional<FluidDefinition> fluid;
  std::vector<FlowBoundaryDefinition> flowBoundaries;
  std::vector<BeamMaterialDefinition> beamMaterials;
  std::vector<BeamDefinition> beams;
  std::vector<BeamNodeDefinition> beamNodes;
  std::vector<CableMaterialDefinition> cableMaterials;
  std::vector<CableDefinition> cables;
  std::vector<CableNodeDefinition> cableNodes;
  std::vector<BoltMaterialDefinition> boltMaterials;
  std::vector<BoltDefinition> bolts;
  std::vector<JointAssignmentDefinition> jointAssignments;
  std::vector<HistoryDefinition> histories;
  std::vector<PhaseDefinition> phases;
  Origin root;  // the scene as a whole, for what is missing from it
  std::vector<std::string> warnings;
};

}  // namespace vdec
