#include "boundary/free_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vdec {

namespace {

struct Moduli {
  double lame, constrained, shear;  // lambda = K - 2G/3, M = K + 4G/3, G
};

Moduli moduliOf(const BlockMaterial& mat) {
  return {mat.bulk - 2.0 * mat.shear / 3.0, mat.bulk + 4.0 * mat.shear / 3.0, mat.shear};
}

// The column's velocity beside end k of a side edge.
Vec2 columnVelocity(const FreeFieldColumn& c, const FreeFieldEdge& edge, int k) {
  const int j = edge.node[k];
  const double w = edge.weight[k];
  return (1.0 - w) * c.nodeVelocity[j] + w * c.nodeVelocity[j + 1];
}

// The column's stress on one side edge, as nodal forces consistent with linear shape functions:
// the edge runs from height ya (gridpoint `from`) to yb, and each element it spans contributes its
// traction sigma_e . n over the part of the edge it covers.
void addColumnTraction(const FreeFieldColumn& c, const FreeFieldEdge& edge, double ya, double yb, Vec2 nL,
                       Gridpoints& g) {
  const double low = std::min(ya, yb), high = std::max(ya, yb);
  Vec2 toFrom, toTo;
  for (int e = edge.firstElement; e <= edge.lastElement; ++e) {
    const double s0 = std::max(low, c.nodeY[e]), s1 = std::min(high, c.nodeY[e + 1]);
    if (s1 <= s0) continue;
    // u runs from 0 at `from` to 1 at `to`; the integrals of (1 - u) and u over the overlap.
    const double u0 = (s0 - ya) / (yb - ya), u1 = (s1 - ya) / (yb - ya);
    const double du = std::abs(u1 - u0), mid = 0.5 * (u0 + u1);
    const Vec2 traction{c.sxx[e] * nL.x + c.sxy[e] * nL.y, c.sxy[e] * nL.x + c.syy[e] * nL.y};
    toFrom += ((1.0 - mid) * du) * traction;
    toTo += (mid * du) * traction;
  }
  g.tractionForce[edge.from] += toFrom;
  g.tractionForce[edge.to] += toTo;
}

// The column's element stresses at time t, incremented from the node velocities of the half
// step just ended (none at the model's first step, as for the zones), and the nodal forces of
// those stresses with the viscous stress of stiffness-proportional damping, beta D de/dt.
void formColumnForces(FreeFieldColumn& c, const std::vector<BlockMaterial>& materials, double strainStep, double beta,
                      std::vector<Vec2>& force) {
  const std::size_t nodes = c.nodeY.size();
  force.assign(nodes, Vec2{});
  for (std::size_t e = 0; e + 1 < nodes; ++e) {
    const double h = c.nodeY[e + 1] - c.nodeY[e];
    const Vec2 dv = c.nodeVelocity[e + 1] - c.nodeVelocity[e];
    const Moduli k = moduliOf(materials[c.elementMaterial[e]]);
    c.sxx[e] += k.lame * dv.y / h * strainStep;
    c.syy[e] += k.constrained * dv.y / h * strainStep;
    c.sxy[e] += k.shear * dv.x / h * strainStep;
    // An element in tension pulls its two nodes together.
    const Vec2 stress{c.sxy[e] + beta * k.shear * dv.x / h, c.syy[e] + beta * k.constrained * dv.y / h};
    force[e] += stress;
    force[e + 1] -= stress;
  }
}

// The column's base, dashpots of the medium below and the incident wave's stress 2 rho C v_in,
// then its motion to t + dt/2.
void moveColumn(FreeFieldColumn& c, double time, double dt, double alpha, const std::vector<TimeFunction>& functions,
                std::vector<Vec2>& force) {
  const double f = c.history < 0 ? 1.0 : functions[c.history](time - c.timeOrigin);
  const Vec2 v0 = c.nodeVelocity.front(), vin = f * c.inputVelocity;
  force.front() += Vec2{c.baseShearImpedance * (2.0 * vin.x - v0.x), c.baseNormalImpedance * (2.0 * vin.y - v0.y)};
  const double lose = 1.0 - 0.5 * alpha * dt, keep = 1.0 / (1.0 + 0.5 * alpha * dt);
  for (std::size_t j = 0; j < c.nodeY.size(); ++j)
    c.nodeVelocity[j] = keep * (lose * c.nodeVelocity[j] + (dt / c.nodeMass[j]) * force[j]);
}

}  // namespace

void keepStaticReactions(const Model& m, FreeFieldColumn& c) {
  c.reactionGridpoint.clear();
  c.reaction.clear();
  if (m.cycle == 0) return;
  const Gridpoints& g = m.gridpoints;
  std::vector<int> side;
  for (const FreeFieldEdge& e : c.edges) side.insert(side.end(), {e.from, e.to});
  std::sort(side.begin(), side.end());
  side.erase(std::unique(side.begin(), side.end()), side.end());
  // The loads in force now, at the present time: those of the conditions the phase keeps or adds.
  std::vector<Vec2> load(g.size());
  for (const LoadedEdge& e : m.loadedEdges) {
    const Vec2 traction = m.loadedEdgeForce(e);
    load[e.from] += 0.5 * traction;
    load[e.to] += 0.5 * traction;
  }
  for (const int i : side) {
    // The zones' and joints' forces of the step just taken hold the static state.
    Vec2 held = g.gravityMass[i] * m.gravity + load[i];
    for (int k = m.gridpointZones.start[i]; k < m.gridpointZones.start[i + 1]; ++k)
      held += m.zones.nodalForce[k];
    if (!g.contactForce.empty()) held += g.contactForce[i];
    // A component still driven keeps its support, which carries it.
    const Vec2 reaction{(g.driven[i] & DriveX) ? 0.0 : -held.x, (g.driven[i] & DriveY) ? 0.0 : -held.y};
    c.reactionGridpoint.push_back(i);
    c.reaction.push_back(reaction);
  }
}

void stepFreeFields(Model& m, double dt, double alpha, double beta) {
  Gridpoints& g = m.gridpoints;
  // Kept from step to step, so that the running model allocates nothing here.
  static thread_local std::vector<Vec2> force;
  for (FreeFieldColumn& c : m.freeFields) {
    formColumnForces(c, m.blockMaterials, m.cycle == 0 ? 0.0 : dt, beta, force);
    for (const FreeFieldEdge& edge : c.edges) {
      const Vec2 d = g.position[edge.to] - g.position[edge.from];
      const double length = norm(d);
      const Vec2 t = (1.0 / length) * d, n{t.y, -t.x};
      addColumnTraction(c, edge, g.initialPosition[edge.from].y, g.initialPosition[edge.to].y, {d.y, -d.x}, g);
      for (const int k : {0, 1}) {
        // Dashpots on the velocity relative to the column's: the part on the gridpoint's own
        // velocity dissipates (as a viscous boundary's), the column's part is a load.
        const int i = k == 0 ? edge.from : edge.to;
        const Vec2 v = g.velocity[i], vf = columnVelocity(c, edge, k);
        g.dashpotForce[i] -= (0.5 * length) * dashpotTraction(edge.normalImpedance, edge.shearImpedance, v, n, t);
        g.tractionForce[i] += (0.5 * length) * dashpotTraction(edge.normalImpedance, edge.shearImpedance, vf, n, t);
      }
    }
    for (std::size_t k = 0; k < c.reaction.size(); ++k) g.tractionForce[c.reactionGridpoint[k]] += c.reaction[k];
    moveColumn(c, m.time, dt, alpha, m.timeFunctions, force);
  }
}

double freeFieldTimeStep(const Model& m) {
  double step = std::numeric_limits<double>::infinity();
  for (const FreeFieldColumn& c : m.freeFields) {
    std::vector<double> rowSum(c.nodeY.size(), 0.0);
    for (std::size_t e = 0; e + 1 < c.nodeY.size(); ++e) {
      const double k = 2.0 * moduliOf(m.blockMaterials[c.elementMaterial[e]]).constrained / (c.nodeY[e + 1] - c.nodeY[e]);
      rowSum[e] += k;
      rowSum[e + 1] += k;
    }
    // With the base's dashpot c on the lagged velocity: (w dt)^2 + 2 c dt / m < 4 (as dashpotTimeStep).
    for (std::size_t j = 0; j < rowSum.size(); ++j) {
      const double dashpot = j == 0 ? std::max(c.baseNormalImpedance, c.baseShearImpedance) : 0.0, mass = c.nodeMass[j];
      step = std::min(step, 4.0 * mass / (dashpot + std::sqrt(dashpot * dashpot + 4.0 * rowSum[j] * mass)));
    }
  }
  return step;
}

}  // namespace vdec
