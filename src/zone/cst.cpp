#include "zone/cst.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/errors.hpp"
#include "core/parallel.hpp"

namespace vdec {

double elasticEnergyDensity(double sxx, double syy, double sxy, double szz, double bulk, double shear) {
  const double p = (sxx + syy + szz) / 3.0;
  const double dx = sxx - p, dy = syy - p, dz = szz - p;
  return p * p / (2.0 * bulk) + (dx * dx + dy * dy + dz * dz + 2.0 * sxy * sxy) / (4.0 * shear);
}

namespace {

std::string zoneName(const Model& m, int z) {
  int first = z;
  while (first > 0 && m.zones.block[first - 1] == m.zones.block[z]) --first;
  return "zone " + std::to_string(z - first) + " of block '" + m.blocks.name[m.zones.block[z]] + "'";
}

}  // namespace

void prepareZones(Model& m) {
  Gridpoints& g = m.gridpoints;
  Zones& zn = m.zones;
  const int count = g.size();
  g.mass.assign(count, 0.0);
  g.gravityMass.assign(count, 0.0);
  g.stiffness.assign(count, 0.0);
  zn.nodalForce.assign(zn.size(), {});
  std::vector<int> degree(count + 1, 0);
  for (int z = 0; z < zn.size(); ++z) {
    const auto& n = zn.gridpoint[z];
    const Vec2 p0 = g.position[n[0]], p1 = g.position[n[1]], p2 = g.position[n[2]];
    const double area = 0.5 * cross(p1 - p0, p2 - p0);
    const double longest = std::max({norm(p1 - p0), norm(p2 - p1), norm(p0 - p2)});
    if (!(area > 1e-12 * longest * longest)) {
      std::ostringstream s;
      s << zoneName(m, z) << " has area " << area << " m^2 (gridpoints at (" << p0.x << ", " << p0.y << "), ("
        << p1.x << ", " << p1.y << "), (" << p2.x << ", " << p2.y << ")): a degenerate or inverted zone; "
        << "change the zoning of the block";
      throw GeometryError(s.str());
    }
    const BlockMaterial& mat = m.blockMaterials[zn.material[z]];
    const double hMin = 2.0 * area / longest;
    const double k = (8.0 / 3.0) * (mat.bulk + 4.0 * mat.shear / 3.0) * longest / hMin;  // 1.3-27
    for (int c = 0; c < 3; ++c) {
      g.gravityMass[n[c]] += mat.density * area / 3.0;
      g.stiffness[n[c]] += k;
      ++degree[n[c] + 1];
    }
  }
  g.mass = g.gravityMass;
  // Gridpoint -> (zone, corner) slots, in zone order: the gather order is fixed.
  GridpointZones& gz = m.gridpointZones;
  for (int i = 0; i < count; ++i) degree[i + 1] += degree[i];
  gz.start = degree;
  gz.slot.assign(3 * zn.size(), 0);
  std::vector<int> fill(degree.begin(), degree.end() - 1);
  for (int z = 0; z < zn.size(); ++z)
    for (int c = 0; c < 3; ++c) gz.slot[fill[zn.gridpoint[z][c]]++] = 3 * z + c;
}

double zoneTimeStep(const Model& m) {
  double dt = INFINITY;
  const Gridpoints& g = m.gridpoints;
  for (int i = 0; i < g.size(); ++i)
    if (g.stiffness[i] > 0.0) dt = std::min(dt, 2.0 * std::sqrt(g.mass[i] / g.stiffness[i]));
  return dt;
}

namespace {

// What the zone loop needs of a material, with its divisions done once.
struct ZoneLaw {
  double a1, a2, twoG, halfInverseBulk, quarterInverseShear;
  const BlockMaterial* material;
};

}  // namespace

ZoneStepTotals computeZoneForces(Model& m, double dt) {
  // Kept from step to step so that the running model allocates nothing here; the zone loop's
  // worker threads reach it through this reference (their own thread_local copies are empty).
  static thread_local std::vector<ZoneLaw> lawBuffer;
  std::vector<ZoneLaw>& laws = lawBuffer;
  laws.clear();
  for (const BlockMaterial& mat : m.blockMaterials)
    laws.push_back({mat.bulk + 4.0 * mat.shear / 3.0, mat.bulk - 2.0 * mat.shear / 3.0, 2.0 * mat.shear,
                    mat.bulk > 0.0 ? 0.5 / mat.bulk : 0.0, mat.shear > 0.0 ? 0.25 / mat.shear : 0.0, &mat});
  // p^2 / 2K + s:s / 4G, as elasticEnergyDensity, with the law's reciprocals.
  auto energyDensity = [](const ZoneLaw& law, double sxx, double syy, double sxy, double szz) {
    const double p = (sxx + syy + szz) * (1.0 / 3.0);
    const double dx = sxx - p, dy = syy - p, dz = szz - p;
    return p * p * law.halfInverseBulk + (dx * dx + dy * dy + dz * dz + 2.0 * sxy * sxy) * law.quarterInverseShear;
  };
  Zones& zn = m.zones;
  const Gridpoints& g = m.gridpoints;
  const int count = zn.size();
  struct Sums {
    double strain = 0.0, plastic = 0.0;
    int firstInverted = std::numeric_limits<int>::max();  // an inside-out zone, if any
  };
  const Sums sums = deterministicReduce<Sums>(count, [&](int z, Sums& acc) {
    const auto& n = zn.gridpoint[z];
    const Vec2 p0 = g.position[n[0]], p1 = g.position[n[1]], p2 = g.position[n[2]];
    const double twiceArea = cross(p1 - p0, p2 - p0);
    if (!(twiceArea > 0.0)) {
      acc.firstInverted = std::min(acc.firstInverted, z);
      return;
    }
    const Vec2 v[3] = {g.velocity[n[0]], g.velocity[n[1]], g.velocity[n[2]]};
    // The increment v dt took the zone from x - v dt to x; its gradient is formed on the
    // configuration halfway (Hughes and Winget 1980), on which a rigid rotation has an exactly
    // skew gradient: no strain, and a spin whose rotation below is the rotation itself.
    const Vec2 m0 = p0 - 0.5 * dt * v[0], m1 = p1 - 0.5 * dt * v[1], m2 = p2 - 0.5 * dt * v[2];
    const double halfStepArea = cross(m1 - m0, m2 - m0);
    if (!(halfStepArea > 0.0)) {
      acc.firstInverted = std::min(acc.firstInverted, z);
      return;
    }
    const double inv = 1.0 / halfStepArea;
    // Gradients of the linear shape functions; Wilkins' contour integral gives the same.
    const double bx[3] = {(m1.y - m2.y) * inv, (m2.y - m0.y) * inv, (m0.y - m1.y) * inv};
    const double by[3] = {(m2.x - m1.x) * inv, (m0.x - m2.x) * inv, (m1.x - m0.x) * inv};
    double dvxdx = 0.0, dvxdy = 0.0, dvydx = 0.0, dvydy = 0.0;
    for (int c = 0; c < 3; ++c) {
      dvxdx += v[c].x * bx[c];
      dvxdy += v[c].x * by[c];
      dvydx += v[c].y * bx[c];
      dvydy += v[c].y * by[c];
    }
    const ZoneLaw& law = laws[zn.material[z]];
    const BlockMaterial& mat = *law.material;
    double sxx = zn.sxx[z], syy = zn.syy[z], sxy = zn.sxy[z];
    // Rotation of the stress with the zone (1.4-114): by the spin increment phi as the exactly
    // orthogonal rotation (I - W/2)^-1 (I + W/2), angle 2 atan(phi/2) (Hughes-Winget); with the
    // gradient on the half-step configuration this is the zone's rotation itself.
    const double phi = 0.5 * (dvydx - dvxdy) * dt;
    if (phi != 0.0) {
      const double q = 1.0 / (1.0 + 0.25 * phi * phi);
      const double c = (1.0 - 0.25 * phi * phi) * q, s = phi * q;
      const double rxx = c * c * sxx - 2.0 * c * s * sxy + s * s * syy;
      const double ryy = s * s * sxx + 2.0 * c * s * sxy + c * c * syy;
      const double rxy = c * s * (sxx - syy) + (c * c - s * s) * sxy;
      sxx = rxx;
      syy = ryy;
      sxy = rxy;
    }
    // Plane-strain elasticity (Hooke, 1.4-105, as the law M of 1.4-115): a1 = K + 4G/3, a2 = K - 2G/3.
    const double exx = dvxdx * dt, eyy = dvydy * dt, exy = 0.5 * (dvxdy + dvydx) * dt;
    const double a1 = law.a1, a2 = law.a2;
    sxx += a1 * exx + a2 * eyy;
    syy += a2 * exx + a1 * eyy;
    sxy += law.twoG * exy;
    double szz = zn.szz[z] + a2 * (exx + eyy);
    const double area = 0.5 * twiceArea;
    if (mat.plastic) {
      // The plastic strain of the return is C^-1 (trial - returned) and the stress over it is on
      // average (trial + returned) / 2, so the work it absorbs is W(trial) - W(returned) for the
      // quadratic elastic energy W: exact, and no further state is needed.
      const double trialEnergy = energyDensity(law, sxx, syy, sxy, szz);
      const std::uint8_t now = mohrCoulombReturn(mat.mohrCoulomb, a1, a2, sxx, syy, sxy, szz);
      if (now != Elastic) acc.plastic += area * (trialEnergy - energyDensity(law, sxx, syy, sxy, szz));
      zn.plasticState[z] = static_cast<std::uint8_t>(now | ((zn.plasticState[z] & (ShearNow | TensionNow | PlasticInPast)) ? PlasticInPast : 0));
    }
    zn.sxx[z] = sxx;
    zn.syy[z] = syy;
    zn.sxy[z] = sxy;
    zn.szz[z] = szz;
    // Nodal forces (1.4-116) on the configuration reached: F_i = -A sigma grad N_i, which is
    // -(1/2) sigma (n1 S1 + n2 S2) over the two sides at node i; tension positive.
    const double cx[3] = {0.5 * (p1.y - p2.y), 0.5 * (p2.y - p0.y), 0.5 * (p0.y - p1.y)};
    const double cy[3] = {0.5 * (p2.x - p1.x), 0.5 * (p0.x - p2.x), 0.5 * (p1.x - p0.x)};
    for (int c = 0; c < 3; ++c)
      zn.nodalForce[z][c] = {-(sxx * cx[c] + sxy * cy[c]), -(sxy * cx[c] + syy * cy[c])};
    acc.strain += area * energyDensity(law, sxx, syy, sxy, szz);
  }, [](Sums& total, const Sums& part) {
    total.strain += part.strain;
    total.plastic += part.plastic;
    total.firstInverted = std::min(total.firstInverted, part.firstInverted);
  });
  const bool inverted = sums.firstInverted != std::numeric_limits<int>::max();
  const int firstInverted = sums.firstInverted;
  if (inverted) {
    std::ostringstream s;
    s << zoneName(m, firstInverted) << " has turned inside out at cycle " << m.cycle << ", time " << m.time
      << " s: the zone was crushed or the motion is unstable; check the loads and the boundary conditions, and "
      << "that no joint or contact stiffness far above the zones' shortens the stable step";
    throw InstabilityError(s.str());
  }
  return {sums.strain, sums.plastic};
}

}  // namespace vdec
