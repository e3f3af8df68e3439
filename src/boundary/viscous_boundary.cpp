#include "boundary/viscous_boundary.hpp"

#include <algorithm>
#include <array>
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
      g.dashpotForce[i] -= (0.5 * length) * dashpotTraction(e.normalImpedance, e.shearImpedance, v, n, t);
    }
    if (e.inputVelocity.x == 0.0 && e.inputVelocity.y == 0.0) continue;
    // An incident wave of particle velocity v_in: the stress 2 rho C v_in (Joyner and Chen 1975)
    // that, with the dashpot's -rho C v, leaves v = v_in in a model that sends nothing back. It
    // is a load: its work is external work, as a boundary stress's is.
    const double f = e.history < 0 ? 1.0 : m.timeFunctions[e.history](m.time - e.timeOrigin);
    const Vec2 vin = f * e.inputVelocity;
    const Vec2 force = 2.0 * length * dashpotTraction(e.normalImpedance, e.shearImpedance, vin, n, t);
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
      return -1.0 * dashpotTraction(e.normalImpedance, e.shearImpedance, u, n, t);
    };
    const Vec2 mid = 0.5 * (pa + pb);
    const Vec2 ta = traction(pa), tm = traction(mid), tb = traction(pb);
    bl.dashpotForce[b] += length * tm;
    bl.dashpotMoment[b] += (length / 6.0) * (cross(pa - c, ta) + 4.0 * cross(mid - c, tm) + cross(pb - c, tb));
    if (e.inputVelocity.x == 0.0 && e.inputVelocity.y == 0.0) continue;
    const double f = e.history < 0 ? 1.0 : m.timeFunctions[e.history](m.time - e.timeOrigin);
    const Vec2 vin = f * e.inputVelocity;
    const Vec2 force = 2.0 * length * dashpotTraction(e.normalImpedance, e.shearImpedance, vin, n, t);
    bl.boundaryForce[b] += force;
    bl.boundaryMoment[b] += cross(mid - c, force);
  }
}

double rigidDashpotTimeStep(const Model& m, double frac) {
  const Blocks& bl = m.blocks;
  // Per block, the dashpots' matrix on the translation (xx, xy, yy) and on the rotation (ww).
  std::vector<std::array<double, 4>> c(bl.size(), std::array<double, 4>{});
  for (const RigidViscousEdge& e : m.rigidViscousEdges) {
    const Vec2 centre = bl.centroid[e.block], pa = m.vertices.geometry[e.from].position, pb = m.vertices.geometry[e.to].position;
    const Vec2 d = pb - pa;
    const double length = norm(d);
    const Vec2 t = (1.0 / length) * d, n{t.y, -t.x};
    const double zn = e.normalImpedance, zs = e.shearImpedance;
    std::array<double, 4>& k = c[e.block];
    k[0] += length * (zn * n.x * n.x + zs * t.x * t.x);
    k[1] += length * (zn * n.x * n.y + zs * t.x * t.y);
    k[2] += length * (zn * n.y * n.y + zs * t.y * t.y);
    // The integral of Zn (r x n)^2 + Zs (r x t)^2 along the edge, r x n and r x t linear in it.
    auto squared = [&](double a, double b) { return length * (a * a + a * b + b * b) / 3.0; };
    const Vec2 ra = pa - centre, rb = pb - centre;
    k[3] += zn * squared(cross(ra, n), cross(rb, n)) + zs * squared(cross(ra, t), cross(rb, t));
  }
  double jointStiffness = 0.0;
  for (const JointMaterial& j : m.jointMaterials) jointStiffness = std::max(jointStiffness, std::max(j.kn, j.ks));
  double step = std::numeric_limits<double>::infinity();
  for (int b = 0; b < bl.size(); ++b) {
    const std::array<double, 4>& k = c[b];
    if (!bl.movesFreely(b) || k[0] + k[2] + k[3] == 0.0) continue;
    // The edges couple translation and rotation: the fastest decay rate of M^-1 C is at most the
    // sum of the rates of its two diagonal blocks (C positive semi-definite). The joint springs as
    // in 1.3-28: kn l_typ with l_typ no longer than the block's diameter, over the mass.
    const double mean = 0.5 * (k[0] + k[2]), spread = std::hypot(0.5 * (k[0] - k[2]), k[1]);
    const double rate = (mean + spread) / bl.mass[b] + k[3] / bl.inertia[b];
    const double spring = jointStiffness * 2.0 * bl.boundingRadius[b] / bl.mass[b];
    step = std::min(step, frac * 4.0 / (rate + std::sqrt(rate * rate + 4.0 * spring)));
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
