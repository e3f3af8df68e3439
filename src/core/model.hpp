#pragma once
// The state of a vdec model: plain arrays indexed by small integer ids. Everything a stage
// reads or writes lives here; stages own no state of their own beyond scratch buffers.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "bem/far_field_state.hpp"
#include "boundary/time_function.hpp"
#include "flow/flow_state.hpp"
#include "motion/strain_modes_state.hpp"
#include "structure/structure_state.hpp"
#include "thermal/heat_state.hpp"
#include "zone/mohr_coulomb.hpp"
#include "core/vec2.hpp"

namespace vdec {

struct BlockMaterial {
  std::string name;
  double density = 0.0;  // kg/m^3 (unit thickness: mass per metre out of plane)
  // Isotropic elasticity of the intact rock, needed by deformable blocks (1.4.6.7); zero for a
  // material only rigid blocks use.
  double bulk = 0.0;     // K, Pa
  double shear = 0.0;    // G, Pa
  bool elastic() const { return bulk > 0.0 && shear > 0.0; }
  // Mohr-Coulomb plasticity of the intact rock (1.4.6), when given.
  bool plastic = false;
  MohrCoulombProperties mohrCoulomb;
  // Heat conduction (1.4.3): conductivities along the material's axis at conductivityAngle
  // (radians, counter-clockwise from x) and across it, W/(m K); specific heat J/(kg K). Zero when
  // not given.
  double conductivityX = 0.0, conductivityY = 0.0, conductivityAngle = 0.0;
  double specificHeat = 0.0;
  double expansion = 0.0;  // linear thermal expansion alpha, 1/degree; beta = 3 alpha (1.4-17)
};

// NUREG/CR-5429 1.4.7: model #1 (point contact, forces), #2 (Coulomb slip), #5 (Coulomb slip
// with loss of cohesion and tensile strength at first failure).
enum class JointLaw : std::uint8_t { PointContact, CoulombSlip, CoulombFracture, ContinuouslyYielding };

struct JointMaterial {
  std::string name;
  JointLaw law = JointLaw::CoulombSlip;
  double kn = 0.0;           // Pa/m (joint laws) or N/m (point contact)
  double ks = 0.0;
  double tanFriction = 0.0;  // tan(phi)
  double cohesion = 0.0;     // Pa (joint laws only)
  double tension = 0.0;      // Pa, tensile strength T0 (joint laws only)
  double tanDilation = 0.0;  // tan(psi)
  // Continuously yielding (1.4-137 to 1.4-146). kn and ks above are the stiffnesses at zero
  // normal stress, which set the time step; the stress-dependent ones, an sn^en and as sn^es,
  // take over where they are larger.
  double knCoefficient = 0.0;    // an, Pa^(1-en)/m
  double knExponent = 0.0;       // en
  double ksCoefficient = 0.0;    // as, Pa^(1-es)/m
  double ksExponent = 0.0;       // es
  double friction = 0.0;         // phi, the basic friction angle, rad
  double initialFriction = 0.0;  // phi_eff at the start, rad
  double roughness = 0.0;        // R, m
  // Fracture flow (1.4-7 to 1.4-9): the hydraulic aperture at zero normal stress, its bounds,
  // and the permeability of the point-contact law (m^2/(Pa s) per unit thickness). NaN: not
  // given (the builder requires them with [fluid] and refuses them without).
  double aperture = NAN;
  double residualAperture = NAN;
  double maxAperture = INFINITY;
  double pointPermeability = NAN;
};

// Degrees of freedom of a rigid block or gridpoint that are driven (velocity prescribed, zero when
// fixed) rather than integrated from the forces. Excavated marks a gridpoint whose zones were all
// excavated during the run: it is held at rest (DriveX | DriveY) and belongs to no zone; and a
// rigid block a phase excavated: held at rest (DriveAll), unloaded, and left out of contact
// detection, so that it touches nothing (its arrays stay, so that block ids do not change).
enum DrivenDof : std::uint8_t { DriveX = 1, DriveY = 2, DriveRotation = 4, DriveAll = 7, Excavated = 8 };

// Rigid blocks, structure of arrays. Vertices of block b are firstVertex[b] ..
// firstVertex[b] + vertexCount[b] - 1 in the vertex arrays, counter-clockwise.
struct Blocks {
  std::vector<std::string> name;
  std::vector<int> material;
  std::vector<int> firstVertex;
  std::vector<int> vertexCount;
  std::vector<double> mass;
  std::vector<double> inertia;        // about the centroid
  std::vector<std::uint8_t> driven;   // DrivenDof bits
  std::vector<double> boundingRadius; // largest centroid-to-vertex distance
  std::vector<Vec2> initialCentroid;
  std::vector<Vec2> centroid;
  std::vector<double> rotation;       // radians, counter-clockwise, from the input position
  std::vector<Vec2> velocity;         // at t - dt/2 before the motion stage, t + dt/2 after
  std::vector<double> angularVelocity;
  std::vector<Vec2> force;            // contact force sum of the current step (gravity excluded)
  std::vector<double> moment;
  std::vector<Vec2> appliedForce;     // constant user loads
  std::vector<double> appliedMoment;
  // Viscous boundaries' forces and moments of the step (per-step accumulators, empty without
  // viscous edges on rigid blocks): the dashpots' (which dissipate) and the incoming wave's
  // (a load).
  std::vector<Vec2> dashpotForce;
  std::vector<double> dashpotMoment;
  std::vector<Vec2> boundaryForce;
  std::vector<double> boundaryMoment;
  // A deformable block moves through its gridpoints and zones; the rigid-body fields above
  // then describe its input polygon only, and rigid motion leaves it alone.
  std::vector<std::uint8_t> deformable;
  // A time function (index into Model::timeFunctions, -1 for none) scaling the input velocity
  // of the driven degrees of freedom: v = inputVelocity f(t).
  std::vector<int> velocityHistory;
  std::vector<Vec2> inputVelocity;
  std::vector<double> inputAngularVelocity;

  int size() const { return static_cast<int>(name.size()); }
  bool movesFreely(int b) const { return (driven[b] & DriveAll) != DriveAll && !deformable[b]; }
  bool excavated(int b) const { return (driven[b] & Excavated) != 0; }
};

// Gridpoints of deformable blocks (1.3.3.3): the nodes of their constant-strain triangles.
struct Gridpoints {
  std::vector<int> block;
  std::vector<Vec2> initialPosition;
  std::vector<Vec2> position;
  std::vector<Vec2> velocity;        // at t - dt/2 before the motion stage, t + dt/2 after
  std::vector<Vec2> tractionForce;   // boundary tractions of the current step (a per-step accumulator)
  std::vector<double> mass;          // inertial mass (density-scaled when asked, 1.3-32)
  std::vector<double> gravityMass;   // rho A / 3 from each zone around it
  std::vector<double> stiffness;     // k_i of 1.3-26 and 1.3-27 from the zones around it
  std::vector<std::uint8_t> driven;  // DriveX / DriveY: velocity prescribed (zero when fixed)
  // The forces contacts put on the gridpoint this step (1.3.3.4.2), gathered in contact order so
  // that the sum does not depend on threads; empty when no deformable block can touch another.
  std::vector<Vec2> contactForce;
  std::vector<Vec2> dashpotForce;    // viscous boundaries' force of the step; empty without them

  int size() const { return static_cast<int>(block.size()); }
};

// Constant-strain triangles (zones) of deformable blocks, counter-clockwise gridpoint ids.
// Stresses are tension positive; szz is tracked for plane strain.
struct Zones {
  std::vector<std::array<int, 3>> gridpoint;
  std::vector<int> block;
  std::vector<int> material;
  std::vector<double> sxx, syy, sxy, szz;
  std::vector<std::uint8_t> plasticState;  // PlasticState bits
  // The forces the zones put on their gridpoints this step, one per zone corner, stored in
  // gridpoint order: gridpoint i's are at [GridpointZones::start[i], start[i + 1]), in zone order,
  // and zone z's corner c is at GridpointZones::place[3 z + c]. The zone loop writes each where
  // its gridpoint reads it, so the gridpoint loop reads them in one stream and sums them in a
  // fixed order, whatever the split of the zone loop over threads.
  std::vector<Vec2> nodalForce;

  int size() const { return static_cast<int>(gridpoint.size()); }
};

// Where each gridpoint's share of the zone forces is kept (Zones::nodalForce).
struct GridpointZones {
  std::vector<int> start;  // size gridpoints + 1: gridpoint i's corners are [start[i], start[i + 1])
  std::vector<int> place;  // size 3 zones: the index of zone z's corner c is place[3 z + c]
};

// A boundary edge of a deformable block carrying a traction: the stress tensor given at the
// edge (pressure is sxx = syy = -p, sxy = 0) times the current outward normal and length.
struct LoadedEdge {
  int from = -1, to = -1;  // gridpoints, counter-clockwise along the block boundary
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  int history = -1;        // Model::timeFunctions entry scaling the stress, -1: constant
  double timeOrigin = 0.0; // the history is f(t - timeOrigin): a phase's boundary starts with it
  int source = -1;         // the Model::boundaryConditions entry it belongs to
};

// A gridpoint component driven at a velocity that varies in time: value times f(t).
struct DrivenVelocity {
  int gridpoint = -1;
  int component = 0;       // 0 x, 1 y
  double value = 0.0;
  int history = -1;
  double timeOrigin = 0.0;
  int source = -1;
};

// A viscous boundary edge (Lysmer and Kuhlemeyer, 1.3-35, 1.3-36): normal and shear dashpots of
// the impedances rho C_p and rho C_s of the block's material, per unit length of the edge; and,
// for a wave coming in through it, the incident particle velocity, entered as the traction
// 2 rho C (v_in . n) n (P) and 2 rho C_s (v_in . t) t (S).
struct ViscousEdge {
  int from = -1, to = -1;        // gridpoints, counter-clockwise along the block boundary
  double normalImpedance = 0.0;  // rho C_p, Pa s/m
  double shearImpedance = 0.0;   // rho C_s
  int source = -1;
  Vec2 inputVelocity;            // incident particle velocity (m/s), times the history if any
  int history = -1;              // Model::timeFunctions entry scaling it; -1: constant
  double timeOrigin = 0.0;       // the history is f(t - timeOrigin)
};

// A viscous boundary edge of a rigid block: as ViscousEdge, between two of its vertices (ids into
// Vertices), the dashpots acting on the block's velocity along the edge.
struct RigidViscousEdge {
  int block = -1;
  int from = -1, to = -1;        // vertices, counter-clockwise along the block boundary
  double normalImpedance = 0.0;
  double shearImpedance = 0.0;
  int source = -1;
  Vec2 inputVelocity;
  int history = -1;
  double timeOrigin = 0.0;
};

// An outline edge of a deformable block coupled to a free-field column: dashpots of the block
// material's impedances on the velocity relative to the column's (1.3-41).
struct FreeFieldEdge {
  int from = -1, to = -1;        // gridpoints, counter-clockwise along the block boundary
  double normalImpedance = 0.0;  // rho C_p, Pa s/m
  double shearImpedance = 0.0;   // rho C_s
  // Where the edge sits on the column, found once: the column elements it spans, and for each
  // end the column node at or below it and the weight of the node above (linear interpolation).
  int firstElement = 0, lastElement = 0;
  std::array<int, 2> node{};
  std::array<double, 2> weight{};
};

// A one-dimensional free-field column (1.3.6.3) beside a vertical lateral boundary: the motion of
// the unbounded layered medium under a vertically travelling wave, computed by the same explicit
// scheme, and applied to the model's side as the column's stress plus dashpots on the velocity
// relative to the column's. The column carries the dynamic motion only, from rest and zero
// stress when it comes on; the side's static reactions of that moment are kept as loads.
struct FreeFieldColumn {
  std::vector<double> nodeY;      // initial heights of the nodes, bottom to top: those of the side's gridpoints
  std::vector<double> nodeMass;   // rho (h_below + h_above) / 2, per unit width, kg/m
  std::vector<Vec2> nodeVelocity; // at t - dt/2 before the stage, t + dt/2 after
  // Element j lies between nodes j and j + 1: its block material and dynamic stress (tension positive).
  std::vector<int> elementMaterial;
  std::vector<double> sxx, syy, sxy;
  double baseNormalImpedance = 0.0, baseShearImpedance = 0.0;  // dashpots of the column's base
  Vec2 inputVelocity;             // the incident wave at the base, as a viscous boundary's
  int history = -1;
  double timeOrigin = 0.0;
  std::vector<FreeFieldEdge> edges;
  std::vector<int> reactionGridpoint;  // static reactions kept on the side's gridpoints
  std::vector<Vec2> reaction;
  int source = -1;
};

// One [[boundary]] table (of the scene or of a phase) resolved to gridpoints and edges: what
// boundary/boundary_conditions applies to a model and takes off it again.
struct BoundaryCondition {
  std::string name;                  // "" for an unnamed one, which cannot be freed
  std::vector<int> gridpoints;       // driven: fixed or at a velocity
  std::uint8_t fix = 0;              // DriveX / DriveY bits fixed (velocity zero)
  std::uint8_t velocityBits = 0;     // DriveX / DriveY bits at a given velocity
  Vec2 velocity;                     // of the velocityBits components (times the history, if any)
  int history = -1;
  std::vector<LoadedEdge> edges;     // loaded by a stress or pressure
  std::vector<ViscousEdge> dashpots; // viscous
  std::vector<RigidViscousEdge> rigidDashpots;  // viscous, on a rigid block
  std::vector<FreeFieldColumn> freeField;  // one column, or none
  bool active = true;
};

// What the contact geometry reads of a vertex at its present place, in one 64-byte record: a
// contact's feature walk and length touch one cache line per vertex instead of five.
struct VertexGeometry {
  Vec2 position;
  // The boundary edge from the vertex to the next, kept with the position so that contact
  // geometry needs no square root or modulo per contact: unit direction and length.
  Vec2 edgeDirection;
  // Rounded corner (1.3.3.2, Fig. 1.3-2d): arc tangent to both edges at the rounding length d
  // from the vertex; centre on the bisector, radius d tan(alpha/2).
  Vec2 arcCentre;
  double edgeLength = 0.0;
  double arcRadius = 0.0;
};

// Boundary vertices of all blocks. For a rigid block they move with its rigid motion;
// the local fields are relative to the centroid at zero rotation. A deformable block's
// vertices are the gridpoints of its outer outline and move with them.
struct Vertices {
  std::vector<int> block;
  std::vector<int> gridpoint;  // the gridpoint a deformable block's vertex is; -1 on a rigid block
  // A vertex where the outline runs on nearly straight (or turns inwards): a point with no
  // rounding, arc radius 0, whose neighbouring edges reach right up to it (see contact_geometry).
  std::vector<std::uint8_t> pointCorner;
  std::vector<VertexGeometry> geometry;
  std::vector<Vec2> localPosition;
  std::vector<Vec2> localArcCentre;
  std::vector<Vec2> localEdgeDirection;
  std::vector<int> next;
  std::vector<int> prev;

  int size() const { return static_cast<int>(block.size()); }
};

enum class FeatureKind : std::uint8_t { Edge, Corner };

// One corner of block A touching block B. Joint laws carry stresses (1.4-132 to 1.4-136 in
// the stress form of MODEL-EQUATIONS.md) and the forces are stress times contact length; for
// the point-contact law the "stresses" are forces and L = 1.
struct Contact {
  int corner = -1;          // vertex of block A
  int blockA = -1;
  int blockB = -1;
  int feature = -1;         // vertex id on B: edge (feature, next) or corner `feature`
  FeatureKind featureKind = FeatureKind::Edge;
  int joint = -1;           // joint material
  double overlap = 0.0;     // geometric, positive when the rounded shapes interpenetrate
  double length = 0.0;      // contact length L (1.3-2), m
  double elasticNormalStress = 0.0;  // what the normal spring alone would carry (< 0 in tension or open)
  double normalStress = 0.0;         // sn, compression positive
  double shearStress = 0.0;          // tau, along tangent t = (n.y, -n.x)
  double normalDisplacement = 0.0;   // accumulated, closing positive
  double shearDisplacement = 0.0;    // accumulated, along t
  // The reading of the motion clock (the running sum of the largest vertex displacement of each
  // step) below which an open contact cannot have closed: it is not evaluated until then.
  double closableAt = 0.0;
  double springEnergy = 0.0;  // J/m stored in the springs at the last evaluation (0 while open)
  bool open = false;        // separated, or broken in tension and not closed again
  bool intact = true;       // model #5: cohesion and tensile strength not yet destroyed
  bool slipping = false;
  bool skipped = false;     // open, and left out of the last step's evaluation (see closableAt)
};

// The state a continuously yielding joint adds to a contact: effective friction phi_eff (rad),
// plastic shear displacement, the stress ratio r of the last shear reversal and the last shear
// direction. Kept beside the contacts rather than in them, so that scenes without this law
// stream no bytes for it through the contact loop.
struct YieldingState {
  double effectiveFriction = 0.0;
  double plasticShear = 0.0;
  double reversalRatio = 0.0;
  std::int8_t shearDirection = 0;
};

// The weight that turns a contact's stresses into forces (Fn = w sn, Fs = w tau): the contact
// length for the joint laws, 1 for the point-contact law.
inline double contactWeight(const JointMaterial& j, const Contact& c) {
  return j.law == JointLaw::PointContact ? 1.0 : c.length;
}

// A Gaussian pulse of a plane P or S wave in the deformable blocks at the start
// (initial_wave.hpp places it once the step is known).
struct InitialWave {
  bool shear = false;
  Vec2 direction;            // of travel, unit
  Vec2 centre;               // of the pulse at t = 0
  double amplitude = 0.0;    // peak particle velocity, m/s
  double width = 0.0;        // Gaussian half-width along the direction, m
  double frontWidth = 0.0;   // along the front, m (infinite: none)
  int block = -1;            // -1: every deformable block
};

struct Model {
  std::vector<BlockMaterial> blockMaterials;
  std::vector<JointMaterial> jointMaterials;
  Blocks blocks;
  Vertices vertices;
  Gridpoints gridpoints;
  Zones zones;
  GridpointZones gridpointZones;
  std::vector<LoadedEdge> loadedEdges;
  std::vector<DrivenVelocity> drivenVelocities;  // only those with a time history
  std::vector<BoundaryCondition> boundaryConditions;  // all ever applied, freed ones inactive
  std::vector<ViscousEdge> viscousEdges;
  std::vector<RigidViscousEdge> rigidViscousEdges;
  std::vector<FreeFieldColumn> freeFields;  // those in force
  std::vector<InitialWave> initialWaves;
  std::vector<TimeFunction> timeFunctions;
  FlowState flow;  // fluid in the joints, when the scene has a [fluid] table
  Structures structures;  // beams and their ties to the rock
  BoundaryElementField boundaryElements;  // the far field beyond the outer boundary, when the scene has one
  HeatField heat;  // conduction in the zones, when the scene has a [heat] table
  StrainModes strainModes;  // the simply-deformable blocks' strains
  // The outline edges of deformable blocks (outer boundaries and holes), each directed with the
  // block on its left: gridpoints from -> to.
  struct BoundaryEdge {
    int block = -1, from = -1, to = -1;
  };
  std::vector<BoundaryEdge> boundaryEdges;
  std::vector<Contact> contacts;
  // Parallel to contacts when a joint material is continuously yielding, else empty.
  std::vector<YieldingState> yieldingStates;
  // The per-step force accumulators (block force and moment, gridpoint contact and traction
  // forces), zeroed in one place at the start of every step before any stage adds to them.
  void clearStepForces() {
    std::fill(blocks.force.begin(), blocks.force.end(), Vec2{});
    std::fill(blocks.moment.begin(), blocks.moment.end(), 0.0);
    std::fill(blocks.dashpotForce.begin(), blocks.dashpotForce.end(), Vec2{});
    std::fill(blocks.dashpotMoment.begin(), blocks.dashpotMoment.end(), 0.0);
    std::fill(blocks.boundaryForce.begin(), blocks.boundaryForce.end(), Vec2{});
    std::fill(blocks.boundaryMoment.begin(), blocks.boundaryMoment.end(), 0.0);
    std::fill(gridpoints.contactForce.begin(), gridpoints.contactForce.end(), Vec2{});
    std::fill(gridpoints.tractionForce.begin(), gridpoints.tractionForce.end(), Vec2{});
    std::fill(gridpoints.dashpotForce.begin(), gridpoints.dashpotForce.end(), Vec2{});
    std::fill(strainModes.force.begin(), strainModes.force.end(), Sym2{});
  }
  bool hasYieldingJoints() const {
    for (const JointMaterial& j : jointMaterials)
      if (j.law == JointLaw::ContinuouslyYielding) return true;
    return false;
  }
  // Joint material per unordered block pair where the scene assigns one; else defaultJoint.
  std::vector<std::pair<std::pair<int, int>, int>> jointAssignments;
  int defaultJoint = -1;

  Vec2 gravity;
  double roundingLength = 0.0;     // d
  double contactTolerance = 0.0;   // gap below which a contact exists
  double time = 0.0;
  long long cycle = 0;

  int jointMaterialFor(int a, int b) const;
  double normalForce(const Contact& c) const { return contactWeight(jointMaterials[c.joint], c) * c.normalStress; }
  double shearForce(const Contact& c) const { return contactWeight(jointMaterials[c.joint], c) * c.shearStress; }
  // A loaded edge's force now: its stress, times the history at the present time, on the edge's
  // current outward normal times length, (dy, -dx) of a counter-clockwise edge.
  Vec2 loadedEdgeForce(const LoadedEdge& e) const {
    const Vec2 d = gridpoints.position[e.to] - gridpoints.position[e.from];
    const Vec2 nL{d.y, -d.x};
    const double scale = e.history < 0 ? 1.0 : timeFunctions[e.history](time - e.timeOrigin);
    return scale * Vec2{e.sxx * nL.x + e.sxy * nL.y, e.sxy * nL.x + e.syy * nL.y};
  }
};

// The dashpot force per unit length of impedances zn (along the normal n) and zs (along the
// tangent t) on the velocity v: zn (v . n) n + zs (v . t) t (Lysmer and Kuhlemeyer, 1.3-35).
inline Vec2 dashpotTraction(double zn, double zs, Vec2 v, Vec2 n, Vec2 t) {
  return zn * dot(v, n) * n + zs * dot(v, t) * t;
}

}  // namespace vdec
