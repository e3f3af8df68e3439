#include "motion/gridpoint_motion.hpp"

#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"
#include "core/vector_unit.hpp"

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

namespace {

// Gridpoints [begin, end) of one chunk, in tiles. The zone forces are summed first, each
// gridpoint's in zone order (the fixed order of the sum) from where the zone loop stored them
// (Zones::nodalForce), with the other inputs copied into arrays. The motion of the whole tile is
// then integrated in one loop without branches over arrays of doubles, which the compiler
// vectorises: a driven component keeps its velocity by a select, and each of the step's sums gets
// a term per component, zero where a plain gridpoint loop adds nothing (adding zero to a sum that
// starts at +0 leaves it bitwise unchanged). Last, the terms are added to the sums gridpoint by
// gridpoint and x before y, in locals that the model's arrays cannot alias; so the results are
// bitwise those of the plain loop. The rate of change of kinetic energy is divided by dt once per
// chunk, not per gridpoint. Compiled once per vector unit (core/vector_unit.hpp).
[[gnu::always_inline]] inline void integrateChunk(Model& m, double dt, double alpha, double local, int begin, int end,
                                                  MotionStepTotals& t) {
  Gridpoints& g = m.gridpoints;
  const Vec2* nodalForce = m.zones.nodalForce.data();
  const int* start = m.gridpointZones.start.data();
  const double lose = 1.0 - 0.5 * alpha * dt, keep = 1.0 / (1.0 + 0.5 * alpha * dt);
  const Vec2 gravity = m.gravity;
  const Vec2* contactForce = g.contactForce.empty() ? nullptr : g.contactForce.data();
  const Vec2* dashpotForce = g.dashpotForce.empty() ? nullptr : g.dashpotForce.data();
  const double* gravityMass = g.gravityMass.data();
  const double* massOf = g.mass.data();
  const Vec2* traction = g.tractionForce.data();
  const std::uint8_t* drivenOf = g.driven.data();
  Vec2* velocity = g.velocity.data();
  Vec2* position = g.position.data();
  double kinetic = 0.0, external = 0.0, damping = 0.0, boundary = 0.0, unbalancedMax = 0.0, speedMax = 0.0;
  double power = 0.0, rate = 0.0, lag = 0.0, scale = 0.0;
  int count = 0;
  constexpr int kTile = 64;
  // Stand-ins for absent contact and dashpot forces. A gathered zone force is never -0 (its sum
  // starts at +0), so adding these zeros leaves it bitwise as it was.
  const Vec2 noForce[kTile] = {};
  for (int tile = begin; tile < end; tile += kTile) {
    const int size = std::min(kTile, end - tile);
    const Vec2* contactTile = contactForce ? contactForce + tile : noForce;
    const Vec2* dashpotTile = dashpotForce ? dashpotForce + tile : noForce;
    // Per component c (x, y) and gridpoint k of the tile: the inputs, gathered and copied into
    // arrays of doubles.
    double internal[2][kTile], body[2][kTile], dashpot[2][kTile], u0[2][kTile], fixed[2][kTile];
    double mass[kTile], scaleX[kTile], scaleY[kTile];
    for (int k = 0; k < size; ++k) {
      const int i = tile + k;
      double sx = 0.0, sy = 0.0, bx = 0.0, by = 0.0;
      for (int s = start[i]; s < start[i + 1]; ++s) {
        const Vec2 f = nodalForce[s];
        sx += f.x, sy += f.y;
        bx += std::abs(f.x), by += std::abs(f.y);
      }
      scaleX[k] = bx, scaleY[k] = by;
      // Contact forces are internal, like the zones': the joints' springs hold their energy.
      internal[0][k] = sx + contactTile[k].x, internal[1][k] = sy + contactTile[k].y;
      body[0][k] = gravityMass[i] * gravity.x + traction[i].x, body[1][k] = gravityMass[i] * gravity.y + traction[i].y;
      dashpot[0][k] = dashpotTile[k].x, dashpot[1][k] = dashpotTile[k].y;
      u0[0][k] = velocity[i].x, u0[1][k] = velocity[i].y;
      fixed[0][k] = (drivenOf[i] & DriveX) ? 1.0 : 0.0, fixed[1][k] = (drivenOf[i] & DriveY) ? 1.0 : 0.0;
      mass[k] = massOf[i];
    }
    // The step's sums get a term per component and gridpoint.
    double u1[2][kTile], kineticTerm[2][kTile], lagTerm[2][kTile], externalTerm[2][kTile], localTerm[2][kTile];
    double massTerm[2][kTile], boundaryTerm[2][kTile], powerTerm[2][kTile], rateTerm[2][kTile], unbalanced[2][kTile];
    for (int c = 0; c < 2; ++c)
      for (int k = 0; k < size; ++k) {
        const bool isDriven = fixed[c][k] != 0.0;
        const double force = (internal[c][k] + body[c][k]) + dashpot[c][k], u = u0[c][k];
        // Local damping, -alpha_L |F| sgn(v), as localDampingForce.
        const double opposing = local * std::abs(force);
        const double localForce = local > 0.0 ? (u > 0.0 ? -opposing : (u < 0.0 ? opposing : 0.0)) : 0.0;
        const double moved = keep * (lose * u + (dt / mass[k]) * (force + localForce));
        const double v = isDriven ? u : moved;
        const double ubar = 0.5 * (u + v);
        u1[c][k] = v;
        // The driver's work on the block through zones and joints, or the loads' work.
        externalTerm[c][k] = isDriven ? -(internal[c][k] * u * dt) : body[c][k] * v * dt;
        localTerm[c][k] = isDriven ? 0.0 : localForce * ubar * dt;
        boundaryTerm[c][k] = isDriven ? 0.0 : dashpot[c][k] * ubar * dt;
        kineticTerm[c][k] = isDriven ? 0.0 : 0.25 * mass[k] * (u * u + v * v);
        lagTerm[c][k] = isDriven ? 0.0 : 0.5 * mass[k] * u * v;
        massTerm[c][k] = isDriven ? 0.0 : alpha * mass[k] * ubar * ubar * dt;
        powerTerm[c][k] = isDriven ? 0.0 : mass[k] * ubar * ubar;
        rateTerm[c][k] = isDriven ? 0.0 : mass[k] * ubar * (v - u);
        unbalanced[c][k] = isDriven ? 0.0 : force * force;
      }
    for (int k = 0; k < size; ++k) {
      const int i = tile + k;
      const Vec2 v1{u1[0][k], u1[1][k]};
      velocity[i] = v1;
      position[i] += dt * v1;
      for (int c = 0; c < 2; ++c) {
        damping -= localTerm[c][k];
        boundary -= boundaryTerm[c][k];
        kinetic += kineticTerm[c][k];
        lag += lagTerm[c][k];
        external += externalTerm[c][k];
        damping += massTerm[c][k];
        power += powerTerm[c][k];
        rate += rateTerm[c][k];
      }
      // The largest unbalanced force and speed are kept squared and rooted once at the end:
      // the square root is monotonic, so the largest root is the root of the largest square.
      if (fixed[0][k] == 0.0 || fixed[1][k] == 0.0) {
        unbalancedMax = std::max(unbalancedMax, (0.0 + unbalanced[0][k]) + unbalanced[1][k]);
        // The scale of the forces the zones put on the gridpoint, for the unbalanced-force
        // ratio: the sums of the components' magnitudes.
        scale += std::sqrt(scaleX[k] * scaleX[k] + scaleY[k] * scaleY[k]);
        ++count;
      }
      speedMax = std::max(speedMax, v1.x * v1.x + v1.y * v1.y);
    }
  }
  t.kineticEnergy = kinetic, t.externalWork = external, t.dampingDissipation = damping;
  t.boundaryDissipation = boundary, t.largestUnbalancedForce = unbalancedMax, t.largestDisplacement = speedMax;
  t.dampingPower = power, t.kineticRate = rate / dt, t.kineticLag = lag, t.forceScaleSum = scale, t.forceCount = count;
}

#if VDEC_VECTOR_UNITS
VDEC_TARGET_AVX512 void integrateAvx512(Model& m, double dt, double alpha, double local, int begin, int end,
                                        MotionStepTotals& t) {
  integrateChunk(m, dt, alpha, local, begin, end, t);
}
VDEC_TARGET_AVX2 void integrateAvx2(Model& m, double dt, double alpha, double local, int begin, int end,
                                    MotionStepTotals& t) {
  integrateChunk(m, dt, alpha, local, begin, end, t);
}
#endif
void integrateBaseline(Model& m, double dt, double alpha, double local, int begin, int end, MotionStepTotals& t) {
  integrateChunk(m, dt, alpha, local, begin, end, t);
}

}  // namespace

MotionStepTotals integrateGridpoints(Model& m, double dt, double alpha, double local) {
  auto chunk = integrateBaseline;
#if VDEC_VECTOR_UNITS
  if (vectorUnit() == VectorUnit::Avx512) chunk = integrateAvx512;
  if (vectorUnit() == VectorUnit::Avx2) chunk = integrateAvx2;
#endif
  MotionStepTotals totals = deterministicReduceChunks<MotionStepTotals>(
      m.gridpoints.size(), [&](int begin, int end, MotionStepTotals& t) { chunk(m, dt, alpha, local, begin, end, t); },
      [](MotionStepTotals& a, const MotionStepTotals& b) { a.merge(b); });
  totals.largestUnbalancedForce = std::sqrt(totals.largestUnbalancedForce);
  totals.largestDisplacement = std::sqrt(totals.largestDisplacement) * dt;
  return totals;
}

}  // namespace vdec
