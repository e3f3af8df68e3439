#include "boundary/viscous_boundary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vdec {

void applyViscousBoundaries(Model& m) {
  Gridpoints& g = m.gridpoints;
  for (const ViscousEdge& e : m.viscousEdges) {
    const Vec2 d = g.position[e.to] - g.position[e.from];
    const double length = norm(d);
    const Vec2 t = (1.0 / length) * d, n{t.y, -t.x};  // n outward: the block lies to the left of from -> to
    for (const int i : {e.from, e.to}) {
      const Vec2 v = g.velocity[i];
      g.dashpotForce[i] -= (0.5 * length) * (e.normalImpedance * dot(v, n) * n + e.shearImpedance * dot(v, t) * t);
    }
    if (e.inputVelocity.x == 0.0 && e.inputVelocity.y == 0.0) continue;
    // An incident wave of particle velocity v_in: the stress 2 rho C v_in (Joyner and Chen 1975)
    // that, with the dashpot's -rho C v, leaves v = v_in in a model that sends nothing back. It
    // is a load: its work is external work, as a boundary stress's is.
    const double f = e.history < 0 ? 1.0 : m.timeFunctions[e.history](m.time - e.timeOrigin);
    const Vec2 vin = f * e.inputVelocity;
    const Vec2 force = 2.0 * length * (e.normalImpedance * dot(vin, n) * n + e.shearImpedance * dot(vin, t) * t);
    g.tractionForce[e.from] += 0.5 * force;
    g.tractionForce[e.to] += 0.5 * force;
  }
}

void applyRigidViscousBoundaries(Model& m) {
  Blocks& bl = m.blocks;
  for (const RigidViscousEdge& e : m.rigidViscousEdges) {
    const int b = e.block;
    const Vec2 c = bl.centroid[b], pa = m.vertices.geometry[e.from].position, pb = m.vertices.geometry[e.to].position;
    const Vec2 d = pb - pa;
    const double length = norm(d);
    const Vec2 t = (1.0 / length) * d, n{t.y, -t.x};
    const Vec2 v = bl.velocity[b];
    const double w = bl.angularVelocity[b];
    auto traction = [&](Vec2 p) {
      const Vec2 r = p - c;
      const Vec2 u = v + w * Vec2{-r.y, r.x};
      return -1.0 * (e.normalImpedance * dot(u, n) * n + e.shearImpedance * dot(u, t) * t);
    };
    const Vec2 mid = 0.5 * (pa + pb);
    const Vec2 ta = traction(pa), tm = traction(mid), tb = traction(pb);
    bl.dashpotForce[b] += length * tm;
    bl.dashpotMoment[b] += (length / 6.0) * (cross(pa - c, ta) + 4.0 * cross(mid - c, tm) + cross(pb - c, tb));
    if (e.inputVelocity.x == 0.0 && e.inputVelocity.y == 0.0) continue;
    const double f = e.history < 0 ? 1.0 : m.timeFunctions[e.history](m.time - e.timeOrigin);
    const Vec2 vin = f * e.inputVelocity;
    const Vec2 force = 2.0 * length * (e.normalImpedance * dot(vin, n) * n + e.shearImpedance * dot(vin, t) * t);
    bl.boundaryForce[b] += force;
    bl.boundaryMoment[b] += cross(mid - c, force);
  }
}

double rigidDashpotTimeStep(const Model& m, double frac) {
  const Blocks& bl = m.blocks;
  std::vector<double> translation(bl.size(), 0.0), rotation(bl.size(), 0.0);
  for (const RigidViscousEdge& e : m.rigidViscousEdges) {
    const Vec2 c = bl.centroid[e.block], pa = m.vertices.geometry[e.from].position, pb = m.vertices.geometry[e.to].position;
    const double z = std::max(e.normalImpedance, e.shearImpedance), length = norm(pb - pa);
    translation[e.block] += z * length;
    // The integral of z |r|^2 over the edge bounds its dashpots' resistance to rotation.
    const Vec2 ra = pa - c, rb = pb - c;
    rotation[e.block] += z * length * (dot(ra, ra) + dot(ra, rb) + dot(rb, rb)) / 3.0;
  }
  double jointStiffness = 0.0;
  for (const JointMaterial& j : m.jointMaterials) jointStiffness = std::max(jointStiffness, std::max(j.kn, j.ks));
  double step = std::numeric_limits<double>::infinity();
  // FRAC is the margin of the spring estimate (1.3-28), not of the dashpot's exact condition: the
  // spring enters as k / FRAC^2, so that the limit is FRAC 2 sqrt(m / k) without a dashpot and
  // tends to the dashpot's own 2 m / c when it dominates.
  auto limit = [&](double mass, double dashpot, double stiffness) {
    const double spring = stiffness / (frac * frac);
    if (dashpot > 0.0) step = std::min(step, 4.0 * mass / (dashpot + std::sqrt(dashpot * dashpot + 4.0 * spring * mass)));
  };
  for (int b = 0; b < bl.size(); ++b) {
    if (!bl.movesFreely(b)) continue;
    // Joint springs along the block's edges: kn l_typ (1.3-28) with l_typ no longer than the
    // block's diameter, and R^2 times that in rotation about a centroid at most R away.
    const double k = jointStiffness * 2.0 * bl.boundingRadius[b];
    limit(bl.mass[b], translation[b], k);
    limit(bl.inertia[b], rotation[b], k * bl.boundingRadius[b] * bl.boundingRadius[b]);
  }
  return step;
}

double dashpotTimeStep(const Model& m) {
  const Gridpoints& g = m.gridpoints;
  std::vector<double> dashpot(g.size(), 0.0);
  auto add = [&](int from, int to, double normalImpedance, double shearImpedance) {
    const double c = 0.5 * norm(g.position[to] - g.position[from]) * std::max(normalImpedance, shearImpedance);
    dashpot[from] += c;
    dashpot[to] += c;
  };
  for (const ViscousEdge& e : m.viscousEdges) add(e.from, e.to, e.normalImpedance, e.shearImpedance);
  for (const FreeFieldColumn& column : m.freeFields)
    for (const FreeFieldEdge& e : column.edges) add(e.from, e.to, e.normalImpedance, e.shearImpedance);
  double step = std::numeric_limits<double>::infinity();
  for (int i = 0; i < g.size(); ++i) {
    const double c = dashpot[i], k = g.stiffness[i], mass = g.mass[i];
    if (c > 0.0) step = std::min(step, 4.0 * mass / (c + std::sqrt(c * c + 4.0 * k * mass)));
  }
  return step;
}

}  // namespace vdec
