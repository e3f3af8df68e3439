#pragma once
// Joint constitutive laws (NUREG/CR-5429 1.3-1 to 1.3-5, 1.4-132 to 1.4-136), in force form.
// Sign convention: normal force compression positive, normal displacement closing positive;
// shear force and displacement along the contact tangent.
#include "core/model.hpp"

namespace vdec {

// Updates c.elasticNormal, c.normalForce, c.shearForce and the state flags for the
// displacement increments (dun, dus) of one step. `weight` is the contact length L for the
// joint laws (stiffness in Pa/m, strengths in Pa) and 1 for the point-contact law (N/m).
inline void updateJointForces(const JointMaterial& j, Contact& c, double weight, double dun, double dus) {
  const bool fracture = j.law == JointLaw::CoulombFracture;
  const bool strengthAvailable = !fracture || c.intact;
  const bool pointContact = j.law == JointLaw::PointContact;
  const double tensileLimit = (strengthAvailable && !pointContact) ? j.tension * weight : 0.0;
  const double cohesion = (strengthAvailable && !pointContact) ? j.cohesion * weight : 0.0;
  const double kn = j.kn * weight, ks = j.ks * weight;

  c.elasticNormal += kn * dun;  // 1.4-132 / 1.4-134
  if (c.open) {
    if (c.elasticNormal >= 0.0) c.open = false;  // closed again where it was stress-free
  } else if (c.elasticNormal < -tensileLimit) {
    c.open = true;  // tensile failure or separation (1.3-4); #5 loses its strength for good
    if (fracture) c.intact = false;
  }
  c.slipping = false;
  if (c.open) {
    c.normalForce = 0.0;
    c.shearForce = 0.0;
    return;
  }
  c.normalForce = c.elasticNormal;
  const double strength = std::max(0.0, cohesion + c.normalForce * j.tanFriction);  // 1.3-5
  const double trial = c.shearForce + ks * dus;
  if (std::abs(trial) <= strength) {
    c.shearForce = trial;
    return;
  }
  c.slipping = true;
  const double slip = (std::abs(trial) - strength) / ks;  // plastic part of |dus|
  c.shearForce = trial > 0.0 ? strength : -strength;
  c.slipDissipation += strength * slip;
  // Dilation (1.4-136): the joint tries to open as it slips; against a held normal
  // displacement that shows as added compression.
  c.elasticNormal += kn * slip * j.tanDilation;
  if (fracture) c.intact = false;
}

}  // namespace vdec
