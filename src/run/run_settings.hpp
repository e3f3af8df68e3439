#pragma once
// What a run is told: its stop criteria, its phases and the changes each makes at its start, and
// the solver settings (docs/user-manual/scene-format.md, [solver], [stop], [[phase]]).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/model.hpp"
#include "zone/excavation.hpp"

namespace vdec {

struct StopCriteria {
  long long cycles = -1;  // < 0: not set
  double time = -1.0;
  double ratio = -1.0;
};

// A joint material's strength changed at the start of a phase (Coulomb laws only).
struct JointStrengthChange {
  int material = -1;
  std::optional<double> tanFriction, cohesion, tension;
};

// A rigid block's degrees of freedom and loads changed at the start of a phase.
struct RigidBlockChange {
  int block = -1;
  std::uint8_t fix = 0;             // DriveX / DriveY / DriveRotation bits driven from now on
  std::uint8_t free = 0;            // bits released, moving on from their present velocity
  Vec2 velocity;                    // of the components in `fix` (zero: held still)
  double angularVelocity = 0.0;
  std::optional<Vec2> force;        // replaces the applied force
  std::optional<double> moment;     // replaces the applied moment
};

// What a phase changes before its first step. Unset members keep the state of the phase before.
struct PhaseChanges {
  std::optional<Vec2> gravity;
  std::vector<JointStrengthChange> joints;
  std::optional<double> massDamping;     // switches adaptive and local damping off
  std::optional<bool> adaptiveDamping;   // true switches local damping off
  std::optional<double> localDamping;    // alpha_L; > 0 switches mass and adaptive damping off, 0 switches it off
  std::vector<RigidBlockChange> blocks;
  std::vector<std::pair<int, MohrCoulombProperties>> blockStrengths;  // block material -> its new strength
  std::vector<ExcavationRegion> excavations;     // zones removed first, in order
  std::vector<std::string> freeBoundaries;       // names of active boundary conditions taken off
  std::vector<BoundaryCondition> boundaries;      // then applied, their histories from the phase's start
  bool resetDisplacements = false;       // displacement histories and outputs measured from here
  bool resetVelocities = false;
  bool staticSolve = false;  // after the changes, solve the elastic zones' equilibrium directly
  std::optional<bool> flow;  // fluid flow switched on (its domains from the initial field) or off
  std::vector<FlowBoundary> flowBoundaries;  // flow boundaries added, their histories from the phase's start
  std::vector<int> freeBeams;                 // beams taken out at the phase's start (indices)
  std::vector<int> installBeams;              // then installed, stress-free where the rock is then
  struct BeamNodeChange {
    int node = -1;
    Vec2 force;
    double moment = 0.0;
    std::uint8_t fix = 0;
  };
  std::vector<BeamNodeChange> beamNodes;      // loads added and degrees of freedom held
  std::vector<int> freeCables, freeBolts;     // taken out at the phase's start (indices)
  std::vector<int> installCables, installBolts;  // then installed, stress-free where the rock is then
  std::optional<BoundaryElementField> boundaryElements;  // then put in place, holding the zones' stress
  double heatTime = 0.0;  // s of thermal time advanced last, before the cycles
};

struct Phase {
  std::string name;
  StopCriteria stop;                 // counted from the phase's start
  bool requireEquilibrium = false;   // ending on cycles or time is then an error
  PhaseChanges changes;
};

struct RunSettings {
  double frac = 0.1;          // FRAC of 1.3-28
  // The zone step as a fraction of 1.3-25's estimate of the critical one (the estimate already
  // has a margin); for stability studies.
  double zoneFraction = 1.0;
  double massDamping = 0.0;   // alpha of 1.3-21, 1/s
  double stiffnessDamping = 0.0;  // beta of 1.3-22 on the joints' springs, s (Rayleigh with alpha)
  bool adaptiveDamping = false;  // alpha by the servo of 1.3-23 instead
  double localDamping = 0.0;     // alpha_L of local damping (motion_totals.hpp), instead of mass damping
  bool densityScaling = false;   // gridpoint inertial masses scaled to one step (1.3-32 to 1.3-34)
  bool staticSolve = false;      // start from the direct solution of the elastic zones (zone/direct_solve)
  double heatTime = 0.0;         // s of thermal time before the cycles of a run without phases
  StopCriteria stop;
  // Run in order; empty: one stage of the run, to `stop`.
  std::vector<Phase> phases;
  bool profile = false;
  bool progress = false;
  // Snapshots: the caller's writer is called at the start, every `snapshotEvery` cycles and at
  // the end (0: never).
  long long snapshotEvery = 0;
  std::function<void(const Model&)> snapshot;
};

}  // namespace vdec
