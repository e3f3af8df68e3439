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

// Updates c.elasticNormalStress, c.normalStress, c.shearStress and the state flags for the
// displacement increments (dun, dus) of one step. Returns the energy dissipated by slip in the
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
