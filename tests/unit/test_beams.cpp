// Beams: the co-rotational frame element strains under no rigid motion, gives the frame element's
// stiffness for small motions, and the tie's springs and limits.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "requirements.hpp"
#include "scene_fixture.hpp"
#include "structure/beams.hpp"

using namespace vdec;
using vdec::testing::sceneFromText;

namespace {

std::string beamScene(const std::string& extra = "") {
  return R"(
[model]
rounding = 0.01
gravity = [0.0, 0.0]
[stop]
cycles = 1
[[joint_material]]
name = "j"
kn = 1e10
ks = 1e10
[[block_material]]
name = "rock"
density = 2500.0
young = 10e9
poisson = 0.25
[[block]]
name = "base"
material = "rock"
vertices = [[-1.0, -1.0], [3.0, -1.0], [3.0, 0.0], [-1.0, 0.0]]
fix = ["x", "y", "rotation"]
[[beam_material]]
name = "steel"
young = 200e9
area = 0.01
inertia = 1e-5
density = 7850.0
tie_normal_stiffness = 1e8
tie_shear_stiffness = 2e8
tie_cohesion = 50.0
tie_friction = 30.0
tie_tension = 20.0
[[beam]]
name = "b"
material = "steel"
points = [[0.0, 0.0], [2.0, 0.0]]
elements = 2
)" + extra;
}

// Every node moved as one rigid body: turned by `angle` about the origin and shifted.
void moveRigidly(Model& m, double angle, Vec2 shift) {
  BeamNodes& nd = m.structures.nodes;
  const double c = std::cos(angle), s = std::sin(angle);
  for (int i = 0; i < nd.size(); ++i) {
    nd.position[i] = rotated(nd.initialPosition[i], c, s) + shift;
    nd.rotation[i] = angle;
  }
}

}  // namespace

TEST(Beams, ARigidTurnOfAnyAngleStrainsNoElement) {
  VDEC_REQUIREMENTS("REQ-STRUCT-001");
  Scene scene = sceneFromText(beamScene(), "rigid");
  Model& m = scene.model;
  for (const double angle : {0.3, 1.5, 3.0, -2.5}) {
    moveRigidly(m, angle, {0.7, -0.2});
    const BeamStepTotals t = computeBeamForces(m, 0.0);
    EXPECT_LT(t.strainEnergy, 1e-20) << angle;
    for (int e = 0; e < m.structures.elements.size(); ++e) {
      EXPECT_LT(std::abs(m.structures.elements.axialForce[e]), 1e-3) << angle;  // E A / L round-off: 8e9 N/m x 1e-16 m
      EXPECT_LT(std::abs(m.structures.elements.endMoment[e][0]), 1e-9) << angle;
      EXPECT_LT(std::abs(m.structures.elements.endMoment[e][1]), 1e-9) << angle;
    }
  }
}

TEST(Beams, SmallMotionsGiveTheFrameElementsStiffness) {
  VDEC_REQUIREMENTS("REQ-STRUCT-001");
  Scene scene = sceneFromText(beamScene(), "stiffness");
  Model& m = scene.model;
  BeamNodes& nd = m.structures.nodes;
  // The element from node 1 (x = 1) to node 2 (x = 2), L = 1: a small transverse motion v and a
  // rotation t of node 2 give the frame element's end forces: shear 12 EI v / L^3 - 6 EI t / L^2 at
  // node 2, moment -6 EI v / L^2 + 4 EI t / L, and an axial stretch u gives E A u / L.
  const double ei = 200e9 * 1e-5, ea = 200e9 * 0.01, v = 1e-9, t = 2e-9, u = 3e-10;
  nd.position[2] = nd.initialPosition[2] + Vec2{u, v};
  nd.rotation[2] = t;
  computeBeamForces(m, 0.0);
  EXPECT_NEAR(nd.force[2].y, -(12.0 * ei * v - 6.0 * ei * t), 1e-6 * 12.0 * ei * v);
  EXPECT_NEAR(nd.moment[2], -(-6.0 * ei * v + 4.0 * ei * t), 1e-6 * 4.0 * ei * t);
  EXPECT_NEAR(nd.force[2].x, -ea * u, 1e-5 * ea * u);
  EXPECT_NEAR(nd.force[1].y, -nd.force[2].y, 1e-9 * std::abs(nd.force[2].y));
}

TEST(Beams, ATieSlipsAtItsCoulombStrengthAndBreaksBeyondItsTension) {
  VDEC_REQUIREMENTS("REQ-STRUCT-003");
  Scene scene = sceneFromText(beamScene("tied = true\n"), "tie");
  Model& m = scene.model;
  BeamNodes& nd = m.structures.nodes;
  ASSERT_EQ(m.structures.ties.size(), 3u);
  const BeamTie& middle = m.structures.ties[1];
  EXPECT_EQ(middle.block, 0);
  EXPECT_EQ(middle.zone, -1);
  // The middle node's length is 1 m: springs 1e8 and 2e8 N/m, cohesion 50 N, tension 20 N.
  // Pressed 1e-7 m into the base (below it): compression 10 N; then sheared by 1e-6 m: 200 N
  // elastic, limited to 50 + 10 tan 30 = 55.77 N.
  nd.velocity[1] = {0.0, -1e-7};
  m.clearStepForces();
  computeBeamForces(m, 1.0);
  EXPECT_NEAR(m.structures.ties[1].force.y, 10.0, 1e-9);
  EXPECT_FALSE(m.structures.ties[1].slipping);
  nd.velocity[1] = {1e-6, 0.0};
  m.clearStepForces();
  computeBeamForces(m, 1.0);
  EXPECT_TRUE(m.structures.ties[1].slipping);
  EXPECT_NEAR(m.structures.ties[1].force.x, -(50.0 + 10.0 * std::tan(std::numbers::pi / 6.0)), 1e-9);
  // The base took the opposite of the three ties' forces.
  EXPECT_NEAR(m.blocks.boundaryForce[0].y, -10.0, 1e-9);
  // Pulled up by 3e-7 m: the 10 N of compression becomes 20 N of tension, at the limit; beyond it
  // the tie breaks for good.
  nd.velocity[1] = {0.0, 3e-7};
  m.clearStepForces();
  computeBeamForces(m, 1.0);
  EXPECT_FALSE(m.structures.ties[1].broken);
  nd.velocity[1] = {0.0, 1e-9};
  m.clearStepForces();
  computeBeamForces(m, 1.0);
  EXPECT_TRUE(m.structures.ties[1].broken);
  nd.velocity[1] = {0.0, -1e-6};
  m.clearStepForces();
  computeBeamForces(m, 1.0);
  EXPECT_EQ(m.structures.ties[1].force.y, 0.0);
}
