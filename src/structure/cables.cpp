#include "structure/cables.hpp"

#include <algorithm>
#include <cmath>

#include "structure/lumped_motion.hpp"
#include "core/errors.hpp"
#include "core/shown.hpp"
#include "structure/rock_point.hpp"

namespace vdec {

namespace {

bool headPlate(const Cable& cable, int node, const CableNodes& nd) {
  return cable.head && node == cable.firstNode && nd.hold[node].block >= 0;
}

}  // namespace

CableStepTotals computeCableForces(Model& m, double dt) {
  CableStepTotals totals;
  Structures& st = m.structures;
  CableNodes& nd = st.cableNodes;
  CableElements& el = st.cableElements;
  std::fill(nd.force.begin(), nd.force.end(), 0.0);
  std::fill(nd.forceScale.begin(), nd.forceScale.end(), 0.0);
  for (int e = 0; e < el.size(); ++e) {
    if (!st.cables[el.cable[e]].installed) continue;
    const CableMaterial& mat = st.cableMaterials[st.cables[el.cable[e]].material];
    const int a = el.node[e][0], b = el.node[e][1];
    const double k = mat.young * mat.area / el.restLength[e];
    const double stretch = dt * (nd.velocity[b] - nd.velocity[a]);
    const double trial = el.axialForce[e] + k * stretch;
    const double force = std::clamp(trial, -mat.yieldCompression, mat.yieldTension);
    // The yield takes the part of the stretch the force does not follow, at the force it holds.
    if (force != trial) totals.plasticWork += std::abs(force * (stretch - (force - el.axialForce[e]) / k));
    el.axialForce[e] = force;
    nd.force[a] += force;  // tension pulls the first node towards the second
    nd.force[b] -= force;
    nd.forceScale[a] += std::abs(force);
    nd.forceScale[b] += std::abs(force);
    totals.strainEnergy += 0.5 * force * force / k;
  }
  for (int i = 0; i < nd.size(); ++i) {
    const Cable& cable = st.cables[nd.cable[i]];
    if (!cable.installed || nd.hold[i].block < 0) continue;
    const CableMaterial& mat = st.cableMaterials[cable.material];
    const RockPointNow rock = rockPointNow(m, nd.hold[i]);
    if (headPlate(cable, i, nd)) {
      // The plate holds the node where the rock is: what pulls the node, the rock takes.
      nd.bondForce[i] = -(nd.force[i] + nd.mass[i] * dot(m.gravity, cable.direction) + nd.appliedForce[i]);
      loadRock(m, nd.hold[i], rock, -nd.bondForce[i] * cable.direction);
      continue;
    }
    const double slipRate = nd.velocity[i] - dot(rock.velocity, cable.direction);
    nd.slip[i] += dt * slipRate;
    const double strength = mat.bondStrength * nd.length[i];
    double bond = nd.bondForce[i] - mat.bondStiffness * nd.length[i] * dt * slipRate;
    nd.slipping[i] = std::abs(bond) > strength;
    if (nd.slipping[i]) bond = bond > 0.0 ? strength : -strength;
    nd.bondForce[i] = bond;
    loadRock(m, nd.hold[i], rock, -bond * cable.direction);
  }
  return totals;
}

MotionStepTotals integrateCableNodes(Model& m, double dt, double alpha, double local) {
  MotionStepTotals totals;
  Structures& st = m.structures;
  CableNodes& nd = st.cableNodes;
  for (int i = 0; i < nd.size(); ++i) {
    const Cable& cable = st.cables[nd.cable[i]];
    if (!cable.installed || nd.fixed[i]) continue;
    if (headPlate(cable, i, nd)) {
      // Moves with the rock under the plate, whose motion this step has already made.
      nd.velocity[i] = dot(rockPointNow(m, nd.hold[i]).velocity, cable.direction);
      nd.displacement[i] += dt * nd.velocity[i];
      continue;
    }
    // As a rigid block's degree of freedom (1.3-21); the elements' force is internal, gravity
    // along the cable, the loads and the grout's force external (the grout's springs and slip
    // are in the work done on node and rock together).
    const double internal = nd.force[i];
    const double body = nd.mass[i] * dot(m.gravity, cable.direction) + nd.appliedForce[i] + nd.bondForce[i];
    const double v1 = advanceLumped(totals, nd.velocity[i], nd.mass[i], internal, body, alpha, local, dt);
    totals.largestUnbalancedForce = std::max(totals.largestUnbalancedForce, std::abs(internal + body));
    totals.forceScaleSum += nd.forceScale[i] + std::abs(nd.bondForce[i]);
    ++totals.forceCount;
    nd.velocity[i] = v1;
    nd.displacement[i] += dt * v1;
    totals.largestDisplacement = std::max(totals.largestDisplacement, std::abs(v1) * dt);
  }
  return totals;
}

double cableTimeStep(const Model& m, double frac, double zoneFraction) {
  const Structures& st = m.structures;
  const CableNodes& nd = st.cableNodes;
  const CableElements& el = st.cableElements;
  std::vector<double> row(nd.size(), 0.0);
  for (int e = 0; e < el.size(); ++e) {
    if (!st.cables[el.cable[e]].installed) continue;
    const CableMaterial& mat = st.cableMaterials[st.cables[el.cable[e]].material];
    const double k = mat.young * mat.area / el.restLength[e];
    const int a = el.node[e][0], b = el.node[e][1];
    const double across = k / std::sqrt(nd.mass[a] * nd.mass[b]);
    row[a] += k / nd.mass[a] + across;
    row[b] += k / nd.mass[b] + across;
  }
  HostStiffness hosts(m);
  for (int i = 0; i < nd.size(); ++i) {
    const Cable& cable = st.cables[nd.cable[i]];
    if (!cable.installed || nd.hold[i].block < 0) continue;
    // A head plate passes its element's stiffness to the rock; grout, its springs.
    const CableMaterial& mat = st.cableMaterials[cable.material];
    const double k = headPlate(cable, i, nd) ? mat.young * mat.area / st.cableElements.restLength[cable.firstElement]
                                             : mat.bondStiffness * nd.length[i];
    row[i] += k / nd.mass[i];
    hosts.add(m, nd.hold[i], k);
  }
  double largest = 0.0;
  for (const double r : row) largest = std::max(largest, r);
  const double dt = largest > 0.0 ? 0.9 * 2.0 / std::sqrt(largest) : INFINITY;
  return std::min(dt, hosts.timeStep(m, frac, zoneFraction));
}

double installCable(Model& m, int index, const std::string& when) {
  Structures& st = m.structures;
  Cable& cable = st.cables[index];
  const CableMaterial& mat = st.cableMaterials[cable.material];
  CableNodes& nd = st.cableNodes;
  CableElements& el = st.cableElements;
  const int first = cable.firstNode, last = first + cable.nodeCount;
  const Vec2 start = nd.position[first];
  std::vector<char> grouted(static_cast<std::size_t>(cable.nodeCount), 0);
  for (int i = first; i < last; ++i) {
    CableNodes::Hold hold;
    const bool plate = cable.head && i == first;
    const double along = norm(nd.position[i] - start), element = el.restLength[cable.firstElement];
    const double reach = findRockPoint(m, nd.position[i], hold);
    nd.hold[i] = {};
    if (reach <= m.roundingLength && (plate || along >= cable.freeLength - 1e-9 * element)) {
      nd.hold[i] = hold;
      nd.position[i] = rockPointNow(m, hold).position;
      grouted[static_cast<std::size_t>(i - first)] = !plate;
    } else if (plate) {
      throw SceneError(when + (when.empty() ? "" : ": ") + "cable '" + cable.name + "': its head at (" +
                       shown(nd.position[i].x) + ", " + shown(nd.position[i].y) + ") lies on no block (the nearest is " +
                       shown(reach) + " m away, beyond the rounding length): place the first point on the rock, or set head = false");
    }
    nd.displacement[i] = nd.velocity[i] = nd.slip[i] = nd.bondForce[i] = 0.0;
    nd.length[i] = 0.0;
  }
  // The grout's length at a node: half of each element grouted at both ends.
  double energy = 0.0;
  for (int e = cable.firstElement; e < cable.firstElement + cable.elementCount; ++e) {
    const int a = el.node[e][0], b = el.node[e][1];
    const bool bonded = grouted[static_cast<std::size_t>(a - first)] && grouted[static_cast<std::size_t>(b - first)];
    if (bonded) {
      nd.length[a] += 0.5 * el.restLength[e];
      nd.length[b] += 0.5 * el.restLength[e];
    }
    el.axialForce[e] = bonded ? 0.0 : cable.pretension;
    energy += 0.5 * el.axialForce[e] * el.axialForce[e] * el.restLength[e] / (mat.young * mat.area);
  }
  m.blocks.boundaryForce.resize(m.blocks.size());
  m.blocks.boundaryMoment.resize(m.blocks.size());
  cable.installed = true;
  return energy;
}

double removeCable(Model& m, int index) {
  Structures& st = m.structures;
  Cable& cable = st.cables[index];
  const CableMaterial& mat = st.cableMaterials[cable.material];
  CableNodes& nd = st.cableNodes;
  CableElements& el = st.cableElements;
  double energy = 0.0;
  for (int e = cable.firstElement; e < cable.firstElement + cable.elementCount; ++e) {
    energy += 0.5 * el.axialForce[e] * el.axialForce[e] * el.restLength[e] / (mat.young * mat.area);
    el.axialForce[e] = 0.0;
  }
  for (int i = cable.firstNode; i < cable.firstNode + cable.nodeCount; ++i) {
    energy += 0.5 * nd.mass[i] * nd.velocity[i] * nd.velocity[i];
    nd.velocity[i] = nd.force[i] = nd.bondForce[i] = 0.0;
    nd.hold[i] = {};
  }
  cable.installed = false;
  return energy;
}

}  // namespace vdec
