#pragma once
// One degree of freedom of a lumped mass under central differences with mass damping alpha or
// local damping (1.3-21, as a rigid block's): the beams' and the cables' nodes.
#include "motion/motion_totals.hpp"

namespace vdec {

// v(t + dt/2) from v(t - dt/2) = v0 under the internal force (whose energy is counted as strain)
// and the body force (whose work is counted as external); the step's kinetic energy, damping and
// work added to `totals`.
inline double advanceLumped(MotionStepTotals& totals, double v0, double mass, double internal, double body,
                            double alpha, double local, double dt) {
  const double load = internal + body;
  const double damping = localDampingForce(local, load, v0);
  const double v1 = (1.0 / (1.0 + 0.5 * alpha * dt)) * ((1.0 - 0.5 * alpha * dt) * v0 + (dt / mass) * (load + damping));
  const double vbar = 0.5 * (v0 + v1);
  totals.kineticEnergy += 0.25 * mass * (v0 * v0 + v1 * v1);
  totals.kineticLag += 0.5 * mass * v0 * v1;
  totals.dampingDissipation += alpha * mass * vbar * vbar * dt - damping * vbar * dt;
  totals.dampingPower += mass * vbar * vbar;
  totals.kineticRate += mass * vbar * (v1 - v0) / dt;
  totals.externalWork += body * v1 * dt;
  return v1;
}

}  // namespace vdec
