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
  }
}

}  // namespace vdec
