#include <cmath>

#include "run/cycle.hpp"
#include "core/errors.hpp"
#include "motion/rigid_motion.hpp"
#include "requirements.hpp"
#include "scene_fixture.hpp"

using namespace vdec;
using vdec::testing::blockOnBaseDefinition;

namespace {

Scene sceneWithFrac(double frac) {
  SceneDefinition scene = blockOnBaseDefinition();
  scene.settings.frac = frac;
  return buildScene(scene);
}

}  // namespace

TEST(RigidMotion, FreeFallFollowsTheCentralDifferenceRecurrenceExactly) {
  VDEC_REQUIREMENTS("REQ-MOTION-001");
  Scene s = buildScene(blockOnBaseDefinition());
  Model& m = s.model;
  m.blocks.centroid[1].y += 10.0;  // far above the base: no contact
  m.contacts.clear();
  const double dt = 1e-3;
  for (int n = 1; n <= 100; ++n) {
    integrateRigidBlocks(m, dt, 0.0);
    // v(1/2) = g dt, y_n = y_0 + g dt^2 n (n + 1) / 2 with v(-1/2) = 0.
    EXPECT_NEAR(m.blocks.centroid[1].y - 10.5, -10.0 * dt * dt * n * (n + 1) / 2.0, 1e-12);
  }
}

TEST(RigidMotion, MassDampingFollowsEquation1321) {
  VDEC_REQUIREMENTS("REQ-MOTION-002");
  Scene s = buildScene(blockOnBaseDefinition());
  Model& m = s.model;
  m.gravity = {0.0, 0.0};
  m.blocks.velocity[1] = {2.0, -1.0};
  m.blocks.angularVelocity[1] = 3.0;
  m.blocks.force[1] = {500.0, 0.0};
  const double dt = 1e-2, a = 4.0;
  integrateRigidBlocks(m, dt, a);
  const double mass = 2500.0;
  EXPECT_NEAR(m.blocks.velocity[1].x, (2.0 * (1 - a * dt / 2) + 500.0 / mass * dt) / (1 + a * dt / 2), 1e-15);
  EXPECT_NEAR(m.blocks.velocity[1].y, (-1.0 * (1 - a * dt / 2)) / (1 + a * dt / 2), 1e-15);
  EXPECT_NEAR(m.blocks.angularVelocity[1], 3.0 * (1 - a * dt / 2) / (1 + a * dt / 2), 1e-15);
}

TEST(RigidMotion, LocalDampingOpposesTheMotionByAFractionOfTheForce) {
  VDEC_REQUIREMENTS("REQ-ZONE-016");
  // v1 = v0 + (F - alpha_L |F| sgn v0) dt / m per degree of freedom: x moves with its force
  // (damping takes 0.8 of it), y against its force (damping adds 0.8 of it), rotation has no
  // moment (no damping force).
  Scene s = buildScene(blockOnBaseDefinition());
  Model& m = s.model;
  m.gravity = {0.0, 0.0};
  m.blocks.velocity[1] = {2.0, -1.0};
  m.blocks.angularVelocity[1] = 3.0;
  m.blocks.force[1] = {500.0, 250.0};
  const double dt = 1e-2, mass = 2500.0;
  const MotionStepTotals t = integrateRigidBlocks(m, dt, 0.0, 0.8);
  EXPECT_NEAR(m.blocks.velocity[1].x, 2.0 + (500.0 - 0.8 * 500.0) * dt / mass, 1e-15);
  EXPECT_NEAR(m.blocks.velocity[1].y, -1.0 + (250.0 + 0.8 * 250.0) * dt / mass, 1e-15);
  EXPECT_EQ(m.blocks.angularVelocity[1], 3.0);
  // Its work over the step, -F_d vbar dt, is dissipation.
  const double vx1 = m.blocks.velocity[1].x, vy1 = m.blocks.velocity[1].y;
  EXPECT_NEAR(t.dampingDissipation, 0.8 * 500.0 * 0.5 * (2.0 + vx1) * dt - 0.8 * 250.0 * 0.5 * (-1.0 + vy1) * dt, 1e-12);
}

TEST(RigidMotion, DrivenDegreesOfFreedomKeepTheirVelocity) {
  VDEC_REQUIREMENTS("REQ-MOTION-003");
  Scene s = buildScene(blockOnBaseDefinition());
  Model& m = s.model;
  m.blocks.driven[1] = DriveX | DriveRotation;
  m.blocks.velocity[1] = {0.25, 0.0};
  m.blocks.force[1] = {1e6, 0.0};
  m.blocks.moment[1] = 1e6;
  integrateRigidBlocks(m, 1e-3, 0.0);
  EXPECT_EQ(m.blocks.velocity[1].x, 0.25);
  EXPECT_EQ(m.blocks.angularVelocity[1], 0.0);
  EXPECT_NEAR(m.blocks.velocity[1].y, -10.0 * 1e-3, 1e-15);
  EXPECT_EQ(m.blocks.centroid[0].x, 0.0);  // the fixed base never moves
}

TEST(RigidMotion, TimeStepFollowsEquation1328) {
  VDEC_REQUIREMENTS("REQ-MOTION-004");
  Scene s = buildScene(blockOnBaseDefinition());
  // M_min = 2500 kg and l_typ = 1 m, both of the free block: the fixed 3 m base does not count.
  EXPECT_NEAR(rigidBlockTimeStep(s.model, 0.1), 0.1 * 2.0 * std::sqrt(2500.0 / (1e8 * 1.0)), 1e-18);
  // With every block driven, all blocks count: l_typ = 3 m, the base's top edge.
  s.model.blocks.driven[1] = DriveAll;
  EXPECT_NEAR(rigidBlockTimeStep(s.model, 0.1), 0.1 * 2.0 * std::sqrt(2500.0 / (1e8 * 3.0)), 1e-18);
}

TEST(RigidMotion, UnstableTimeStepStopsTheRunWithADiagnostic) {
  VDEC_REQUIREMENTS("REQ-MOTION-005");
  // FRAC 1.7 is about three times the critical value for this block (0.53, RB-STABILITY-FRAC).
  Scene s = sceneWithFrac(1.7);
  s.settings.stop.cycles = 200;
  Cycle cycle(s.model, s.settings, {});
  const RunReport r = cycle.run();
  EXPECT_EQ(r.errorCode, static_cast<int>(ExitCode::Instability));
  EXPECT_NE(r.error.find("solver.frac"), std::string::npos) << r.error;
  EXPECT_LT(r.cycles, 200);
}

TEST(RigidMotion, StableRunKeepsEnergyWithinWhatWasSupplied) {
  VDEC_REQUIREMENTS("REQ-MOTION-005");
  Scene s = sceneWithFrac(0.05);
  s.settings.stop.cycles = 2000;
  Cycle cycle(s.model, s.settings, {});
  const RunReport r = cycle.run();
  EXPECT_EQ(r.errorCode, 0) << r.error;
  // Undamped: (kinetic + strain) tracks the work of gravity to O((w dt)^2), w dt = 0.1 here.
  EXPECT_LT(r.energy.largestExcess, 0.05);
}

TEST(RigidMotion, SameSceneGivesBitwiseIdenticalResults) {
  VDEC_REQUIREMENTS("REQ-RUN-002");
  auto runOnce = [] {
    Scene s = sceneWithFrac(0.2);
    s.model.blocks.angularVelocity[1] = 0.05;
    s.settings.stop.cycles = 3000;
    Cycle cycle(s.model, s.settings, {});
    cycle.run();
    return s.model;
  };
  const Model a = runOnce(), b = runOnce();
  EXPECT_EQ(a.blocks.centroid[1].x, b.blocks.centroid[1].x);
  EXPECT_EQ(a.blocks.centroid[1].y, b.blocks.centroid[1].y);
  EXPECT_EQ(a.blocks.rotation[1], b.blocks.rotation[1]);
  ASSERT_EQ(a.contacts.size(), b.contacts.size());
  for (std::size_t i = 0; i < a.contacts.size(); ++i) EXPECT_EQ(a.contacts[i].normalStress, b.contacts[i].normalStress);
}
