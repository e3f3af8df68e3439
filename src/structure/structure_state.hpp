#pragma once
// Structural support (NUREG/CR-5429 1.2.6, 1.4.4): beams of 2D frame elements, three degrees of
// freedom a node (two displacements and a rotation), masses lumped at the nodes, tied to the rock
// by normal and shear springs. Plain arrays, part of the Model; structure/beams.hpp runs them.
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec2.hpp"

namespace vdec {

// A [[beam_material]], per unit thickness: the section's properties over the out-of-plane
// spacing of the supports (a steel set every 1.5 m carries A / 1.5 per metre of tunnel).
struct BeamMaterial {
  std::string name;
  double young = 0.0;     // E, Pa
  double area = 0.0;      // A / spacing, m^2 per m
  double inertia = 0.0;   // I / spacing, m^4 per m
  double density = 0.0;   // kg/m^3 of the section's material
  // The ties to the rock, per unit length of beam: springs (N/m per m), Coulomb strength
  // (cohesion N/m per m, friction tan(phi)) and tensile strength (N/m per m); infinite
  // strengths leave a tie bonded.
  double tieNormalStiffness = 0.0;
  double tieShearStiffness = 0.0;
  double tieCohesion = INFINITY;
  double tieFriction = 0.0;
  double tieTension = INFINITY;
};

// Beam nodes, structure of arrays.
struct BeamNodes {
  std::vector<int> beam;
  std::vector<Vec2> initialPosition;
  std::vector<Vec2> position;
  std::vector<double> rotation;        // radians, counter-clockwise, from the input position
  std::vector<Vec2> velocity;          // at t - dt/2 before the motion stage, t + dt/2 after
  std::vector<double> angularVelocity;
  std::vector<Vec2> force;             // of the elements, summed each step
  std::vector<double> moment;
  std::vector<Vec2> tieForce;          // of its tie, each step
  std::vector<double> forceScale;      // the sum of the sizes of the forces on it this step (for the unbalanced ratio)
  std::vector<Vec2> appliedForce;      // constant loads
  std::vector<double> appliedMoment;
  std::vector<double> mass;            // rho A of half of each element at the node
  std::vector<double> rotaryInertia;   // mass times the square of the half elements' length / 3 (see beams.cpp)
  std::vector<double> length;          // tributary: half of each element at the node
  std::vector<std::uint8_t> fixed;     // DriveX, DriveY, DriveRotation: held at rest
  int size() const { return static_cast<int>(position.size()); }
};

// Frame elements between two nodes, structure of arrays; the forces of the last step for output.
struct BeamElements {
  std::vector<std::array<int, 2>> node;
  std::vector<int> beam;
  std::vector<double> restLength;
  std::vector<double> restAngle;       // of the chord node 0 -> node 1 at the input position
  std::vector<double> axialForce;      // N per m, tension positive
  std::vector<double> shearForce;      // N per m: (M0 + M1) / L, turning the chord counter-clockwise
  std::vector<std::array<double, 2>> endMoment;  // N m per m that the element exerts on its nodes' rotation, negated
  int size() const { return static_cast<int>(node.size()); }
};

// A node's springs to the rock: to a point fixed in a rigid block, or to a point of a zone of a
// deformable block (by its barycentric weights).
struct BeamTie {
  int node = -1;
  int block = -1;                      // the host block
  Vec2 local;                          // rigid host: the point relative to the centroid, unrotated
  int zone = -1;                       // deformable host: the zone and the point's weights in it
  std::array<double, 3> weight{};
  Vec2 force;                          // on the node, N per m (the host gets its opposite)
  double normalStiffness = 0.0;        // k_n times the node's length, N/m per m
  double shearStiffness = 0.0;
  double cohesion = INFINITY;          // times the node's length
  double friction = 0.0;
  double tension = INFINITY;           // times the node's length
  bool broken = false;                 // pulled off beyond its tensile strength: no force from then on
  bool slipping = false;               // at its shear strength in the last step
};

struct Beam {
  std::string name;
  int material = -1;
  int firstNode = 0, nodeCount = 0;
  int firstElement = 0, elementCount = 0;
  bool closed = false;                 // a ring: the last node joined to the first
  bool tied = false;                   // tied to the rock when installed
  // In the model: from the start for a [[beam]], from its phase's start for a [[phase.beam]],
  // until a phase frees it. A beam not installed has no forces, motion or ties.
  bool installed = false;
};

// A [[cable_material]], per unit thickness (the section, the grout's bond stiffness and strength
// over the out-of-plane spacing of the cables).
struct CableMaterial {
  std::string name;
  double young = 0.0;            // E, Pa
  double area = 0.0;             // A / spacing, m^2 per m
  double density = 0.0;          // kg/m^3
  double yieldTension = INFINITY;      // N per m: the axial force's bounds
  double yieldCompression = INFINITY;
  double bondStiffness = 0.0;    // k_bond / spacing, N/m per m of cable per m of thickness
  double bondStrength = INFINITY;  // s_bond / spacing, N per m of cable per m of thickness
  double spacing = 1.0;          // m, out of plane (a cable's pretension is divided by it)
};

// A straight cable of axial elements along `direction`; its nodes move along it only (no
// lateral restraint, 1.4.4.3), each bonded by the grout to the rock that holds it.
struct Cable {
  std::string name;
  int material = -1;
  Vec2 direction;                // unit, first point to last
  int firstNode = 0, nodeCount = 0;
  int firstElement = 0, elementCount = 0;
  double freeLength = 0.0;       // m from the first point: not grouted
  double pretension = 0.0;       // N per m of thickness, in the free length's elements when installed
  bool head = false;             // the first node held to the rock by a plate (no slip)
  bool installed = false;
};

// A point of the rock a support holds: in a rigid block's frame (local: from the centroid,
// unrotated), or at barycentric weights in a zone of a deformable block; block -1: none.
struct RockHold {
  int block = -1;
  Vec2 local;
  int zone = -1;
  std::array<double, 3> weight{};
};

// Cable nodes, structure of arrays. The grout's hold on the rock (block -1: a node outside the
// rock, ungrouted).
struct CableNodes {
  std::vector<int> cable;
  std::vector<Vec2> position;          // as installed
  std::vector<double> displacement;    // along the cable since installation
  std::vector<double> velocity;        // along the cable
  std::vector<double> force;           // of the elements, each step
  std::vector<double> forceScale;      // the sizes of the forces on it, each step
  std::vector<double> appliedForce;    // along the cable
  std::vector<double> mass;
  std::vector<double> length;          // tributary
  std::vector<std::uint8_t> fixed;     // held at rest along the cable
  std::vector<double> slip;            // along the cable, relative to the rock, since installation
  std::vector<double> bondForce;       // the grout's on the node, along the cable
  std::vector<std::uint8_t> slipping;  // at its strength in the last step
  using Hold = RockHold;
  std::vector<Hold> hold;
  int size() const { return static_cast<int>(cable.size()); }
};

struct CableElements {
  std::vector<std::array<int, 2>> node;
  std::vector<int> cable;
  std::vector<double> restLength;
  std::vector<double> axialForce;      // N per m, tension positive
  int size() const { return static_cast<int>(node.size()); }
};

// A [[bolt_material]], per unit thickness (stiffnesses and strengths over the out-of-plane
// spacing): local reinforcement across joints (1.4-36 to 1.4-51).
struct BoltMaterial {
  std::string name;
  double axialStiffness = 0.0;       // K_a, N/m per m
  double shearStiffness = 0.0;       // K_s, N/m per m
  double axialStrength = INFINITY;   // the axial force's bound, tension and compression, N per m
  double shearStrength = INFINITY;   // F_s of 1.4-40 (the bar's tensile capacity), N per m
  double activeLength = 0.0;         // m, across the joint
  bool crushing = true;              // the reduction factor r_f of 1.4-47
};

// A straight bolt (a [[bolt]]): a reinforcement at every joint its segment crosses.
struct Bolt {
  std::string name;
  int material = -1;
  Vec2 from, to;                     // the segment as given
  Vec2 direction;                    // unit, from -> to
  int firstCrossing = 0, crossingCount = 0;  // found when installed
  bool installed = false;
};

// A bolt's reinforcement at one joint, structure of arrays. Side 0 is the block the bolt leaves
// (going from -> to), side 1 the block it enters; the displacement is side 1's relative to side 0
// at the joint, since installation.
struct BoltCrossings {
  std::vector<int> bolt;
  std::vector<Vec2> point;                     // on the joint, where installed
  std::vector<Vec2> jointDirection;            // unit, along the joint there (side 0's edge)
  std::vector<std::array<RockHold, 2>> side;
  std::vector<Vec2> displacement;
  std::vector<double> axialDisplacement;       // u_axial of 1.4-47: increments along the active length, summed
  std::vector<double> axialForce;              // N per m, tension positive
  std::vector<double> shearForce;              // N per m, along the bolt's direction turned +90 degrees
  std::vector<std::uint8_t> broken;            // a side excavated: no force from then on
  int size() const { return static_cast<int>(bolt.size()); }
};

struct Structures {
  std::vector<BeamMaterial> materials;
  std::vector<Beam> beams;
  BeamNodes nodes;
  BeamElements elements;
  std::vector<BeamTie> ties;
  std::vector<CableMaterial> cableMaterials;
  std::vector<Cable> cables;
  CableNodes cableNodes;
  CableElements cableElements;
  std::vector<BoltMaterial> boltMaterials;
  std::vector<Bolt> bolts;
  BoltCrossings crossings;
  bool any() const { return !beams.empty() || !cables.empty() || !bolts.empty(); }
};

}  // namespace vdec
