#pragma once
// Constant-strain triangles of deformable blocks (NUREG/CR-5429 1.3.3.3, 1.4-105 to 1.4-117):
// strain rates from the gridpoint velocities (Wilkins' integral, exact for a triangle), the
// rotation of the stress with the zone, the plane-strain elastic law with szz tracked, and the
// forces each zone puts on its gridpoints.
#include "core/model.hpp"

namespace vdec {

struct ZoneStepTotals {
  double strainEnergy = 0.0;        // J/m, sum over zones of the elastic energy density times area
  double plasticDissipation = 0.0;  // J/m this step: the elastic energy the plastic return removed
  double viscousDissipation = 0.0;  // J/m this step: the work of the stiffness-proportional viscous stress
};

// One step: updates every zone's stress from the velocities of the half step just ended and
// stores the zone's nodal forces (Zones::nodalForce) where its gridpoints read them. With
// stiffnessDamping = beta > 0 (1.3-22), a zone that stays elastic in the step also carries the
// viscous stress beta D de / dt of its elastic stress increment in its nodal forces (not in its
// stress). Throws InstabilityError naming the zone if a zone turns inside out.
ZoneStepTotals computeZoneForces(Model& model, double dt, double stiffnessDamping = 0.0);

// Elastic energy density of a plane-strain stress state: p^2 / 2K + s:s / 4G.
double elasticEnergyDensity(double sxx, double syy, double sxy, double szz, double bulk, double shear);

// Set-up: gridpoint masses (rho A / 3 from each zone), the stiffness estimate k_i of 1.3-26 and
// 1.3-27, and the gridpoint-to-zone index. Throws GeometryError naming the block and zone for
// a zone of zero or negative area.
void prepareZones(Model& model);

// dt_z = 2 min_i sqrt(m_i / k_i) (1.3-25); infinity without zones.
double zoneTimeStep(const Model& model);

}  // namespace vdec
