#include "boundary/viscous_boundary.hpp"

#include <cmath>

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

}  // namespace vdec
