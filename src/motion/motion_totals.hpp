#pragma once
// What a motion stage (rigid blocks or gridpoints) reports of one step, summed the same way for
// both so that the cycle adds them without knowing which produced them; and the local damping
// force both stages apply.
#include <algorithm>
#include <cmath>

namespace vdec {

// Local damping: a force opposing the motion of each degree of freedom in proportion to the
// magnitude of its out-of-balance force, -alpha_L |F| sgn(v) (v at the start of the step), so
// that it vanishes at equilibrium whatever the velocity and damps every mode alike. vdec's
// alternative to mass damping (1.3-21), which resists steady motion and lets a suddenly applied
// load overshoot; see docs/models/deformable-blocks.md#local-damping.
inline double localDampingForce(double alphaLocal, double force, double velocity) {
  if (alphaLocal <= 0.0 || velocity == 0.0) return 0.0;
  return velocity > 0.0 ? -alphaLocal * std::abs(force) : alphaLocal * std::abs(force);
}

struct MotionStepTotals {
  double kineticEnergy = 0.0;       // time-centred: mean of the energies at t - dt/2 and t + dt/2
  double externalWork = 0.0;        // by gravity, applied loads, tractions and drivers over the step
  double dampingDissipation = 0.0;  // by mass damping (alpha m vbar^2 dt) or local damping (-F_d vbar dt)
  double boundaryDissipation = 0.0; // by viscous boundaries' dashpots (-F_v vbar dt)
  double largestUnbalancedForce = 0.0;
  double largestDisplacement = 0.0; // of any vertex or gridpoint over the step (bounds contact detection)
  double dampingPower = 0.0;        // sum m vbar^2 (times alpha: the power mass damping absorbs; 1.3-23)
  double kineticRate = 0.0;         // sum m vbar (v1 - v0) / dt, the rate of change of kinetic energy
  // sum m v0 v1 / 2 over the free degrees of freedom: beside the kinetic energy (sum m (v0^2 +
  // v1^2) / 4) it tells how much of the motion reverses every step (the step's Nyquist mode).
  double kineticLag = 0.0;
  // The scale of the forces for the unbalanced-force ratio: a sum of magnitudes and its count
  // (closed contacts' forces, or the zone forces on free gridpoints).
  double forceScaleSum = 0.0;
  int forceCount = 0;

  void merge(const MotionStepTotals& o) {
    kineticEnergy += o.kineticEnergy;
    externalWork += o.externalWork;
    dampingDissipation += o.dampingDissipation;
    boundaryDissipation += o.boundaryDissipation;
    largestUnbalancedForce = std::max(largestUnbalancedForce, o.largestUnbalancedForce);
    largestDisplacement = std::max(largestDisplacement, o.largestDisplacement);
    dampingPower += o.dampingPower;
    kineticRate += o.kineticRate;
    kineticLag += o.kineticLag;
    forceScaleSum += o.forceScaleSum;
    forceCount += o.forceCount;
  }
};

}  // namespace vdec
