#pragma once
// Histories: named time series of a block, a joint (all contacts between two blocks) or the
// whole model, sampled every `every` cycles.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/model.hpp"
#include "thermal/heat.hpp"

namespace vdec {

enum class HistoryQuantity {
  BlockX, BlockY, BlockDisplacementX, BlockDisplacementY, BlockVelocityX, BlockVelocityY,
  BlockRotation, BlockAngularVelocity,
  JointNormalForce, JointShearForce, JointNormalStress, JointShearStress,
  JointNormalDisplacement, JointShearDisplacement, JointLength, JointContacts,
  JointEffectiveFriction, JointPlasticShear,
  UnbalancedRatio, LargestUnbalancedForce, KineticEnergy, StrainEnergy, EnergyRatio,
  GridpointDisplacementX, GridpointDisplacementY, GridpointVelocityX, GridpointVelocityY,
  ZoneSxx, ZoneSyy, ZoneSxy, ZoneSzz,
  MeanSxx, MeanSyy, MeanSxy,
  BlockAccelerationX, BlockAccelerationY, GridpointAccelerationX, GridpointAccelerationY,
  DomainPressure, KnotFlow, KnotAperture, FluidInflow, FluidOutflow, FluidContent, FluidImbalance,
  BeamDisplacementX, BeamDisplacementY, BeamRotation, BeamAxialForce, BeamShearForce, BeamMoment,
  CableAxialForce, CableDisplacement, CableSlip, CableBondForce,
  BoltAxialForce, BoltShearForce, BoltAxialDisplacement, BoltShearDisplacement,
  BlockReactionX, BlockReactionY,
  GridpointTemperature, HeatTime, HeatStored, HeatSources, HeatBoundary, HeatFixed, HeatFlow,
  BlockSxx, BlockSyy, BlockSxy, BlockExx, BlockEyy, BlockExy,
};


// Fluid: the fluid's account (fluid.*), or the domain or knot nearest a point at each sample
// (domain.*, knot.*): the network changes with the contacts, so a point, not an id, names them.
// Beam: the node (displacements, rotation) or the element (forces) of a named beam nearest a point.
// Cable: the node (displacement, slip, bond force) or element (axial force) of a named cable nearest a point.
// Bolt: the reinforcement of a named bolt nearest a point (found at each sample: a bolt installed
// by a phase has its reinforcements from then on).
// Line: the zone edges along a segment from `point` to `lineEnd` (heat.flow).
enum class HistorySubject { Block, Joint, Model, Gridpoint, Zone, Fluid, Beam, Cable, Bolt, Line };

struct HistoryQuantityInfo {
  HistoryQuantity quantity;
  std::string_view name;  // as written in the scene, e.g. "block.x"
  HistorySubject subject;
  std::string_view unit;
  std::string_view meaning;
};

const std::vector<HistoryQuantityInfo>& historyQuantities();
std::optional<HistoryQuantityInfo> findHistoryQuantity(std::string_view name);
// The names of every quantity, comma-separated, for a message about an unknown one.
std::string historyQuantityNames();
HistorySubject findHistorySubject(HistoryQuantity quantity);

struct HistorySpec {
  std::string name;
  HistoryQuantity quantity = HistoryQuantity::BlockX;
  int block = -1;       // Block subject, or the first block of a joint
  int otherBlock = -1;  // Joint subject
  int gridpoint = -1;   // Gridpoint subject
  int zone = -1;        // Zone subject
  int every = 1;
  Vec2 point;           // Fluid subject: domain.* and knot.* quantities; Beam: where along the element
  int beamNode = -1;    // Beam subject: the node nearest the point
  int beamElement = -1; // and the element nearest it
  int cableNode = -1;   // Cable subject: the node nearest the point
  int cableElement = -1;
  int bolt = -1;        // Bolt subject
  Vec2 lineEnd;         // Line subject: the segment from `point` to here
  HeatLine line;        // and its zone edges
};

// Acceleration quantities are formed by the cycle from the velocity they are the rate of:
// accelerationBaseVelocity samples that velocity component of the spec's block or gridpoint.
bool isAcceleration(HistoryQuantity quantity);
double accelerationBaseVelocity(const Model& model, const HistorySpec& spec);

// Model-wide measures of the current step, computed by the cycle.
struct Monitors {
  double unbalancedRatio = 0.0;
  double largestUnbalancedForce = 0.0;
  double kineticEnergy = 0.0;
  double strainEnergy = 0.0;
  double energyRatio = 0.0;  // mechanical energy / energy supplied
};

// The most samples a history keeps. A series that reaches it is halved, keeping the samples of
// the cycles that are multiples of twice its interval, and samples at that doubled interval from
// then on: a run of any length holds at most this many samples per history (16 bytes each), and
// the series stays what a run with the doubled `every` would have recorded.
inline constexpr std::size_t kHistorySampleLimit = 100000;

struct HistorySeries {
  std::vector<double> t;
  std::vector<double> value;
  long long every = 1;         // the interval in force: the scene's `every`, doubled at each halving
  int halvings = 0;
  bool sampledAtCycleZero = false;  // the first sample is that of cycle 0 (block and gridpoint quantities)
  // Acceleration quantities: the velocity of the half step before, from which the next step's
  // acceleration is formed (kept every step, whatever `every`).
  double lastVelocity = 0.0;
  bool hasLastVelocity = false;
};

template <class A>
void visitState(A& a, HistorySpec& h) {
  a(h.name), a(h.quantity), a(h.block), a(h.otherBlock), a(h.gridpoint), a(h.zone), a(h.every), a(h.point);
  a(h.lineEnd), a(h.line.edge), a(h.line.share);
}

template <class A>
void visitState(A& a, HistorySeries& h) {
  a(h.t), a(h.value), a(h.every), a(h.halvings), a(h.sampledAtCycleZero), a(h.lastVelocity), a(h.hasLastVelocity);
}


// Appends one sample, taken at a cycle that is a multiple of series.every; at `limit` samples
// (even) halves the series as above and returns true.
bool appendHistorySample(HistorySeries& series, double t, double value, std::size_t limit = kHistorySampleLimit);

double sampleHistory(const Model& model, const HistorySpec& spec, const Monitors& monitors);

}  // namespace vdec
