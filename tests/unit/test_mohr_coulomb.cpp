// The Mohr-Coulomb return for zones at known stress states.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "core/errors.hpp"
#include "requirements.hpp"
#include "scene_fixture.hpp"
#include "zone/mohr_coulomb.hpp"

using namespace vdec;

namespace {

constexpr double K = 10e9 / (3 * 0.5), G = 10e9 / 2.5;  // E = 10 GPa, nu = 0.25
constexpr double a1 = K + 4 * G / 3, a2 = K - 2 * G / 3;

MohrCoulombProperties material(double frictionDeg, double cohesion, double dilationDeg, double tension) {
  auto n = [](double deg) {
    const double s = std::sin(deg * std::numbers::pi / 180.0);
    return (1 + s) / (1 - s);
  };
  return {n(frictionDeg), n(dilationDeg), cohesion, tension};
}

// Principal stresses (s1 <= s2 <= s3) including szz.
std::array<double, 3> principal(double sxx, double syy, double sxy, double szz) {
  const double c = 0.5 * (sxx + syy), r = std::hypot(0.5 * (sxx - syy), sxy);
  std::array<double, 3> p{c - r, c + r, szz};
  std::sort(p.begin(), p.end());
  return p;
}

}  // namespace

TEST(MohrCoulomb, ElasticStatesAreLeftAlone) {
  VDEC_REQUIREMENTS("REQ-MC-001");
  const MohrCoulombProperties mc = material(30, 1e6, 0, 0.5e6);
  double sxx = -1e6, syy = -3e6, sxy = 0.2e6, szz = -1e6;
  EXPECT_EQ(mohrCoulombReturn(mc, a1, a2, sxx, syy, sxy, szz), Elastic);
  EXPECT_EQ(sxx, -1e6);
  EXPECT_EQ(syy, -3e6);
  EXPECT_EQ(sxy, 0.2e6);
  EXPECT_EQ(szz, -1e6);
}

TEST(MohrCoulomb, ShearReturnLandsOnTheSurfaceAlongTheFlowDirection) {
  VDEC_REQUIREMENTS("REQ-MC-001");
  // c = 1 MPa, phi = 30 deg (N_phi = 3), psi = 10 deg; a trial stress beyond the surface.
  const MohrCoulombProperties mc = material(30, 1e6, 10, 0.5e6);
  double sxx = -1e6, syy = -9e6, sxy = 0.0, szz = -2.5e6;
  const auto before = principal(sxx, syy, sxy, szz);
  ASSERT_EQ(mohrCoulombReturn(mc, a1, a2, sxx, syy, sxy, szz), ShearNow);
  const auto after = principal(sxx, syy, sxy, szz);
  // On the surface: s1 = s3 N_phi - 2 c sqrt(N_phi).
  EXPECT_NEAR(after[0] - after[2] * 3.0 + 2e6 * std::sqrt(3.0), 0.0, 1e-6);
  // The correction is -lambda D dg/ds with g = s1 - s3 N_psi: its components stand in the
  // ratios (a1 - a2 N_psi) : a2 (1 - N_psi) : (a2 - a1 N_psi).
  const double nPsi = mc.nPsi;
  const double d1 = after[0] - before[0], d2 = after[1] - before[1], d3 = after[2] - before[2];
  EXPECT_NEAR(d2 / d1, a2 * (1 - nPsi) / (a1 - a2 * nPsi), 1e-9);
  EXPECT_NEAR(d3 / d1, (a2 - a1 * nPsi) / (a1 - a2 * nPsi), 1e-9);
  // The plastic strain is lambda (1, 0, -N_psi) with lambda < 0 (FLAC's sign: fs < 0 on
  // yielding): shortening along s1, extension along s3, and a volumetric part lambda (1 - N_psi),
  // positive (tension positive): dilation (N_psi > 1) opens the rock, by (N_psi - 1) for each
  // unit of plastic shortening.
  const double lambda = -d1 / (a1 - a2 * nPsi);
  EXPECT_LT(lambda, 0.0);
  EXPECT_GT(lambda * (1 - nPsi), 0.0);
}

TEST(MohrCoulomb, TensionCutOffCapsTheLargestStress) {
  VDEC_REQUIREMENTS("REQ-MC-001");
  const MohrCoulombProperties mc = material(30, 1e6, 0, 0.5e6);
  double sxx = 2e6, syy = -0.5e6, sxy = 0.0, szz = 0.3e6;  // sxx above the 0.5 MPa cut-off
  ASSERT_EQ(mohrCoulombReturn(mc, a1, a2, sxx, syy, sxy, szz), TensionNow);
  EXPECT_NEAR(sxx, 0.5e6, 1e-6);
  // The others move by (ft / a1) a2.
  const double shift = (0.5e6 - 2e6) / a1 * a2;
  EXPECT_NEAR(syy, -0.5e6 + shift, 1e-6);
  EXPECT_NEAR(szz, 0.3e6 + shift, 1e-6);
}

TEST(MohrCoulomb, OutOfPlaneStressTakesPartAsAPrincipalStress) {
  VDEC_REQUIREMENTS("REQ-MC-001");
  // In-plane the state is safe (s1 = -4, s3 = -2 MPa: fs = -4 + 6 + 3.46 > 0), but szz = -12 MPa
  // is the most compressive principal stress: with it fs = -12 + 6 + 3.46 < 0, the zone fails,
  // and the return moves szz.
  const MohrCoulombProperties mc = material(30, 1e6, 0, 0.5e6);
  double sxx = -2e6, syy = -4e6, sxy = 0.0, szz = -12e6;
  ASSERT_EQ(mohrCoulombReturn(mc, a1, a2, sxx, syy, sxy, szz), ShearNow);
  const auto after = principal(sxx, syy, sxy, szz);
  EXPECT_NEAR(after[0] - after[2] * 3.0 + 2e6 * std::sqrt(3.0), 0.0, 1e-6);
  EXPECT_GT(szz, -12e6);
}

TEST(MohrCoulomb, BadPropertiesAreErrorsAndDilationAboveFrictionWarns) {
  VDEC_REQUIREMENTS("REQ-MC-001");
  auto scene = [](const std::string& plastic) {
    return std::string(R"(
[model]
rounding = 0.01
[stop]
cycles = 1
[[block_material]]
name = "rock"
density = 2500.0
young = 10e9
poisson = 0.25
)") + plastic + R"(
[[block]]
name = "s"
material = "rock"
vertices = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
zoning = { nx = 1, ny = 1 }
)";
  };
  auto error = [&](const std::string& plastic, const std::string& name) {
    try {
      vdec::testing::sceneFromText(scene(plastic), name);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("friction = 30.0\ncohesion = -1.0\n", "mc-c").find("key 'block_material[0].cohesion': must be >= 0"),
            std::string::npos);
  EXPECT_NE(error("friction = 0.0\ncohesion = 1e6\n", "mc-phi0").find("must be in (0, 90) degrees"), std::string::npos);
  EXPECT_NE(error("friction = 95.0\ncohesion = 1e6\n", "mc-phi95").find("must be in (0, 90) degrees"), std::string::npos);
  EXPECT_NE(error("friction = 30.0\ncohesion = 1e6\ntension = 5e6\n", "mc-t").find("must not exceed the cone's apex"),
            std::string::npos);
  const Scene warned = vdec::testing::sceneFromText(scene("friction = 20.0\ncohesion = 0.0\ndilation = 25.0\n"), "mc-warn");
  ASSERT_EQ(warned.warnings.size(), 1u);
  EXPECT_NE(warned.warnings[0].find("generates energy"), std::string::npos);
}

TEST(MohrCoulomb, ReturnsOntoAnEdgeWhereTheFaceReturnWouldReorderThePrincipalStresses) {
  VDEC_REQUIREMENTS("REQ-MC-004");
  // c = 1 MPa, phi = 30 deg (N_phi = 3, 2 c sqrt(N_phi) = 3.46 MPa), psi = 0. A trial with the
  // two most compressive stresses nearly equal (szz just above sxx): the face return, which
  // moves s1 by a1 lambda and s2 by a2 lambda, would carry s1 past s2. The edge return must
  // land with both faces (1, 3) and (2, 3) on the surface, hence s1 = s2, by a correction in
  // the span of the two faces' D n, each with a multiplier of the yielding sign.
  const MohrCoulombProperties mc = material(30, 1e6, 0, 1e9);
  const double k = 2e6 * std::sqrt(3.0);
  double sxx = -20e6, syy = -1e6, sxy = 0.0, szz = -19.9e6;
  EXPECT_EQ(mohrCoulombReturn(mc, a1, a2, sxx, syy, sxy, szz), ShearNow);
  const auto p = principal(sxx, syy, sxy, szz);
  EXPECT_NEAR(p[0] - 3.0 * p[2] + k, 0.0, 1e-6);  // face (1, 3)
  EXPECT_NEAR(p[1] - 3.0 * p[2] + k, 0.0, 1e-6);  // face (2, 3)
  EXPECT_NEAR(p[0], p[1], 1e-6);
  // The correction (trial - returned) = l1 D (1, 0, -1) + l2 D (0, 1, -1) (psi = 0), with both
  // multipliers of the sign of a yielding face's, f / (m . D n) < 0: solve for l1, l2 from the
  // first two components and check the third.
  const double d1 = -20e6 - sxx, d2 = -19.9e6 - szz, d3 = -1e6 - syy;  // sxx -> s1, szz -> s2, syy -> s3
  // D (1, 0, -1) = (a1 - a2, 0, a2 - a1); D (0, 1, -1) = (0, a1 - a2, a2 - a1).
  const double l1 = d1 / (a1 - a2), l2 = d2 / (a1 - a2);
  EXPECT_LT(l1, 0.0);
  EXPECT_LT(l2, 0.0);
  EXPECT_NEAR(d3, (l1 + l2) * (a2 - a1), 1e-6 * std::abs(d3));
}

TEST(MohrCoulomb, ReturnsOntoTheOtherEdgeWhenTheTwoLeastCompressiveMeet) {
  VDEC_REQUIREMENTS("REQ-MC-004");
  // The two least compressive stresses nearly equal and a dilation angle: the face return moves
  // s2 by a2 (1 - N_psi) lambda and s3 by (a2 - a1 N_psi) lambda, which carries s2 past s3;
  // the edge return lands on faces (1, 3) and (1, 2) with s2 = s3.
  const MohrCoulombProperties mc = material(30, 1e6, 20, 1e9);
  const double k = 2e6 * std::sqrt(3.0);
  double sxx = -30e6, syy = -2.0e6, sxy = 0.0, szz = -2.05e6;
  EXPECT_EQ(mohrCoulombReturn(mc, a1, a2, sxx, syy, sxy, szz), ShearNow);
  const auto p = principal(sxx, syy, sxy, szz);
  EXPECT_NEAR(p[0] - 3.0 * p[2] + k, 0.0, 1e-6);  // face (1, 3)
  EXPECT_NEAR(p[0] - 3.0 * p[1] + k, 0.0, 1e-6);  // face (1, 2)
  EXPECT_NEAR(p[1], p[2], 1e-6);
}

TEST(MohrCoulomb, AFaceReturnThatKeepsTheOrderIsUnchangedByTheEdgeLogic) {
  VDEC_REQUIREMENTS("REQ-MC-004");
  // Well inside the face region: one face active, s2 moved only by a2 (1 - N_psi) lambda.
  const MohrCoulombProperties mc = material(30, 1e6, 10, 1e9);
  double sxx = -30e6, syy = -2e6, sxy = 0.0, szz = -10e6;
  const double nPsi = material(30, 0, 10, 0).nPsi;
  EXPECT_EQ(mohrCoulombReturn(mc, a1, a2, sxx, syy, sxy, szz), ShearNow);
  const auto p = principal(sxx, syy, sxy, szz);
  EXPECT_NEAR(p[0] - 3.0 * p[2] + 2e6 * std::sqrt(3.0), 0.0, 1e-6);
  const double lambda = (-30e6 - sxx) / (a1 - a2 * nPsi);
  EXPECT_NEAR(szz, -10e6 - lambda * a2 * (1.0 - nPsi), 1e-6);
}

TEST(MohrCoulomb, EveryReturnNearTheApexEndsOnOrInsideBothSurfaces) {
  VDEC_REQUIREMENTS("REQ-MC-004");
  // Trial stresses around the apex of the shear cone, with the tension cut-off at and below it:
  // the face returns alone can end beyond the other surface (a shear return above the cut-off,
  // a tension return outside the shear face, two stresses above the cut-off). Every returned
  // state must satisfy f_s >= 0 and s3 <= T (to round-off).
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const double phi : {30.0, 40.0})
    for (const double psi : {0.0, 10.0})
      for (const double tensionShare : {1.0, 0.5, 0.3}) {
        const double c = 1e6, apex = c / std::tan(phi * std::numbers::pi / 180.0);
        const MohrCoulombProperties mc = material(phi, c, psi, tensionShare * apex);
        const double k = 2.0 * c * std::sqrt(mc.nPhi);
        int returns = 0, outside = 0;
        for (int i = 0; i < 20000; ++i) {
          double sxx = apex * (1.0 - 3.0 * std::abs(u(random))) + 0.5 * c * u(random);
          double syy = apex * (1.0 - 3.0 * std::abs(u(random))) + 0.5 * c * u(random);
          double sxy = 0.5 * c * u(random), szz = apex * (1.0 - 3.0 * std::abs(u(random)));
          if (mohrCoulombReturn(mc, a1, a2, sxx, syy, sxy, szz) == Elastic) continue;
          ++returns;
          const auto p = principal(sxx, syy, sxy, szz);
          if (p[0] - p[2] * mc.nPhi + k < -1.0 || p[2] > mc.tension + 1.0) ++outside;
        }
        EXPECT_GT(returns, 5000);
        EXPECT_EQ(outside, 0) << "phi " << phi << ", psi " << psi << ", T = " << tensionShare << " x apex";
      }
}
