#include "motion/gridpoint_motion.hpp"

#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"

namespace vdec {

void applyEdgeTractions(Model& m) {
  Gridpoints& g = m.gridpoints;
  for (const LoadedEdge& e : m.loadedEdges) {
    const Vec2 traction = m.loadedEdgeForce(e);
    g.tractionForce[e.from] += 0.5 * traction;
    g.tractionForce[e.to] += 0.5 * traction;
  }
}

void applyDrivenVelocities(Model& m, double dt) {
  // The velocity of the half step about to be taken, v(t + dt/2).
  for (const DrivenVelocity& d : m.drivenVelocities) {
    const double v = d.value * m.timeFunctions[d.history](m.time - d.timeOrigin + 0.5 * dt);
    (d.component == 0 ? m.gridpoints.velocity[d.gridpoint].x : m.gridpoints.velocity[d.gridpoint].y) = v;
  }
}

MotionStepTotals integrateGridpoints(Model& m, double dt, double alpha, double local) {
  Gridpoints& g = m.gridpoints;
  const Zones& zn = m.zones;
  const GridpointZones& gz = m.gridpointZones;
  const double lose = 1.0 - 0.5 * alpha * dt, keep = 1.0 / (1.0 + 0.5 * alpha * dt);
  const Vec2 gravity = m.gravity;
  const Vec2* contactForce = g.contactForce.empty() ? nullptr : g.contactForce.data();
  const Vec2* dashpotForce = g.dashpotForce.empty() ? nullptr : g.dashpotForce.data();
  auto step = [&](int i, MotionStepTotals& t) {
    Vec2 zoneForce, absolute;
    for (int k = gz.start[i]; k < gz.start[i + 1]; ++k) {
      const Vec2 f = zn.nodalForce[gz.slot[k] / 3][gz.slot[k] % 3];
      zoneForce += f;
      absolute += Vec2{std::abs(f.x), std::abs(f.y)};
    }
    // The scale of the forces the zones put on the gridpoint, for the unbalanced-force ratio:
    // the sums of the components' magnitudes, one square root per gridpoint.
    const double zoneMagnitude = norm(absolute);
    const Vec2 body = g.gravityMass[i] * gravity + g.tractionForce[i];
    // Contact forces are internal, like the zones': the joints' springs hold their energy.
    const Vec2 internal = contactForce ? zoneForce + contactForce[i] : zoneForce;
    const Vec2 dashpot = dashpotForce ? dashpotForce[i] : Vec2{};
    const Vec2 load = internal + body + dashpot;
    const Vec2 v0 = g.velocity[i];
    Vec2 v1 = v0;
    const double mass = g.mass[i];
    double unbalanced = 0.0;
    bool free = false;
    auto advance = [&](bool driven, double u0, double force, double bodyForce, double internalForce,
                       double dashpotComponent) {
      if (driven) {
        t.externalWork -= internalForce * u0 * dt;  // the driver's work on the block through zones and joints
        return u0;
      }
      free = true;
      unbalanced += force * force;
      const double damping = localDampingForce(local, force, u0);
      const double u1 = keep * (lose * u0 + (dt / mass) * (force + damping));
      const double ubar = 0.5 * (u0 + u1);
      t.dampingDissipation -= damping * ubar * dt;
      t.boundaryDissipation -= dashpotComponent * ubar * dt;
      t.kineticEnergy += 0.25 * mass * (u0 * u0 + u1 * u1);
      t.kineticLag += 0.5 * mass * u0 * u1;
      t.externalWork += bodyForce * u1 * dt;
      t.dampingDissipation += alpha * mass * ubar * ubar * dt;
      t.dampingPower += mass * ubar * ubar;
      t.kineticRate += mass * ubar * (u1 - u0) / dt;
      return u1;
    };
    v1.x = advance(g.driven[i] & DriveX, v0.x, load.x, body.x, internal.x, dashpot.x);
    v1.y = advance(g.driven[i] & DriveY, v0.y, load.y, body.y, internal.y, dashpot.y);
    // The largest unbalanced force and speed are kept squared and rooted once at the end:
    // the square root is monotonic, so the largest root is the root of the largest square.
    if (free) {
      t.largestUnbalancedForce = std::max(t.largestUnbalancedForce, unbalanced);
      t.forceScaleSum += zoneMagnitude;
      ++t.forceCount;
    }
    g.velocity[i] = v1;
    g.position[i] += dt * v1;
    t.largestDisplacement = std::max(t.largestDisplacement, v1.x * v1.x + v1.y * v1.y);
  };
  MotionStepTotals totals = deterministicReduce<MotionStepTotals>(
      g.size(), step, [](MotionStepTotals& a, const MotionStepTotals& b) { a.merge(b); });
  totals.largestUnbalancedForce = std::sqrt(totals.largestUnbalancedForce);
  totals.largestDisplacement = std::sqrt(totals.largestDisplacement) * dt;
  return totals;
}

}  // namespace vdec
