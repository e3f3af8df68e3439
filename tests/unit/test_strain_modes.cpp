// Simply-deformable blocks' kinematics, generalised forces and masses (motion/strain_modes.hpp),
// each against an independent route: the virtual work of the strained positions by finite
// differences, a rotation written out as matrices, and the mass by quadrature of the mode fields.
#include <cmath>

#include "contact/contact_geometry.hpp"
#include "geometry/polygon.hpp"
#include "motion/strain_modes.hpp"
#include "requirements.hpp"
#include "scene_fixture.hpp"

using namespace vdec;

namespace {

// A free trapezoid (not symmetric, so that every coupling of its mass is non-zero) of a
// simply-deformable block, alone in its scene.
Scene trapezoid() {
  return vdec::testing::sceneFromText(R"(
[model]
rounding = 0.01
gravity = [0.0, 0.0]
[[block_material]]
name = "rock"
density = 2000.0
young = 10e9
poisson = 0.2
[[joint_material]]
name = "joint"
kn = 1e10
ks = 1e10
[[block]]
name = "t"
material = "rock"
kind = "simply-deformable"
vertices = [[0.0, 0.0], [3.0, 0.0], [2.2, 1.5], [0.4, 1.1]]
[stop]
cycles = 1
)", "trapezoid");
}

// The world position of body point X: c + R (I + E) X.
Vec2 worldPoint(const Model& m, int b, Vec2 X, const Sym2& e) {
  const double c = std::cos(m.blocks.rotation[b]), s = std::sin(m.blocks.rotation[b]);
  const Vec2 strained{X.x + e.xx * X.x + e.xy * X.y, X.y + e.xy * X.x + e.yy * X.y};
  return m.blocks.centroid[b] + Vec2{c * strained.x - s * strained.y, s * strained.x + c * strained.y};
}

}  // namespace

TEST(StrainModes, GeneralisedForceIsTheVirtualWorkOfTheStrainedPosition) {
  VDEC_REQUIREMENTS("REQ-SD-002");
  Scene scene = trapezoid();
  Model& m = scene.model;
  m.blocks.rotation[0] = 0.7;
  m.strainModes.strain[0] = {2e-3, -1e-3, 5e-4};
  placeBlockVertices(m, 0);
  const Vec2 X{0.9, -0.35};
  const Vec2 f{3.0e5, -1.2e5};
  const Vec2 r = worldPoint(m, 0, X, m.strainModes.strain[0]) - m.blocks.centroid[0];
  // The body point is found back from the world point.
  const Vec2 back = bodyPoint(m.strainModes, 0, r);
  EXPECT_NEAR(back.x, X.x, 1e-14);
  EXPECT_NEAR(back.y, X.y, 1e-14);
  addStrainForceAt(m.strainModes, 0, back, f);
  // Q_k = f . dx/dE_k at fixed c and theta, by central differences of the position.
  const double h = 1e-6;
  auto work = [&](int mode) {
    Sym2 plus = m.strainModes.strain[0], minus = plus;
    double* p = mode == 0 ? &plus.xx : mode == 1 ? &plus.yy : &plus.xy;
    double* q = mode == 0 ? &minus.xx : mode == 1 ? &minus.yy : &minus.xy;
    *p += h, *q -= h;
    return dot(f, worldPoint(m, 0, X, plus) - worldPoint(m, 0, X, minus)) / (2.0 * h);
  };
  const Sym2& Q = m.strainModes.force[0];
  EXPECT_NEAR(Q.xx, work(0), 1e-6 * std::abs(work(0)));
  EXPECT_NEAR(Q.yy, work(1), 1e-6 * std::abs(work(1)));
  EXPECT_NEAR(Q.xy, work(2), 1e-6 * std::abs(work(2)));
}

TEST(StrainModes, WorldAxesTensorIsTheRotationWrittenOutAsMatrices) {
  VDEC_REQUIREMENTS("REQ-SD-001");
  Scene scene = trapezoid();
  Model& m = scene.model;
  const double theta = 2.3;
  m.blocks.rotation[0] = theta;
  const Sym2 t{1.5, -0.4, 0.8};
  const double R[2][2] = {{std::cos(theta), -std::sin(theta)}, {std::sin(theta), std::cos(theta)}};
  const double T[2][2] = {{t.xx, t.xy}, {t.xy, t.yy}};
  double W[2][2] = {};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k)
        for (int l = 0; l < 2; ++l) W[i][j] += R[i][k] * T[k][l] * R[j][l];
  const Sym2 w = inWorldAxes(m, 0, t);
  EXPECT_NEAR(w.xx, W[0][0], 1e-14);
  EXPECT_NEAR(w.yy, W[1][1], 1e-14);
  EXPECT_NEAR(w.xy, W[0][1], 1e-14);
}

TEST(StrainModes, MassIsTheQuadratureOfTheModeFieldsProducts) {
  VDEC_REQUIREMENTS("REQ-SD-003");
  Scene scene = trapezoid();
  const Model& m = scene.model;
  // rho times the integral of phi_a . phi_b over the polygon, by the midpoint rule on a fine grid
  // of the bounding box, points inside the polygon counted.
  Polygon p;
  for (int v = 0; v < 4; ++v) p.push_back(m.vertices.localPosition[v]);
  auto inside = [&](Vec2 q) {
    bool in = false;
    for (int i = 0, j = 3; i < 4; j = i++)
      if ((p[i].y > q.y) != (p[j].y > q.y) && q.x < (p[j].x - p[i].x) * (q.y - p[i].y) / (p[j].y - p[i].y) + p[i].x) in = !in;
    return in;
  };
  double M[4][4] = {};
  const int n = 1200;
  const double x0 = -1.6, y0 = -0.8, size = 3.2 / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec2 q{x0 + (i + 0.5) * size, y0 + (j + 0.5) * size};
      if (!inside(q)) continue;
      const Vec2 phi[4] = {{-q.y, q.x}, {q.x, 0.0}, {0.0, q.y}, {q.y, q.x}};
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) M[a][b] += 2000.0 * dot(phi[a], phi[b]) * size * size;
    }
  const auto& stored = m.strainModes.mass[0];
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) EXPECT_NEAR(stored[4 * a + b], M[a][b], 2e-3 * M[0][0]) << a << ", " << b;
  // The rotation's entry is the block's moment of inertia.
  EXPECT_NEAR(stored[0], m.blocks.inertia[0], 1e-9 * m.blocks.inertia[0]);
}

TEST(Polygon, SecondMomentsOfARectangleAndTheirSum) {
  VDEC_REQUIREMENTS("REQ-SD-003");
  const Polygon r{{1.0, 1.0}, {4.0, 1.0}, {4.0, 3.0}, {1.0, 3.0}};
  const SecondMoments j = secondMoments(r);
  EXPECT_NEAR(j.xx, 2.0 * 27.0 / 12.0, 1e-12);  // h b^3 / 12, b = 3, h = 2
  EXPECT_NEAR(j.yy, 3.0 * 8.0 / 12.0, 1e-12);
  EXPECT_NEAR(j.xy, 0.0, 1e-12);
  const Polygon t{{0.0, 0.0}, {3.0, 0.0}, {2.2, 1.5}, {0.4, 1.1}};
  const SecondMoments k = secondMoments(t);
  EXPECT_NEAR(k.xx + k.yy, polarSecondMoment(t), 1e-12);
}
