#include "run/history.hpp"

#include "flow/fracture_flow.hpp"
#include "motion/strain_modes.hpp"

#include <algorithm>
#include <numbers>

namespace vdec {

const std::vector<HistoryQuantityInfo>& historyQuantities() {
  using Q = HistoryQuantity;
  using S = HistorySubject;
  static const std::vector<HistoryQuantityInfo> table = {
      {Q::BlockX, "block.x", S::Block, "m", "centroid x"},
      {Q::BlockY, "block.y", S::Block, "m", "centroid y"},
      {Q::BlockDisplacementX, "block.displacement_x", S::Block, "m", "centroid x minus its initial value"},
      {Q::BlockDisplacementY, "block.displacement_y", S::Block, "m", "centroid y minus its initial value"},
      {Q::BlockVelocityX, "block.velocity_x", S::Block, "m/s", "centroid velocity x (at the half step)"},
      {Q::BlockVelocityY, "block.velocity_y", S::Block, "m/s", "centroid velocity y (at the half step)"},
      {Q::BlockRotation, "block.rotation", S::Block, "rad", "rotation, counter-clockwise positive"},
      {Q::BlockAngularVelocity, "block.angular_velocity", S::Block, "rad/s", "angular velocity"},
      {Q::BlockAccelerationX, "block.acceleration_x", S::Block, "m/s^2", "centroid acceleration x: the change of velocity over the step, at the step's start"},
      {Q::BlockAccelerationY, "block.acceleration_y", S::Block, "m/s^2", "centroid acceleration y: the change of velocity over the step, at the step's start"},
      {Q::BlockReactionX, "block.reaction_x", S::Block, "N/m", "x force the block's drive adds to hold its velocity: minus the sum of the forces of the step on it (contacts, supports, fluid, gravity, applied loads); of a free block, minus its unbalanced force"},
      {Q::BlockReactionY, "block.reaction_y", S::Block, "N/m", "y force the block's drive adds, as block.reaction_x"},
      {Q::BlockSxx, "block.sxx", S::Block, "Pa", "stress sxx of a simply-deformable block, tension positive"},
      {Q::BlockSyy, "block.syy", S::Block, "Pa", "stress syy of a simply-deformable block, tension positive"},
      {Q::BlockSxy, "block.sxy", S::Block, "Pa", "stress sxy of a simply-deformable block"},
      {Q::BlockExx, "block.exx", S::Block, "-", "strain exx of a simply-deformable block, extension positive"},
      {Q::BlockEyy, "block.eyy", S::Block, "-", "strain eyy of a simply-deformable block, extension positive"},
      {Q::BlockExy, "block.exy", S::Block, "-", "tensor shear strain exy of a simply-deformable block (half the engineering shear)"},
      {Q::JointNormalForce, "joint.normal_force", S::Joint, "N/m", "sum of contact normal forces, compression positive"},
      {Q::JointShearForce, "joint.shear_force", S::Joint, "N/m", "sum of contact shear forces"},
      {Q::JointNormalStress, "joint.normal_stress", S::Joint, "Pa", "sum of normal forces / joint.length"},
      {Q::JointShearStress, "joint.shear_stress", S::Joint, "Pa", "sum of shear forces / joint.length"},
      {Q::JointNormalDisplacement, "joint.normal_displacement", S::Joint, "m", "mean accumulated normal displacement, closing positive"},
      {Q::JointShearDisplacement, "joint.shear_displacement", S::Joint, "m", "mean accumulated shear displacement"},
      {Q::JointLength, "joint.length", S::Joint, "m", "sum of the lengths of closed contacts"},
      {Q::JointContacts, "joint.contacts", S::Joint, "-", "number of contacts"},
      {Q::JointEffectiveFriction, "joint.effective_friction", S::Joint, "degrees",
       "mean effective friction angle phi_eff of the contacts (continuously-yielding law)"},
      {Q::JointPlasticShear, "joint.plastic_shear_displacement", S::Joint, "m",
       "mean plastic shear displacement of the contacts (continuously-yielding law)"},
      {Q::UnbalancedRatio, "model.unbalanced_ratio", S::Model, "-", "largest unbalanced force / mean contact force"},
      {Q::LargestUnbalancedForce, "model.largest_unbalanced_force", S::Model, "N/m", "largest unbalanced force of a free block"},
      {Q::KineticEnergy, "model.kinetic_energy", S::Model, "J/m", "kinetic energy (time-centred)"},
      {Q::StrainEnergy, "model.strain_energy", S::Model, "J/m", "elastic energy in the contacts and zones"},
      {Q::EnergyRatio, "model.energy_ratio", S::Model, "-", "(kinetic + strain energy) / largest energy supplied so far"},
      {Q::MeanSxx, "model.mean_sxx", S::Model, "Pa", "sxx of all zones, averaged over their present areas"},
      {Q::MeanSyy, "model.mean_syy", S::Model, "Pa", "syy of all zones, averaged over their present areas"},
      {Q::MeanSxy, "model.mean_sxy", S::Model, "Pa", "sxy of all zones, averaged over their present areas"},
      {Q::GridpointDisplacementX, "gridpoint.displacement_x", S::Gridpoint, "m", "x displacement of a deformable block's gridpoint"},
      {Q::GridpointDisplacementY, "gridpoint.displacement_y", S::Gridpoint, "m", "y displacement of a deformable block's gridpoint"},
      {Q::GridpointTemperature, "gridpoint.temperature", S::Gridpoint, "degrees", "temperature of the gridpoint's thermal node ([heat]), in the scene's unit of temperature"},
      {Q::HeatTime, "heat.time", S::Model, "s", "the thermal clock ([heat])"},
      {Q::HeatStored, "heat.stored", S::Model, "J/m", "heat stored in the free thermal nodes since the start ([heat])"},
      {Q::HeatSources, "heat.sources", S::Model, "J/m", "heat released by the [[heat_source]]s since the start"},
      {Q::HeatBoundary, "heat.boundary", S::Model, "J/m", "heat in through fluxes, convection and radiation since the start"},
      {Q::HeatFixed, "heat.fixed", S::Model, "J/m", "heat the held nodes gave their neighbours since the start"},
      {Q::HeatFlow, "heat.flow", S::Line, "W/m", "heat flow through the zone edges along the segment from `from` to `to`, towards the right of that direction: the conducted flux -k grad T of the zones on each edge (their mean where two meet), times the edge's length ([heat])"},
      {Q::GridpointVelocityX, "gridpoint.velocity_x", S::Gridpoint, "m/s", "x velocity of the gridpoint (at the half step)"},
      {Q::GridpointVelocityY, "gridpoint.velocity_y", S::Gridpoint, "m/s", "y velocity of the gridpoint (at the half step)"},
      {Q::GridpointAccelerationX, "gridpoint.acceleration_x", S::Gridpoint, "m/s^2", "x acceleration of the gridpoint: the change of velocity over the step, at the step's start"},
      {Q::GridpointAccelerationY, "gridpoint.acceleration_y", S::Gridpoint, "m/s^2", "y acceleration of the gridpoint: the change of velocity over the step, at the step's start"},
      {Q::ZoneSxx, "zone.sxx", S::Zone, "Pa", "zone stress sxx, tension positive"},
      {Q::ZoneSyy, "zone.syy", S::Zone, "Pa", "zone stress syy, tension positive"},
      {Q::ZoneSxy, "zone.sxy", S::Zone, "Pa", "zone stress sxy"},
      {Q::ZoneSzz, "zone.szz", S::Zone, "Pa", "zone stress szz (plane strain), tension positive"},
      {Q::DomainPressure, "domain.pressure", S::Fluid, "Pa", "pressure of the fluid domain whose centre is nearest the point"},
      {Q::KnotFlow, "knot.flow", S::Fluid, "m^2/s", "flow through the knot nearest the point, from its domain_0 side to its domain_1 side"},
      {Q::KnotAperture, "knot.aperture", S::Fluid, "m", "hydraulic aperture of the knot nearest the point"},
      {Q::FluidInflow, "fluid.inflow", S::Fluid, "m^2", "fluid that has entered the model through held mouths and domains and from sources"},
      {Q::FluidOutflow, "fluid.outflow", S::Fluid, "m^2", "fluid that has left the model through held mouths and domains"},
      {Q::FluidContent, "fluid.content", S::Fluid, "m^2", "fluid the domains hold, as its volume at zero pressure"},
      {Q::FluidImbalance, "fluid.imbalance", S::Fluid, "m^2", "inflow - outflow + created - removed - (content - initial content): zero to round-off"},
      {Q::BeamDisplacementX, "beam.displacement_x", S::Beam, "m", "x displacement of the beam's node nearest the point"},
      {Q::BeamDisplacementY, "beam.displacement_y", S::Beam, "m", "y displacement of the beam's node nearest the point"},
      {Q::BeamRotation, "beam.rotation", S::Beam, "rad", "rotation of the beam's node nearest the point, counter-clockwise positive"},
      {Q::BeamAxialForce, "beam.axial_force", S::Beam, "N/m", "axial force of the beam's element nearest the point, tension positive"},
      {Q::BeamShearForce, "beam.shear_force", S::Beam, "N/m", "shear force dM/ds of the beam's element nearest the point (s along the beam)"},
      {Q::CableAxialForce, "cable.axial_force", S::Cable, "N/m", "axial force of the cable's element nearest the point, tension positive"},
      {Q::CableDisplacement, "cable.displacement", S::Cable, "m", "displacement along the cable (first point towards last) of its node nearest the point"},
      {Q::CableSlip, "cable.slip", S::Cable, "m", "slip of the cable's node nearest the point relative to the rock, along the cable"},
      {Q::CableBondForce, "cable.bond_force", S::Cable, "N/m", "the grout's force on the cable's node nearest the point, along the cable"},
      {Q::BoltAxialForce, "bolt.axial_force", S::Bolt, "N/m", "axial force of the bolt's reinforcement nearest the point, tension positive (0 before the bolt is installed)"},
      {Q::BoltShearForce, "bolt.shear_force", S::Bolt, "N/m", "shear force of the bolt's reinforcement nearest the point, along the bolt's direction turned +90 degrees"},
      {Q::BoltAxialDisplacement, "bolt.axial_displacement", S::Bolt, "m", "u_axial of the reinforcement nearest the point: the joint's displacement increments along its active length, summed"},
      {Q::BoltShearDisplacement, "bolt.shear_displacement", S::Bolt, "m", "the joint's displacement at the reinforcement nearest the point along the bolt's direction turned +90 degrees"},
      {Q::BeamMoment, "beam.moment", S::Beam, "N m/m", "bending moment E I kappa of the beam's element nearest the point, linear between its ends, at the point's projection on it"},
  };
  return table;
}

std::string historyQuantityNames() {
  std::string known;
  for (const auto& q : historyQuantities()) known += (known.empty() ? "" : ", ") + std::string(q.name);
  return known;
}

std::optional<HistoryQuantityInfo> findHistoryQuantity(std::string_view name) {
  for (const auto& info : historyQuantities())
    if (info.name == name) return info;
  return std::nullopt;
}

bool isAcceleration(HistoryQuantity q) {
  return q == HistoryQuantity::BlockAccelerationX || q == HistoryQuantity::BlockAccelerationY ||
         q == HistoryQuantity::GridpointAccelerationX || q == HistoryQuantity::GridpointAccelerationY;
}

double accelerationBaseVelocity(const Model& m, const HistorySpec& h) {
  switch (h.quantity) {
    case HistoryQuantity::BlockAccelerationX: return m.blocks.velocity[h.block].x;
    case HistoryQuantity::BlockAccelerationY: return m.blocks.velocity[h.block].y;
    case HistoryQuantity::GridpointAccelerationX: return m.gridpoints.velocity[h.gridpoint].x;
    default: return m.gridpoints.velocity[h.gridpoint].y;
  }
}

HistorySubject findHistorySubject(HistoryQuantity quantity) {
  for (const auto& info : historyQuantities())
    if (info.quantity == quantity) return info.subject;
  return HistorySubject::Model;
}

namespace {

double jointMeasure(const Model& m, const HistorySpec& h) {
  double normalForce = 0.0, shearForce = 0.0, length = 0.0, un = 0.0, us = 0.0, friction = 0.0, plastic = 0.0;
  int count = 0, yielding = 0;
  for (std::size_t i = 0; i < m.contacts.size(); ++i) {
    const Contact& c = m.contacts[i];
    const bool between = (c.blockA == h.block && c.blockB == h.otherBlock) ||
                         (c.blockA == h.otherBlock && c.blockB == h.block);
    if (!between) continue;
    normalForce += m.normalForce(c);
    shearForce += m.shearForce(c);
    if (!c.open) length += c.length;
    un += c.normalDisplacement;
    us += c.shearDisplacement;
    if (m.jointMaterials[c.joint].law == JointLaw::ContinuouslyYielding) {
      friction += m.yieldingStates[i].effectiveFriction;
      plastic += m.yieldingStates[i].plasticShear;
      ++yielding;
    }
    ++count;
  }
  switch (h.quantity) {
    case HistoryQuantity::JointNormalForce: return normalForce;
    case HistoryQuantity::JointShearForce: return shearForce;
    case HistoryQuantity::JointNormalStress: return length > 0 ? normalForce / length : 0.0;
    case HistoryQuantity::JointShearStress: return length > 0 ? shearForce / length : 0.0;
    case HistoryQuantity::JointNormalDisplacement: return count ? un / count : 0.0;
    case HistoryQuantity::JointShearDisplacement: return count ? us / count : 0.0;
    case HistoryQuantity::JointLength: return length;
    case HistoryQuantity::JointEffectiveFriction: return yielding ? friction / yielding * 180.0 / std::numbers::pi : 0.0;
    case HistoryQuantity::JointPlasticShear: return yielding ? plastic / yielding : 0.0;
    default: return static_cast<double>(count);
  }
}

// The area-weighted mean of one stress component over all zones: with free sides and loads on
// two opposite faces, the mean syy is the load over the width, by equilibrium.
double meanZoneStress(const Model& m, const std::vector<double>& component) {
  const Gridpoints& g = m.gridpoints;
  double sum = 0.0, area = 0.0;
  for (int z = 0; z < m.zones.size(); ++z) {
    const auto& n = m.zones.gridpoint[z];
    const double a = 0.5 * cross(g.position[n[1]] - g.position[n[0]], g.position[n[2]] - g.position[n[0]]);
    sum += a * component[z];
    area += a;
  }
  return area > 0.0 ? sum / area : 0.0;
}

double fluidMeasure(const Model& m, const HistorySpec& h) {
  const FlowState& fs = m.flow;
  auto nearest = [&h](const auto& items, auto where) {
    int best = -1;
    double distance = INFINITY;
    for (std::size_t i = 0; i < items.size(); ++i) {
      const double d = norm(where(items[i]) - h.point);
      if (d < distance) distance = d, best = static_cast<int>(i);
    }
    return best;
  };
  switch (h.quantity) {
    case HistoryQuantity::DomainPressure: {
      const int d = nearest(fs.domains, [](const FlowDomain& x) { return x.centre; });
      return d < 0 ? 0.0 : fs.domains[d].pressure;
    }
    case HistoryQuantity::KnotFlow:
    case HistoryQuantity::KnotAperture: {
      const int k = nearest(fs.knots, [](const FlowKnot& x) { return x.point; });
      if (k < 0) return 0.0;
      return h.quantity == HistoryQuantity::KnotFlow ? fs.knots[k].flow : fs.knots[k].aperture;
    }
    case HistoryQuantity::FluidInflow: return fs.totals.inflow;
    case HistoryQuantity::FluidOutflow: return fs.totals.outflow;
    case HistoryQuantity::FluidContent: return flowContent(m);
    default: return flowImbalance(m);
  }
}

double beamMeasure(const Model& m, const HistorySpec& h) {
  const BeamNodes& nd = m.structures.nodes;
  const BeamElements& el = m.structures.elements;
  switch (h.quantity) {
    case HistoryQuantity::BeamDisplacementX: return nd.position[h.beamNode].x - nd.initialPosition[h.beamNode].x;
    case HistoryQuantity::BeamDisplacementY: return nd.position[h.beamNode].y - nd.initialPosition[h.beamNode].y;
    case HistoryQuantity::BeamRotation: return nd.rotation[h.beamNode];
    case HistoryQuantity::BeamAxialForce: return el.axialForce[h.beamElement];
    case HistoryQuantity::BeamShearForce: return el.shearForce[h.beamElement];
    default: {
      const Vec2 a = nd.initialPosition[el.node[h.beamElement][0]], b = nd.initialPosition[el.node[h.beamElement][1]];
      const double t = std::clamp(dot(h.point - a, b - a) / dot(b - a, b - a), 0.0, 1.0);
      return (1.0 - t) * el.endMoment[h.beamElement][0] + t * el.endMoment[h.beamElement][1];
    }
  }
}

double cableMeasure(const Model& m, const HistorySpec& h) {
  const CableNodes& nd = m.structures.cableNodes;
  switch (h.quantity) {
    case HistoryQuantity::CableAxialForce: return m.structures.cableElements.axialForce[h.cableElement];
    case HistoryQuantity::CableDisplacement: return nd.displacement[h.cableNode];
    case HistoryQuantity::CableSlip: return nd.slip[h.cableNode];
    default: return nd.bondForce[h.cableNode];
  }
}

double boltMeasure(const Model& m, const HistorySpec& h) {
  const Structures& st = m.structures;
  const Bolt& bolt = st.bolts[h.bolt];
  const BoltCrossings& x = st.crossings;
  if (bolt.crossingCount == 0) return 0.0;
  int i = bolt.firstCrossing;
  for (int k = i; k < bolt.firstCrossing + bolt.crossingCount; ++k)
    if (norm(x.point[k] - h.point) < norm(x.point[i] - h.point)) i = k;
  switch (h.quantity) {
    case HistoryQuantity::BoltAxialForce: return x.axialForce[i];
    case HistoryQuantity::BoltShearForce: return x.shearForce[i];
    case HistoryQuantity::BoltAxialDisplacement: return x.axialDisplacement[i];
    default: return dot(x.displacement[i], perp(bolt.direction));
  }
}

// A simply-deformable block's stress or strain in the world's axes, at the positions just reached.
double strainMeasure(const Model& m, const HistorySpec& h) {
  double szz = 0.0;
  const bool stress = h.quantity == HistoryQuantity::BlockSxx || h.quantity == HistoryQuantity::BlockSyy ||
                      h.quantity == HistoryQuantity::BlockSxy;
  const Sym2 t = inWorldAxes(m, h.block, stress ? presentStress(m, h.block, szz) : m.strainModes.strain[m.strainModes.of[h.block]]);
  switch (h.quantity) {
    case HistoryQuantity::BlockSxx:
    case HistoryQuantity::BlockExx: return t.xx;
    case HistoryQuantity::BlockSyy:
    case HistoryQuantity::BlockEyy: return t.yy;
    default: return t.xy;
  }
}

Vec2 blockReaction(const Model& m, int b) {
  const Blocks& bl = m.blocks;
  Vec2 total = bl.force[b] + bl.mass[b] * m.gravity + bl.appliedForce[b];
  if (!bl.boundaryForce.empty()) total += bl.boundaryForce[b];
  if (!bl.dashpotForce.empty()) total += bl.dashpotForce[b];
  return -1.0 * total;
}

}  // namespace

bool appendHistorySample(HistorySeries& series, double t, double value, std::size_t limit) {
  series.t.push_back(t);
  series.value.push_back(value);
  if (series.t.size() < limit) return false;
  // Sample k was taken at cycle (k + first) * every, first = 0 when cycle 0 was sampled: keep the
  // samples whose cycle is a multiple of 2 every.
  const std::size_t first = series.sampledAtCycleZero ? 0 : 1;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < series.t.size(); ++k) {
    if ((k + first) % 2 != 0) continue;
    series.t[kept] = series.t[k];
    series.value[kept] = series.value[k];
    ++kept;
  }
  series.t.resize(kept);
  series.value.resize(kept);
  series.every *= 2;
  ++series.halvings;
  return true;
}

double sampleHistory(const Model& m, const HistorySpec& h, const Monitors& mon) {
  const Blocks& b = m.blocks;
  switch (h.quantity) {
    case HistoryQuantity::BlockX: return b.centroid[h.block].x;
    case HistoryQuantity::BlockY: return b.centroid[h.block].y;
    case HistoryQuantity::BlockDisplacementX: return b.centroid[h.block].x - b.initialCentroid[h.block].x;
    case HistoryQuantity::BlockDisplacementY: return b.centroid[h.block].y - b.initialCentroid[h.block].y;
    case HistoryQuantity::BlockVelocityX: return b.velocity[h.block].x;
    case HistoryQuantity::BlockVelocityY: return b.velocity[h.block].y;
    case HistoryQuantity::BlockRotation: return b.rotation[h.block];
    case HistoryQuantity::BlockAngularVelocity: return b.angularVelocity[h.block];
    case HistoryQuantity::BlockReactionX: return blockReaction(m, h.block).x;
    case HistoryQuantity::BlockReactionY: return blockReaction(m, h.block).y;
    case HistoryQuantity::BlockSxx:
    case HistoryQuantity::BlockSyy:
    case HistoryQuantity::BlockSxy:
    case HistoryQuantity::BlockExx:
    case HistoryQuantity::BlockEyy:
    case HistoryQuantity::BlockExy: return strainMeasure(m, h);
    case HistoryQuantity::UnbalancedRatio: return mon.unbalancedRatio;
    case HistoryQuantity::LargestUnbalancedForce: return mon.largestUnbalancedForce;
    case HistoryQuantity::KineticEnergy: return mon.kineticEnergy;
    case HistoryQuantity::StrainEnergy: return mon.strainEnergy;
    case HistoryQuantity::EnergyRatio: return mon.energyRatio;
    case HistoryQuantity::GridpointDisplacementX:
      return m.gridpoints.position[h.gridpoint].x - m.gridpoints.initialPosition[h.gridpoint].x;
    case HistoryQuantity::GridpointDisplacementY:
      return m.gridpoints.position[h.gridpoint].y - m.gridpoints.initialPosition[h.gridpoint].y;
    case HistoryQuantity::GridpointVelocityX: return m.gridpoints.velocity[h.gridpoint].x;
    case HistoryQuantity::GridpointVelocityY: return m.gridpoints.velocity[h.gridpoint].y;
    case HistoryQuantity::GridpointTemperature: return m.heat.temperature[m.heat.nodeOfGridpoint[h.gridpoint]];
    case HistoryQuantity::HeatTime: return m.heat.time;
    case HistoryQuantity::HeatStored: return m.heat.stored;
    case HistoryQuantity::HeatSources: return m.heat.sources;
    case HistoryQuantity::HeatBoundary: return m.heat.boundary;
    case HistoryQuantity::HeatFixed: return m.heat.fixedInflow;
    case HistoryQuantity::HeatFlow: return heatFlowAcross(m, h.line, h.point, h.lineEnd);
    case HistoryQuantity::ZoneSxx: return m.zones.sxx[h.zone];
    case HistoryQuantity::ZoneSyy: return m.zones.syy[h.zone];
    case HistoryQuantity::ZoneSxy: return m.zones.sxy[h.zone];
    case HistoryQuantity::ZoneSzz: return m.zones.szz[h.zone];
    case HistoryQuantity::MeanSxx: return meanZoneStress(m, m.zones.sxx);
    case HistoryQuantity::MeanSyy: return meanZoneStress(m, m.zones.syy);
    case HistoryQuantity::MeanSxy: return meanZoneStress(m, m.zones.sxy);
    default:
      switch (findHistorySubject(h.quantity)) {
        case HistorySubject::Fluid: return fluidMeasure(m, h);
        case HistorySubject::Beam: return beamMeasure(m, h);
        case HistorySubject::Cable: return cableMeasure(m, h);
        case HistorySubject::Bolt: return boltMeasure(m, h);
        default: return jointMeasure(m, h);
      }
  }
}

}  // namespace vdec
