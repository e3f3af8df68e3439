// Heat conduction in the zones (1.4.3): the thermal nodes (coincident gridpoints of different
// blocks merged, so that joints do not impede heat), the fixed temperatures, fluxes, convection
// and sources resolved on them, the conductance formed and the thermal step chosen.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/shown.hpp"
#include "scene/build_parts.hpp"
#include "thermal/heat.hpp"

namespace vdec {

namespace {

// The most thermal steps one advance may take.
constexpr double kHeatStepLimit = 1e7;
// W/(m^2 K^4) (CODATA 2018, exact since the SI redefinition).
constexpr double kStefanBoltzmann = 5.670374419e-8;

// Gridpoints that coincide at the start, within `slack`, share one node; nodes are numbered in the
// order of their first gridpoint.
std::vector<int> mergedNodes(const Gridpoints& g, double slack, int& count) {
  const int n = g.size();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<int> byX(n);
  std::iota(byX.begin(), byX.end(), 0);
  std::sort(byX.begin(), byX.end(), [&](int a, int b) {
    return g.initialPosition[a].x < g.initialPosition[b].x || (g.initialPosition[a].x == g.initialPosition[b].x && a < b);
  });
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n && g.initialPosition[byX[b]].x - g.initialPosition[byX[a]].x <= slack; ++b)
      if (std::abs(g.initialPosition[byX[b]].y - g.initialPosition[byX[a]].y) <= slack) {
        const int ra = root(byX[a]), rb = root(byX[b]);
        parent[std::max(ra, rb)] = std::min(ra, rb);
      }
  std::vector<int> node(n, -1);
  count = 0;
  for (int i = 0; i < n; ++i) {
    const int r = root(i);
    node[i] = r == i ? count++ : node[r];
  }
  return node;
}

int decayGroup(HeatField& h, const HeatDecay& decay) {
  if (decay.empty()) return 0;
  h.decays.push_back(decay);
  return static_cast<int>(h.decays.size()) - 1;
}

void addLoad(HeatField& h, int node, double power, int decay, bool boundary, int history = -1) {
  h.loadNode.push_back(node);
  h.loadHistory.push_back(history);
  h.loadPower.push_back(power);
  h.loadDecay.push_back(decay);
  h.loadBoundary.push_back(boundary);
}

void resolveHeatBoundary(Model& m, const HeatBoundaryDefinition& d) {
  HeatField& h = m.heat;
  std::vector<char> inBlocks(m.blocks.size(), 0);
  if (d.block.empty()) {
    for (int b = 0; b < m.blocks.size(); ++b) inBlocks[b] = m.blocks.deformable[b];
  } else {
    const int block = blockNamed(m, d.origin, "block", d.block);
    if (!m.blocks.deformable[block]) d.origin.fail("block", "block '" + d.block + "' is rigid: heat is conducted in zones only");
    inBlocks[block] = 1;
  }
  const GridpointSelection picked = selectGridpoints(m, inBlocks, d.x, d.y, d.r, d.angle, d.centre);
  const Gridpoints& g = m.gridpoints;
  int history = -1;
  if (d.history) {
    h.histories.push_back(*d.history);
    history = static_cast<int>(h.histories.size()) - 1;
  }
  if (d.kind == HeatBoundaryDefinition::Kind::Temperature) {
    if (picked.count == 0) d.origin.failTable("selects no gridpoint: check block, x, y, r, angle");
    for (int i = 0; i < g.size(); ++i)
      if (picked.selected[i]) {
        const int node = h.nodeOfGridpoint[i];
        h.fixed[node] = 1;
        h.fixedValue[node] = d.value;
        h.fixedHistory[node] = history;
        h.temperature[node] = history < 0 ? d.value : d.value * h.histories[history](0.0);
      }
    return;
  }
  const int decay = decayGroup(h, d.decay);
  int edges = 0;
  for (const Model::BoundaryEdge& e : m.boundaryEdges) {
    if (!inBlocks[e.block] || !picked.selected[e.from] || !picked.selected[e.to]) continue;
    ++edges;
    const double half = 0.5 * norm(g.initialPosition[e.to] - g.initialPosition[e.from]);
    for (const int p : {e.from, e.to}) {
      const int node = h.nodeOfGridpoint[p];
      if (d.kind == HeatBoundaryDefinition::Kind::Flux) {
        addLoad(h, node, d.value * half, decay, true, history);
      } else if (d.kind == HeatBoundaryDefinition::Kind::Radiation) {
        h.radiationNode.push_back(node);
        h.radiationCoefficient.push_back(d.value * kStefanBoltzmann * half);
        h.radiationAmbient.push_back(d.ambient);
      } else {
        h.convectionNode.push_back(node);
        h.convectionConductance.push_back(d.value * half);
        h.convectionAmbient.push_back(d.ambient);
      }
    }
  }
  if (edges == 0)
    d.origin.failTable("selects no outline edge: a flux or convection acts on the edges of a block's outline whose two "
                       "ends are both selected; check block, x, y, r, angle");
}

void resolveHeatSource(Model& m, const HeatSourceDefinition& d, double slack) {
  HeatField& h = m.heat;
  const int decay = decayGroup(h, d.decay);
  if (d.atPoint) {
    const Gridpoints& g = m.gridpoints;
    for (int i = 0; i < g.size(); ++i)
      if (norm(g.initialPosition[i] - d.point) <= slack) {
        addLoad(h, h.nodeOfGridpoint[i], d.power, decay, false);
        return;
      }
    d.origin.fail("point", "no gridpoint at (" + shown(d.point.x) + ", " + shown(d.point.y) +
                               "): a line source sits on a gridpoint; zone the block so that one lies there");
  }
  const int block = blockNamed(m, d.origin, "block", d.block);
  if (!m.blocks.deformable[block]) d.origin.fail("block", "block '" + d.block + "' is rigid: heat sources act in zones only");
  const Zones& zn = m.zones;
  for (int z = 0; z < zn.size(); ++z) {
    if (zn.block[z] != block) continue;
    const auto& p = zn.gridpoint[z];
    const Vec2 a = m.gridpoints.position[p[0]], b = m.gridpoints.position[p[1]], c = m.gridpoints.position[p[2]];
    const double third = d.power * 0.5 * cross(b - a, c - a) / 3.0;
    for (int k = 0; k < 3; ++k) addLoad(h, h.nodeOfGridpoint[p[k]], third, decay, false);
  }
}

}  // namespace

void buildHeat(Model& m, const SceneDefinition& s) {
  const HeatDefinition& d = *s.heat;
  if (m.zones.size() == 0) d.origin.failTable("needs deformable blocks: heat is conducted in their zones");
  for (int b = 0; b < m.blocks.size(); ++b) {
    if (!m.blocks.deformable[b]) continue;
    const int material = m.blocks.material[b];
    const BlockMaterial& mat = m.blockMaterials[material];
    const Origin& origin = s.blockMaterials[material].origin;
    if (!(mat.conductivityX > 0.0)) origin.fail("conductivity", "is required with [heat]: block '" + m.blocks.name[b] + "' conducts heat (W/(m K); or conductivity_x and conductivity_y)");
    if (!(mat.specificHeat > 0.0)) origin.fail("specific_heat", "is required with [heat]: block '" + m.blocks.name[b] + "' stores heat (J/(kg K))");
    if (!std::isfinite(mat.density * mat.specificHeat))
      origin.fail("specific_heat", "times the density gives a heat capacity beyond the range of a double: lower it");
  }
  HeatField& h = m.heat;
  double size = 1.0;
  for (int b = 0; b < m.blocks.size(); ++b)
    if (m.blocks.deformable[b]) size = std::max(size, 2.0 * m.blocks.boundingRadius[b]);
  const double slack = 1e-9 * size;
  int nodes = 0;
  h.nodeOfGridpoint = mergedNodes(m.gridpoints, slack, nodes);
  h.temperature.assign(static_cast<std::size_t>(nodes), d.initialTemperature);
  h.fixed.assign(static_cast<std::size_t>(nodes), 0);
  h.fixedValue.assign(static_cast<std::size_t>(nodes), 0.0);
  h.fixedHistory.assign(static_cast<std::size_t>(nodes), -1);
  h.decays.assign(1, {});
  h.theta = d.theta;
  for (const HeatBoundaryDefinition& b : s.heatBoundaries) resolveHeatBoundary(m, b);
  for (const HeatSourceDefinition& source : s.heatSources) resolveHeatSource(m, source, slack);
  assembleHeat(m);
  for (const double k : h.conductance)
    if (!std::isfinite(k))
      d.origin.failTable("the zones' conductance is beyond the range of a double: lower the materials' conductivity");
  h.stableStep = heatStableStep(m);
  if (d.step > 0.0) {
    if (d.theta == 0.0 && d.step > h.stableStep)
      d.origin.fail("step", shown(d.step) + " s is above the explicit scheme's stable step " + shown(h.stableStep) +
                                " s (Gershgorin's bound 2 / max_i (sum_j |K_ij| + h_i) / C_i): lower it, or give theta > 0 "
                                "(0.5 for Crank-Nicolson)");
    h.step = d.step;
  } else {
    h.step = std::isfinite(h.stableStep) ? 0.95 * h.stableStep : std::max(d.time, 1.0);
  }
  // A thermal advance is a loop of steps: refuse one that would not end in any reasonable time.
  auto checkSteps = [&](double duration, const Origin& origin, const char* key) {
    const double steps = duration / h.step;
    if (steps > kHeatStepLimit)
      origin.fail(key, shown(duration) + " s of thermal time takes " + shown(std::ceil(steps)) + " steps of " + shown(h.step) +
                           " s, more than " + shown(kHeatStepLimit) + ": give a longer heat.step (with theta > 0 any step is stable)");
  };
  checkSteps(d.time, d.origin, "time");
  for (const PhaseDefinition& phase : s.phases)
    if (phase.heatTime) checkSteps(*phase.heatTime, phase.origin, "heat_time");
  // The zones are stress-free at the initial temperature: a held boundary's different temperature
  // is a change, whose thermal stress the first advance applies.
  h.zoneTemperature.assign(static_cast<std::size_t>(m.zones.size()), d.initialTemperature);
  h.on = true;
}

}  // namespace vdec
