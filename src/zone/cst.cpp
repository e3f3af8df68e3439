#include "zone/cst.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/errors.hpp"
#include "core/parallel.hpp"
#include "core/vector_unit.hpp"

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
  zn.nodalForce.assign(3 * static_cast<std::size_t>(zn.size()), {});
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
  // 1.3-26: a gridpoint on an outline that can touch another block also carries the joints'
  // stiffness, the larger of kn and ks times the two outline segments at it, and at least 2 d:
  // a corner touching alone has the contact length d, and another contact can act on the
  // gridpoint through its edge.
  if (!g.contactForce.empty()) {
    double perLength = 0.0, point = 0.0;  // Pa/m of the joint laws; N/m of the point-contact law
    for (const JointMaterial& j : m.jointMaterials)
      (j.law == JointLaw::PointContact ? point : perLength) =
          std::max(j.law == JointLaw::PointContact ? point : perLength, std::max(j.kn, j.ks));
    const Vertices& vx = m.vertices;
    for (int v = 0; v < vx.size(); ++v)
      if (vx.gridpoint[v] >= 0)
        g.stiffness[vx.gridpoint[v]] +=
            point + perLength * std::max(vx.geometry[v].edgeLength + vx.geometry[vx.prev[v]].edgeLength,
                                         2.0 * m.roundingLength);
  }
  // The masses and stiffnesses the zone step is formed from (1.3-26): a density or modulus near the
  // largest double overflows here, and must be named rather than reach the step as inf or NaN.
  for (int i = 0; i < count; ++i) {
    if (std::isfinite(g.gravityMass[i]) && g.gravityMass[i] > 0.0 && std::isfinite(g.stiffness[i])) continue;
    if (g.driven[i] & Excavated) continue;  // no zone left: held at rest, massless
    const int material = m.blocks.material[g.block[i]];
    std::ostringstream s;
    s << "gridpoint at (" << g.position[i].x << ", " << g.position[i].y << ") of block '" << m.blocks.name[g.block[i]]
      << "': its mass " << g.gravityMass[i] << " kg/m and stiffness " << g.stiffness[i]
      << " N/m (1.3-26) are not both finite and positive: lower block_material[" << material
      << "].density, its elastic moduli, or the joint stiffness kn and ks";
    throw SceneError(s.str());
  }
  g.mass = g.gravityMass;
  // Each gridpoint's zone corners, in zone order: the order of the gridpoint's sum is fixed.
  GridpointZones& gz = m.gridpointZones;
  for (int i = 0; i < count; ++i) degree[i + 1] += degree[i];
  gz.start = degree;
  gz.place.assign(3 * static_cast<std::size_t>(zn.size()), 0);
  std::vector<int> fill(degree.begin(), degree.end() - 1);
  for (int z = 0; z < zn.size(); ++z)
    for (int c = 0; c < 3; ++c) gz.place[3 * z + c] = fill[zn.gridpoint[z][c]]++;
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
  bool plastic;  // the material's, here so that the gather of a tile need not follow the pointer
};

// p^2 / 2K + s:s / 4G, as elasticEnergyDensity, with the law's reciprocals 1 / 2K and 1 / 4G.
inline double energyDensity(double halfInverseBulk, double quarterInverseShear, double sxx, double syy, double sxy,
                            double szz) {
  const double p = (sxx + syy + szz) * (1.0 / 3.0);
  const double dx = sxx - p, dy = syy - p, dz = szz - p;
  return p * p * halfInverseBulk + (dx * dx + dy * dy + dz * dz + 2.0 * sxy * sxy) * quarterInverseShear;
}

struct ZoneSums {
  double strain = 0.0, plastic = 0.0, viscous = 0.0;
  int firstInverted = std::numeric_limits<int>::max();  // an inside-out zone, if any
};

// Zones [begin, end) of one chunk; compiled once per vector unit (core/vector_unit.hpp). The sums
// run in locals, which the stores to the model's arrays cannot alias.
[[gnu::always_inline]] inline void zoneForcesOfChunk(Model& m, const std::vector<ZoneLaw>& laws, double dt,
                                                     double viscous, int begin, int end, ZoneSums& acc) {
  Zones& zn = m.zones;
  const Gridpoints& g = m.gridpoints;
  Vec2* nodalForce = zn.nodalForce.data();
  const int* place = m.gridpointZones.place.data();
  double strainSum = 0.0, plasticSum = 0.0, viscousSum = 0.0;
  int firstInverted = std::numeric_limits<int>::max();
  // Zones go through in tiles: their gridpoints' positions and velocities are gathered into
  // arrays, and the arithmetic, the same for every elastic zone, runs over the tile in loops
  // without branches, which the compiler vectorises: the stress update, then the nodal forces
  // and energies. A tile holding a plastic or inside-out zone goes through zone by zone instead
  // for its forces (the return, the checks). The sums are added zone by zone in zone order on
  // either path, so the results are those of a zone-by-zone loop.
  constexpr int kTile = 64;
  for (int tile = begin; tile < end; tile += kTile) {
    const int size = std::min(kTile, end - tile);
    double p0x[kTile], p0y[kTile], p1x[kTile], p1y[kTile], p2x[kTile], p2y[kTile];
    double v0x[kTile], v0y[kTile], v1x[kTile], v1y[kTile], v2x[kTile], v2y[kTile];
    double sxx[kTile], syy[kTile], sxy[kTile], szz[kTile], a1[kTile], a2[kTile], twoG[kTile];
    double halfInverseBulk[kTile], quarterInverseShear[kTile];
    double twiceArea[kTile], halfStepArea[kTile], ex[kTile], ey[kTile], exy2[kTile];
    bool plasticTile = false;
    for (int k = 0; k < size; ++k) {
      const int z = tile + k;
      const auto& n = zn.gridpoint[z];
      const Vec2 q0 = g.position[n[0]], q1 = g.position[n[1]], q2 = g.position[n[2]];
      const Vec2 w0 = g.velocity[n[0]], w1 = g.velocity[n[1]], w2 = g.velocity[n[2]];
      p0x[k] = q0.x, p0y[k] = q0.y, p1x[k] = q1.x, p1y[k] = q1.y, p2x[k] = q2.x, p2y[k] = q2.y;
      v0x[k] = w0.x, v0y[k] = w0.y, v1x[k] = w1.x, v1y[k] = w1.y, v2x[k] = w2.x, v2y[k] = w2.y;
      sxx[k] = zn.sxx[z], syy[k] = zn.syy[z], sxy[k] = zn.sxy[z], szz[k] = zn.szz[z];
      const ZoneLaw& law = laws[zn.material[z]];
      a1[k] = law.a1, a2[k] = law.a2, twoG[k] = law.twoG;
      halfInverseBulk[k] = law.halfInverseBulk, quarterInverseShear[k] = law.quarterInverseShear;
      plasticTile |= law.plastic;
    }
    for (int k = 0; k < size; ++k) {
      twiceArea[k] = (p1x[k] - p0x[k]) * (p2y[k] - p0y[k]) - (p1y[k] - p0y[k]) * (p2x[k] - p0x[k]);
      // The increment v dt took the zone from x - v dt to x; its gradient is formed on the
      // configuration halfway (Hughes and Winget 1980), on which a rigid rotation has an
      // exactly skew gradient: no strain, and a spin whose rotation below is the rotation itself.
      const double m0x = p0x[k] - 0.5 * dt * v0x[k], m0y = p0y[k] - 0.5 * dt * v0y[k];
      const double m1x = p1x[k] - 0.5 * dt * v1x[k], m1y = p1y[k] - 0.5 * dt * v1y[k];
      const double m2x = p2x[k] - 0.5 * dt * v2x[k], m2y = p2y[k] - 0.5 * dt * v2y[k];
      halfStepArea[k] = (m1x - m0x) * (m2y - m0y) - (m1y - m0y) * (m2x - m0x);
      const double inv = 1.0 / halfStepArea[k];
      // Gradients of the linear shape functions; Wilkins' contour integral gives the same.
      const double bx0 = (m1y - m2y) * inv, bx1 = (m2y - m0y) * inv, bx2 = (m0y - m1y) * inv;
      const double by0 = (m2x - m1x) * inv, by1 = (m0x - m2x) * inv, by2 = (m1x - m0x) * inv;
      const double dvxdx = v0x[k] * bx0 + v1x[k] * bx1 + v2x[k] * bx2;
      const double dvxdy = v0x[k] * by0 + v1x[k] * by1 + v2x[k] * by2;
      const double dvydx = v0y[k] * bx0 + v1y[k] * bx1 + v2y[k] * bx2;
      const double dvydy = v0y[k] * by0 + v1y[k] * by1 + v2y[k] * by2;
      // Rotation of the stress with the zone (1.4-114): by the spin increment phi as the
      // exactly orthogonal rotation (I - W/2)^-1 (I + W/2), angle 2 atan(phi/2)
      // (Hughes-Winget); with the gradient on the half-step configuration this is the zone's
      // rotation itself. At phi = 0 it is exactly the identity.
      const double phi = 0.5 * (dvydx - dvxdy) * dt;
      const double q = 1.0 / (1.0 + 0.25 * phi * phi);
      const double c = (1.0 - 0.25 * phi * phi) * q, s = phi * q;
      const double rxx = c * c * sxx[k] - 2.0 * c * s * sxy[k] + s * s * syy[k];
      const double ryy = s * s * sxx[k] + 2.0 * c * s * sxy[k] + c * c * syy[k];
      const double rxy = c * s * (sxx[k] - syy[k]) + (c * c - s * s) * sxy[k];
      // Plane-strain elasticity (Hooke, 1.4-105, as the law M of 1.4-115): a1 = K + 4G/3,
      // a2 = K - 2G/3.
      const double exx = dvxdx * dt, eyy = dvydy * dt, exy = 0.5 * (dvxdy + dvydx) * dt;
      ex[k] = exx, ey[k] = eyy, exy2[k] = 2.0 * exy;
      sxx[k] = rxx + (a1[k] * exx + a2[k] * eyy);
      syy[k] = ryy + (a2[k] * exx + a1[k] * eyy);
      sxy[k] = rxy + twoG[k] * exy;
      szz[k] = szz[k] + a2[k] * (exx + eyy);
    }
    // Nodal forces (1.4-116) on the configuration reached: F_i = -A sigma grad N_i, which is
    // -(1/2) sigma (n1 S1 + n2 S2) over the two sides at node i; tension positive. `fxx`, `fyy`,
    // `fxy`: the zone's stress, with stiffness damping plus the viscous stress of its elastic
    // increment. And the zone's elastic energy.
    double f0x[kTile], f0y[kTile], f1x[kTile], f1y[kTile], f2x[kTile], f2y[kTile], energy[kTile];
    auto forces = [&](int k, double fxx, double fyy, double fxy) __attribute__((always_inline)) {
      const double cx0 = 0.5 * (p1y[k] - p2y[k]), cx1 = 0.5 * (p2y[k] - p0y[k]), cx2 = 0.5 * (p0y[k] - p1y[k]);
      const double cy0 = 0.5 * (p2x[k] - p1x[k]), cy1 = 0.5 * (p0x[k] - p2x[k]), cy2 = 0.5 * (p1x[k] - p0x[k]);
      f0x[k] = -(fxx * cx0 + fxy * cy0), f0y[k] = -(fxy * cx0 + fyy * cy0);
      f1x[k] = -(fxx * cx1 + fxy * cy1), f1y[k] = -(fxy * cx1 + fyy * cy1);
      f2x[k] = -(fxx * cx2 + fxy * cy2), f2y[k] = -(fxy * cx2 + fyy * cy2);
      energy[k] = (0.5 * twiceArea[k]) *
                  energyDensity(halfInverseBulk[k], quarterInverseShear[k], sxx[k], syy[k], sxy[k], szz[k]);
    };
    // The viscous stress of the elastic increment, whose work over the increment is dissipated.
    double work[kTile], vxx[kTile], vyy[kTile], vxy[kTile];
    auto viscousStress = [&](int k) __attribute__((always_inline)) {
      vxx[k] = viscous * (a1[k] * ex[k] + a2[k] * ey[k]), vyy[k] = viscous * (a2[k] * ex[k] + a1[k] * ey[k]);
      vxy[k] = viscous * twoG[k] * 0.5 * exy2[k];
      work[k] = (0.5 * twiceArea[k]) * (vxx[k] * ex[k] + vyy[k] * ey[k] + vxy[k] * exy2[k]);
    };
    auto store = [&](int k) __attribute__((always_inline)) {
      const int z = tile + k;
      zn.sxx[z] = sxx[k], zn.syy[z] = syy[k], zn.sxy[z] = sxy[k], zn.szz[z] = szz[k];
      const int* at = &place[3 * z];
      nodalForce[at[0]] = {f0x[k], f0y[k]}, nodalForce[at[1]] = {f1x[k], f1y[k]}, nodalForce[at[2]] = {f2x[k], f2y[k]};
    };
    bool invertedTile = false;
    for (int k = 0; k < size; ++k) invertedTile |= !(twiceArea[k] > 0.0) | !(halfStepArea[k] > 0.0);
    if (!plasticTile && !invertedTile) {
      if (viscous > 0.0) {
        for (int k = 0; k < size; ++k) {
          viscousStress(k);
          forces(k, sxx[k] + vxx[k], syy[k] + vyy[k], sxy[k] + vxy[k]);
        }
      } else {
        for (int k = 0; k < size; ++k) forces(k, sxx[k], syy[k], sxy[k]);
      }
      for (int k = 0; k < size; ++k) {
        store(k);
        strainSum += energy[k];
      }
      if (viscous > 0.0)
        for (int k = 0; k < size; ++k) viscousSum += work[k];
      continue;
    }
    for (int k = 0; k < size; ++k) {
      const int z = tile + k;
      if (!(twiceArea[k] > 0.0) || !(halfStepArea[k] > 0.0)) {
        firstInverted = std::min(firstInverted, z);
        continue;
      }
      const ZoneLaw& law = laws[zn.material[z]];
      const BlockMaterial& mat = *law.material;
      bool yielded = false;
      if (mat.plastic) {
        // The plastic strain of the return is C^-1 (trial - returned) and the stress over it
        // is on average (trial + returned) / 2, so the work it absorbs is W(trial) -
        // W(returned) for the quadratic elastic energy W: exact, and no further state is needed.
        const double trialEnergy = energyDensity(law.halfInverseBulk, law.quarterInverseShear, sxx[k], syy[k], sxy[k], szz[k]);
        const std::uint8_t now = mohrCoulombReturn(mat.mohrCoulomb, law.a1, law.a2, sxx[k], syy[k], sxy[k], szz[k]);
        if (now != Elastic)
          plasticSum += (0.5 * twiceArea[k]) *
                        (trialEnergy - energyDensity(law.halfInverseBulk, law.quarterInverseShear, sxx[k], syy[k], sxy[k], szz[k]));
        yielded = now != Elastic;
        zn.plasticState[z] = static_cast<std::uint8_t>(now | ((zn.plasticState[z] & (ShearNow | TensionNow | PlasticInPast)) ? PlasticInPast : 0));
      }
      // The viscous stress is dropped while the zone yields, as a slipping contact drops its
      // shear part.
      if (viscous > 0.0 && !yielded) {
        viscousStress(k);
        viscousSum += work[k];
        forces(k, sxx[k] + vxx[k], syy[k] + vyy[k], sxy[k] + vxy[k]);
      } else {
        forces(k, sxx[k], syy[k], sxy[k]);
      }
      store(k);
      strainSum += energy[k];
    }
  }
  acc.strain = strainSum, acc.plastic = plasticSum, acc.viscous = viscousSum, acc.firstInverted = firstInverted;
}

#if VDEC_VECTOR_UNITS
VDEC_TARGET_AVX512 void zoneForcesAvx512(Model& m, const std::vector<ZoneLaw>& laws, double dt, double viscous,
                                         int begin, int end, ZoneSums& acc) {
  zoneForcesOfChunk(m, laws, dt, viscous, begin, end, acc);
}
VDEC_TARGET_AVX2 void zoneForcesAvx2(Model& m, const std::vector<ZoneLaw>& laws, double dt, double viscous,
                                     int begin, int end, ZoneSums& acc) {
  zoneForcesOfChunk(m, laws, dt, viscous, begin, end, acc);
}
#endif
void zoneForcesBaseline(Model& m, const std::vector<ZoneLaw>& laws, double dt, double viscous, int begin, int end,
                        ZoneSums& acc) {
  zoneForcesOfChunk(m, laws, dt, viscous, begin, end, acc);
}

}  // namespace

ZoneStepTotals computeZoneForces(Model& m, double dt, double stiffnessDamping) {
  // Kept from step to step so that the running model allocates nothing here; the zone loop's
  // worker threads reach it through this reference (their own thread_local copies are empty).
  static thread_local std::vector<ZoneLaw> lawBuffer;
  std::vector<ZoneLaw>& laws = lawBuffer;
  laws.clear();
  for (const BlockMaterial& mat : m.blockMaterials)
    laws.push_back({mat.bulk + 4.0 * mat.shear / 3.0, mat.bulk - 2.0 * mat.shear / 3.0, 2.0 * mat.shear,
                    mat.bulk > 0.0 ? 0.5 / mat.bulk : 0.0, mat.shear > 0.0 ? 0.25 / mat.shear : 0.0, &mat, mat.plastic});
  // The viscous stress beta D de / dt: its factor on the elastic increment (none in the first step,
  // which takes no increment).
  const double viscous = dt > 0.0 ? stiffnessDamping / dt : 0.0;
  auto chunk = zoneForcesBaseline;
#if VDEC_VECTOR_UNITS
  if (vectorUnit() == VectorUnit::Avx512) chunk = zoneForcesAvx512;
  if (vectorUnit() == VectorUnit::Avx2) chunk = zoneForcesAvx2;
#endif
  const ZoneSums sums = deterministicReduceChunks<ZoneSums>(
      m.zones.size(), [&](int begin, int end, ZoneSums& acc) { chunk(m, laws, dt, viscous, begin, end, acc); },
      [](ZoneSums& total, const ZoneSums& part) {
        total.strain += part.strain;
        total.plastic += part.plastic;
        total.viscous += part.viscous;
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
  return {sums.strain, sums.plastic, sums.viscous};
}

}  // namespace vdec
