#include <cmath>

#include "joint/joint_laws.hpp"
#include "requirements.hpp"

using namespace vdec;

namespace {
JointMaterial coulomb(JointLaw law = JointLaw::CoulombSlip) {
  JointMaterial j;
  j.law = law;
  j.kn = 2e9;
  j.ks = 1e9;
  j.tanFriction = std::tan(30.0 * M_PI / 180.0);
  j.cohesion = 1e5;
  j.tension = 5e4;
  j.tanDilation = std::tan(10.0 * M_PI / 180.0);
  return j;
}
}  // namespace

TEST(JointLaws, ElasticIncrementsAreStressesFromStiffnessTimesDisplacement) {
  VDEC_REQUIREMENTS("REQ-JOINT-001");
  const JointMaterial j = coulomb();
  Contact c;
  EXPECT_EQ(updateJointStresses(j, c, 1e-5, 2e-6), 0.0);
  EXPECT_DOUBLE_EQ(c.normalStress, 2e9 * 1e-5);
  EXPECT_DOUBLE_EQ(c.shearStress, 1e9 * 2e-6);
  EXPECT_FALSE(c.slipping);
}

TEST(JointLaws, ShearForceIsCappedAtCohesionPlusFrictionAndDilationAddsCompression) {
  VDEC_REQUIREMENTS("REQ-JOINT-002");
  const JointMaterial j = coulomb();
  Contact c;
  updateJointStresses(j, c, 1e-3 / 2e9 * 1e6, 0.0);  // sn = 1 kPa
  const double sn = c.normalStress;
  EXPECT_NEAR(sn, 1e6 * 1e-3, 1e-6);
  const double strength = 1e5 + sn * j.tanFriction;
  const double work = updateJointStresses(j, c, 0.0, 1e-3);  // trial 1e6 Pa far above the strength
  EXPECT_TRUE(c.slipping);
  EXPECT_NEAR(c.shearStress, strength, 1e-9 * strength);
  const double slip = (1e9 * 1e-3 - strength) / 1e9;
  EXPECT_NEAR(c.elasticNormalStress, sn + 2e9 * slip * j.tanDilation, 1e-6);
  // Dissipated: the plastic shear work less what dilation stores by opening against sn.
  EXPECT_NEAR(work, (strength - sn * j.tanDilation) * slip, 1e-9 * strength * slip);
  // Reversal: elastic unloading first.
  updateJointStresses(j, c, 0.0, -1e-6);
  EXPECT_FALSE(c.slipping);
  EXPECT_NEAR(c.shearStress, strength - 1e3, 1e-6);
}

TEST(JointLaws, TensileStrengthThenOpeningAndReclosure) {
  VDEC_REQUIREMENTS("REQ-JOINT-003");
  const JointMaterial j = coulomb();
  Contact c;
  updateJointStresses(j, c, -2e-5, 0.0);  // -4e4 Pa: within T0 = 5e4
  EXPECT_FALSE(c.open);
  EXPECT_NEAR(c.normalStress, -4e4, 1e-6);
  updateJointStresses(j, c, -1e-5, 0.0);  // -6e4 Pa: breaks
  EXPECT_TRUE(c.open);
  EXPECT_EQ(c.normalStress, 0.0);
  EXPECT_EQ(c.shearStress, 0.0);
  updateJointStresses(j, c, 2e-5, 0.0);  // still short of where the spring is stress-free
  EXPECT_TRUE(c.open);
  updateJointStresses(j, c, 2e-5, 0.0);
  EXPECT_FALSE(c.open);
  EXPECT_NEAR(c.normalStress, 2e9 * 1e-5, 1e-6);
  EXPECT_TRUE(c.intact);  // model #2 keeps its strength
}

TEST(JointLaws, CoulombFractureLosesCohesionAndTensionAtFirstSlip) {
  VDEC_REQUIREMENTS("REQ-JOINT-004");
  const JointMaterial j = coulomb(JointLaw::CoulombFracture);
  Contact c;
  updateJointStresses(j, c, 5e-4, 0.0);  // sn = 1 MPa
  const double sn = c.normalStress;
  updateJointStresses(j, c, 0.0, 1e-3);
  EXPECT_TRUE(c.slipping);
  EXPECT_NEAR(c.shearStress, 1e5 + sn * j.tanFriction, 1e-6);
  EXPECT_FALSE(c.intact);
  const double snAfter = c.normalStress;
  updateJointStresses(j, c, 0.0, 1e-4);
  EXPECT_NEAR(c.shearStress, (c.normalStress) * j.tanFriction, 1e-6);
  EXPECT_GE(c.normalStress, snAfter);
  // No tensile strength left: any tension opens the contact.
  Contact t;
  t.intact = false;
  updateJointStresses(j, t, -1e-9, 0.0);
  EXPECT_TRUE(t.open);
}

TEST(JointLaws, PointContactLawUsesForcesAndHasNoTension) {
  VDEC_REQUIREMENTS("REQ-JOINT-005");
  JointMaterial j;
  j.law = JointLaw::PointContact;
  j.kn = 1e7;
  j.ks = 5e6;
  j.tanFriction = 0.5;
  j.cohesion = 1e9;  // ignored by the point-contact law (the reader rejects it anyway)
  Contact c;
  updateJointStresses(j, c, 1e-4, 0.0);
  EXPECT_DOUBLE_EQ(c.normalStress, 1e3);
  updateJointStresses(j, c, 0.0, 1e-3);
  EXPECT_DOUBLE_EQ(c.shearStress, 500.0);
  updateJointStresses(j, c, -2e-4, 0.0);
  EXPECT_TRUE(c.open);
}

namespace {
JointMaterial continuouslyYielding() {
  JointMaterial j;
  j.law = JointLaw::ContinuouslyYielding;
  j.kn = 1e9;
  j.ks = 1e9;
  j.friction = 30.0 * M_PI / 180.0;
  j.initialFriction = 45.0 * M_PI / 180.0;
  j.tanFriction = std::tan(j.friction);
  j.roughness = 5e-4;
  return j;
}

// A contact of the law closed to normal stress sn (below the knee of a power-law stiffness),
// with its yielding state.
struct CyContact {
  Contact c;
  YieldingState y;
};
CyContact cyContactAt(const JointMaterial& j, double sn) {
  CyContact out;
  out.y.effectiveFriction = j.initialFriction;
  updateContinuouslyYielding(j, out.c, out.y, sn / j.kn, 0.0);
  return out;
}
}  // namespace

TEST(JointLaws, ContinuouslyYieldingFirstIncrementIsElasticThenSlopeIsKsTimesF) {
  VDEC_REQUIREMENTS("REQ-JOINT-007");
  const JointMaterial j = continuouslyYielding();
  auto [c, y] = cyContactAt(j, 1e6);
  EXPECT_DOUBLE_EQ(c.normalStress, 1e6);
  // F = 1 at tau = 0: the first increment is the elastic one, with no plastic displacement.
  updateContinuouslyYielding(j, c, y, 0.0, 1e-6);
  EXPECT_DOUBLE_EQ(c.shearStress, 1e3);
  EXPECT_DOUBLE_EQ(y.plasticShear, 0.0);
  // The next has F = 1 - tau / (sn tan phi_eff), and (1 - F) |dus| of plastic displacement,
  // which lowers phi_eff towards phi by exp(-dus_p / R) (1.4-144).
  const double f = 1.0 - 1e3 / (1e6 * std::tan(j.initialFriction));
  updateContinuouslyYielding(j, c, y, 0.0, 1e-6);
  EXPECT_NEAR(c.shearStress, 1e3 + f * 1e3, 1e-9);
  EXPECT_NEAR(y.plasticShear, (1.0 - f) * 1e-6, 1e-21);
  EXPECT_NEAR(y.effectiveFriction, j.friction + (j.initialFriction - j.friction) * std::exp(-(1.0 - f) * 1e-6 / 5e-4),
              1e-15);
}

TEST(JointLaws, ContinuouslyYieldingPeaksAtTheBoundingStrengthThenSoftensToResidual) {
  VDEC_REQUIREMENTS("REQ-JOINT-007");
  const JointMaterial j = continuouslyYielding();
  auto [c, y] = cyContactAt(j, 1e6);
  double peak = 0.0, peakBound = 0.0;
  for (int i = 0; i < 20000; ++i) {  // 20 mm in 1 um steps
    const double before = c.shearStress;
    updateContinuouslyYielding(j, c, y, 0.0, 1e-6);
    if (c.shearStress < before && peak == 0.0) {
      peak = before;
      peakBound = 1e6 * std::tan(y.effectiveFriction);
    }
    c.elasticNormalStress = c.normalStress = 1e6;  // constant normal stress: discard the dilation
  }
  // At the peak F = 0: tau meets the bounding strength, within one increment's change of it.
  EXPECT_NEAR(peak, peakBound, 2e3);
  EXPECT_GT(peak, 1e6 * std::tan(j.friction) * 1.05);
  // Residual: phi_eff -> phi and tau -> sn tan(phi).
  EXPECT_NEAR(y.effectiveFriction, j.friction, 1e-9);
  EXPECT_NEAR(c.shearStress, 1e6 * std::tan(j.friction), 1.0);
}

TEST(JointLaws, ContinuouslyYieldingReversalRestoresTheElasticSlopeAndCapsR) {
  VDEC_REQUIREMENTS("REQ-JOINT-007");
  const JointMaterial j = continuouslyYielding();
  auto [c, y] = cyContactAt(j, 1e6);
  for (int i = 0; i < 2000; ++i) {
    updateContinuouslyYielding(j, c, y, 0.0, 1e-6);
    c.elasticNormalStress = c.normalStress = 1e6;  // constant normal stress
  }
  const double tau = c.shearStress, phiEff = y.effectiveFriction;
  // Reversal: r = tau / tau_m with tau_m now negative, so F = 1.
  updateContinuouslyYielding(j, c, y, 0.0, -1e-7);
  EXPECT_NEAR(c.shearStress, tau - 1e9 * 1e-7, 1e-6);
  EXPECT_DOUBLE_EQ(y.reversalRatio, tau / (-1e6 * std::tan(phiEff)));
  c.elasticNormalStress = c.normalStress = 1e6;
  // Straight back: r = tau / tau_m is near 1 and capped at 0.75, F = (1 - tau/tau_m) / 0.25.
  const double before = c.shearStress, bound = 1e6 * std::tan(y.effectiveFriction);
  updateContinuouslyYielding(j, c, y, 0.0, 1e-8);
  EXPECT_DOUBLE_EQ(y.reversalRatio, 0.75);
  EXPECT_NEAR(c.shearStress, before + (1.0 - before / bound) / 0.25 * 1e9 * 1e-8, 1e-6);
}

TEST(JointLaws, ContinuouslyYieldingDilatesAboveTheBasicFrictionAndHasNoTensileStrength) {
  VDEC_REQUIREMENTS("REQ-JOINT-007");
  JointMaterial j = continuouslyYielding();
  auto [c, y] = cyContactAt(j, 1e6);
  c.shearStress = 0.8e6;  // apparent friction atan(0.8) = 38.66 degrees > phi = 30
  const double work = updateContinuouslyYielding(j, c, y, 0.0, 1e-6);
  const double opening = std::tan(std::atan(0.8) - j.friction) * 1e-6;
  EXPECT_NEAR(c.elasticNormalStress, 1e6 + 1e9 * opening, 1e-6);
  const double f = (1.0 - 0.8e6 / (1e6 * std::tan(j.initialFriction)));
  EXPECT_NEAR(work, 0.8e6 * (1.0 - f) * 1e-6 - 1e6 * opening, 1e-9);
  // Below phi: no dilation.
  auto [low, lowState] = cyContactAt(j, 1e6);
  low.shearStress = 0.5e6;
  updateContinuouslyYielding(j, low, lowState, 0.0, 1e-6);
  EXPECT_DOUBLE_EQ(low.elasticNormalStress, 1e6);
  // Any tension opens it.
  updateContinuouslyYielding(j, low, lowState, -1.0001e-3, 0.0);
  EXPECT_TRUE(low.open);
  EXPECT_EQ(low.normalStress, 0.0);
  EXPECT_EQ(low.shearStress, 0.0);
}

TEST(JointLaws, ContinuouslyYieldingNormalStiffnessGrowsAsAPowerOfTheNormalStress) {
  VDEC_REQUIREMENTS("REQ-JOINT-008");
  JointMaterial j = continuouslyYielding();
  j.knCoefficient = 1e6;  // kn = 1e6 sn^0.5: overtakes kn0 = 1e9 at sn = 1e6
  j.knExponent = 0.5;
  EXPECT_DOUBLE_EQ(cyKneeStress(j), 1e6);
  EXPECT_DOUBLE_EQ(cyNormalStiffness(j, 1e4), 1e9);
  EXPECT_DOUBLE_EQ(cyNormalStiffness(j, 4e6), 2e9);
  // Closure and stress are inverse, and the stored energy is the integral of sn dun.
  for (double sn : {5e5, 1e6, 4e6, 9e6}) {
    const double knee = 1e6, kneeClosure = 1e-3;
    const double closure = sn <= knee ? sn / 1e9 : kneeClosure + (std::sqrt(sn) - std::sqrt(knee)) / (1e6 * 0.5);
    EXPECT_NEAR(cyNormalStressOfClosure(j, closure), sn, 1e-9 * sn);
  }
  double energy = 0.0, sn = 0.0;
  const double dun = 1e-8;
  for (int i = 0; i < 300000; ++i) {  // 3 mm of closure by the midpoint rule
    const double next = cyNormalStressOfClosure(j, (i + 1) * dun);
    energy += 0.5 * (sn + next) * dun;
    sn = next;
  }
  EXPECT_NEAR(cyNormalSpringEnergy(j, sn), energy, 1e-6 * energy);
  // The time step's stiffness is the zero-stress one; the growth is reported.
  auto [c, y] = cyContactAt(j, 0.0);
  c.normalStress = c.elasticNormalStress = 9e6;
  EXPECT_DOUBLE_EQ(jointStiffnessGrowth(j, c), 3.0);
}
