#pragma once
// Joint constitutive laws (NUREG/CR-5429 1.3-1 to 1.3-5, 1.4-132 to 1.4-136) in stress form:
// a joint contact carries normal and shear stress, and its forces are stress times contact
// length (Fn = sn L, Fs = tau L), so that where the length changes the stress stays continuous
// and a contact made or re-made mid-run carries the stress of the face around it. The point-
// contact law (#1) is the same update with forces and N/m stiffnesses, and L = 1.
// Sign convention: normal stress compression positive, normal displacement closing positive;
// shear stress and displacement along the contact tangent.
#include <algorithm>
#include <cmath>

#include "core/model.hpp"

namespace vdec {

// Continuously yielding joint (Cundall and Hart 1984, Lemos 1987; 1.4-137 to 1.4-146).

// Normal stiffness at normal stress sn: kn = an sn^en (1.4-137), never below the stiffness at
// zero stress, which a joint starting unloaded needs and the time step is set from.
inline double cyNormalStiffness(const JointMaterial& j, double sn) {
  if (j.knCoefficient <= 0.0 || sn <= 0.0) return j.kn;
  return std::max(j.kn, j.knCoefficient * std::pow(sn, j.knExponent));
}

// Shear stiffness at normal stress sn: ks = as sn^es (1.4-139), with the same floor.
inline double cyShearStiffness(const JointMaterial& j, double sn) {
  if (j.ksCoefficient <= 0.0 || sn <= 0.0) return j.ks;
  return std::max(j.ks, j.ksCoefficient * std::pow(sn, j.ksExponent));
}

// The normal stress at which an an sn^en stiffness overtakes the zero-stress one.
inline double cyKneeStress(const JointMaterial& j) {
  if (j.knCoefficient <= 0.0) return INFINITY;
  if (j.knExponent <= 0.0) return j.knCoefficient > j.kn ? 0.0 : INFINITY;
  return std::pow(j.kn / j.knCoefficient, 1.0 / j.knExponent);
}

// Energy stored in the normal spring at stress sn >= 0: the integral of s / kn(s) ds, in
// closed form on the two branches of kn.
inline double cyNormalSpringEnergy(const JointMaterial& j, double sn) {
  const double knee = cyKneeStress(j);
  if (sn <= knee) return 0.5 * sn * sn / j.kn;
  const double a = j.knCoefficient, e = j.knExponent;
  return 0.5 * knee * knee / j.kn + (std::pow(sn, 2.0 - e) - std::pow(knee, 2.0 - e)) / (a * (2.0 - e));
}

// The normal stress of a contact found already closed by `closure`: the loading curve of
// cyNormalStiffness integrated from zero stress.
inline double cyNormalStressOfClosure(const JointMaterial& j, double closure) {
  if (closure <= 0.0) return j.kn * closure;
  const double knee = cyKneeStress(j);
  const double kneeClosure = knee / j.kn;
  if (closure <= kneeClosure) return j.kn * closure;
  const double a = j.knCoefficient, e = j.knExponent, beyond = closure - kneeClosure;
  if (e == 1.0) return knee * std::exp(a * beyond);
  return std::pow(std::pow(knee, 1.0 - e) + a * (1.0 - e) * beyond, 1.0 / (1.0 - e));
}

// The closure at which the loading curve reaches normal stress sn: the inverse of
// cyNormalStressOfClosure (negative stress, an open joint, on the zero-stress slope).
inline double cyClosureOfNormalStress(const JointMaterial& j, double sn) {
  const double knee = cyKneeStress(j);
  if (sn <= knee) return sn / j.kn;
  const double a = j.knCoefficient, e = j.knExponent, kneeClosure = knee / j.kn;
  if (e == 1.0) return kneeClosure + std::log(sn / knee) / a;
  return kneeClosure + (std::pow(sn, 1.0 - e) - std::pow(knee, 1.0 - e)) / (a * (1.0 - e));
}

// The normal spring is elastic with one curve, so a closure increment moves the stress along the
// curve exactly: stress -> closure, add the increment, closure -> stress. Integrating
// kn(sn) dun with the stiffness of the start of the step instead (forward Euler) falls behind
// the curve on loading by O(dun) per step, and under a dead load, where equilibrium fixes the
// stress, the closure then ends 5 to 17 % beyond the curve's at the default FRAC.
inline double cyNormalStressAfter(const JointMaterial& j, double sn, double closureIncrement) {
  return cyNormalStressOfClosure(j, cyClosureOfNormalStress(j, sn) + closureIncrement);
}

// One step of the continuously yielding law. The joint has no tensile strength and no
// cohesion. Shear follows dtau = F ks dus (1.4-138) with F = (1 - tau/tau_m) / (1 - r)
// (1.4-140) towards the bounding strength tau_m = sn tan(phi_eff) sign(dus) (1.4-141); r is
// tau/tau_m at the last reversal, capped at 0.75. With tau_m and r held over the step this is a
// linear equation in tau, integrated exactly: an explicit F would overshoot tau_m, and oscillate
// about it, wherever one step's elastic increment ks |dus| exceeds (1 - r) |tau_m| (a joint at
// low normal stress). The tangent stays at most ks (F <= 1). phi_eff decays with the plastic
// shear displacement (1 - F)|dus| (1.4-142, 1.4-143), applied through the exact solution
// (1.4-144), so it cannot overshoot phi. Dilation at the angle i = atan(|tau|/sn) - phi where
// positive (1.4-145) accompanies the plastic shear displacement, as the slip of the Coulomb
// joint's dilation does; against a held normal displacement it shows as added compression.
// Returns the energy dissipated per unit length: the plastic work of the shear stress less the
// work of the dilation against the normal stress, sn dus_p (tan(phi + i) - tan i), which is
// positive whenever the shear stress acts along the shearing (not just after a reversal,
// while tau still has the old sign).
inline double updateContinuouslyYielding(const JointMaterial& j, Contact& c, YieldingState& y, double dun,
                                         double dus) {
  c.elasticNormalStress = cyNormalStressAfter(j, c.elasticNormalStress, dun);
  c.slipping = false;
  c.open = c.elasticNormalStress < 0.0;
  if (c.open) {
    c.normalStress = c.shearStress = 0.0;
    // Reclosed, the joint starts again from zero shear stress: no reversal to remember.
    y.reversalRatio = 0.0;
    y.shearDirection = 0;
    return 0.0;
  }
  const double sn = c.normalStress = c.elasticNormalStress;
  if (dus == 0.0 || sn == 0.0) return 0.0;
  const std::int8_t direction = dus > 0.0 ? 1 : -1;
  const double strength = sn * std::tan(y.effectiveFriction);
  const double target = direction * strength;  // tau_m
  if (y.shearDirection != 0 && direction != y.shearDirection)
    y.reversalRatio = std::min(c.shearStress / target, 0.75);
  y.shearDirection = direction;
  const double ks = cyShearStiffness(j, sn), path = std::abs(dus);
  const double tau = c.shearStress;
  // dtau/ds = ks (tau_m - tau) / ((1 - r) |tau_m|) along the path length s.
  double next = target + (tau - target) * std::exp(-ks * path / ((1.0 - y.reversalRatio) * strength));
  if (direction * (next - tau) > ks * path) next = tau + direction * ks * path;  // F <= 1
  c.shearStress = next;
  const double plastic = std::max(0.0, path - direction * (next - tau) / ks);
  y.plasticShear += plastic;
  y.effectiveFriction = j.friction + (y.effectiveFriction - j.friction) * std::exp(-plastic / j.roughness);
  const double meanTau = 0.5 * (tau + next);
  const double dilationAngle = std::atan(std::abs(meanTau) / sn) - j.friction;
  double dilationWork = 0.0;
  if (dilationAngle > 0.0) {
    const double opening = std::tan(dilationAngle) * plastic;
    c.elasticNormalStress = cyNormalStressAfter(j, c.elasticNormalStress, opening);
    dilationWork = sn * opening;
  }
  c.slipping = plastic > 0.0;
  return meanTau * direction * plastic - dilationWork;
}

// Energy stored in a closed contact's springs per unit length (times the weight, J/m).
inline double jointSpringEnergy(const JointMaterial& j, const Contact& c) {
  if (j.law == JointLaw::ContinuouslyYielding)
    return cyNormalSpringEnergy(j, c.normalStress) +
           0.5 * c.shearStress * c.shearStress / cyShearStiffness(j, c.normalStress);
  // One division: this runs twice per contact and step.
  return 0.5 * (c.normalStress * c.normalStress * j.ks + c.shearStress * c.shearStress * j.kn) / (j.kn * j.ks);
}

// The larger of a continuously yielding contact's normal and shear stiffness at its present
// normal stress (Pa/m).
inline double cyStiffness(const JointMaterial& j, const Contact& c) {
  return std::max(cyNormalStiffness(j, c.normalStress), cyShearStiffness(j, c.normalStress));
}

// A closed contact's length changed from L0 to L1 = L0 / ratio with the geometry, not by any
// displacement of its springs: the stresses are scaled so that the energy its springs hold,
// L W(sn, tau), stays what it was. Holding the stresses instead (forces scaling with L) made or
// destroyed W (L1 - L0) without work wherever the length changed, and where it changed in one
// step (a block tilting off a face) the pivot force dropped by most of its value.
inline void keepSpringEnergyAcrossLength(const JointMaterial& j, Contact& c, double ratio) {
  if (j.law == JointLaw::PointContact || ratio == 1.0) return;
  if (j.law != JointLaw::ContinuouslyYielding) {
    const double scale = std::sqrt(ratio);  // W = sn^2 / (2 kn) + tau^2 / (2 ks)
    c.elasticNormalStress *= scale;
    c.normalStress *= scale;
    c.shearStress *= scale;
    return;
  }
  // The normal spring's energy per length W_n(sn), convex and increasing for sn >= 0: Newton's
  // method on W_n(s) = ratio W_n(sn) from the linear guess converges in a few steps.
  const double sn0 = std::max(c.normalStress, 0.0), target = ratio * cyNormalSpringEnergy(j, sn0);
  double sn = sn0 * std::sqrt(ratio);
  for (int k = 0; k < 30 && sn > 0.0; ++k) {
    const double step = (cyNormalSpringEnergy(j, sn) - target) / (sn / cyNormalStiffness(j, sn));
    sn = std::max(sn - step, 0.5 * sn);
    if (std::abs(step) <= 1e-14 * sn) break;
  }
  c.shearStress *= std::sqrt(ratio * cyShearStiffness(j, sn) / cyShearStiffness(j, sn0));
  c.normalStress = sn;
  c.elasticNormalStress = sn;
}

// Updates c.elasticNormalStress, c.normalStress, c.shearStress and the state flags for the
// displacement increments (dun, dus) of one step, for the point-contact and Coulomb laws (the
// continuously yielding law, with its own state, is updateContinuouslyYielding). Returns the energy dissipated by slip in the
// step per unit contact length (times L, J/m): the shear stress's plastic work less what the
// dilation stores in the normal spring by opening against the normal stress.
inline double updateJointStresses(const JointMaterial& j, Contact& c, double dun, double dus) {
  const bool fracture = j.law == JointLaw::CoulombFracture;
  const bool strengthAvailable = (!fracture || c.intact) && j.law != JointLaw::PointContact;
  const double tensileLimit = strengthAvailable ? j.tension : 0.0;
  const double cohesion = strengthAvailable ? j.cohesion : 0.0;

  c.elasticNormalStress += j.kn * dun;  // 1.4-132 / 1.4-134
  if (c.open) {
    if (c.elasticNormalStress >= 0.0) c.open = false;  // closed again where it was stress-free
  } else if (c.elasticNormalStress < -tensileLimit) {
    c.open = true;  // tensile failure or separation (1.3-4); #5 loses its strength for good
    if (fracture) c.intact = false;
  }
  c.slipping = false;
  if (c.open) {
    c.normalStress = 0.0;
    c.shearStress = 0.0;
    return 0.0;
  }
  c.normalStress = c.elasticNormalStress;
  const double strength = std::max(0.0, cohesion + c.normalStress * j.tanFriction);  // 1.3-5
  const double trial = c.shearStress + j.ks * dus;
  if (std::abs(trial) <= strength) {
    c.shearStress = trial;
    return 0.0;
  }
  c.slipping = true;
  const double slip = (std::abs(trial) - strength) / j.ks;  // plastic part of |dus|
  c.shearStress = trial > 0.0 ? strength : -strength;
  // Dilation (1.4-136): the joint tries to open as it slips; against a held normal
  // displacement that shows as added compression.
  const double normalBefore = c.normalStress;
  c.elasticNormalStress += j.kn * slip * j.tanDilation;
  if (fracture) c.intact = false;
  return (strength - normalBefore * j.tanDilation) * slip;
}

}  // namespace vdec
