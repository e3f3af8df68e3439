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

TEST(JointLaws, ContinuouslyYieldingFollowsTheExactSolutionOfItsShearEquationOverAStep) {
  VDEC_REQUIREMENTS("REQ-JOINT-007");
  const JointMaterial j = continuouslyYielding();
  auto [c, y] = cyContactAt(j, 1e6);
  EXPECT_DOUBLE_EQ(c.normalStress, 1e6);
  // With tau_m = sn tan(phi_eff) held, dtau/dus = ks (1 - tau/tau_m) gives
  // tau = tau_m (1 - exp(-ks dus / tau_m)) from tau = 0; the rest of dus is plastic.
  const double bound = 1e6 * std::tan(j.initialFriction), dus = 1e-5;
  updateContinuouslyYielding(j, c, y, 0.0, dus);
  const double tau = bound * (1.0 - std::exp(-1e9 * dus / bound));
  EXPECT_NEAR(c.shearStress, tau, 1e-9 * tau);
  EXPECT_NEAR(y.plasticShear, dus - tau / 1e9, 1e-15);
  EXPECT_NEAR(y.effectiveFriction, j.friction + (j.initialFriction - j.friction) * std::exp(-(dus - tau / 1e9) / 5e-4),
              1e-15);
  // A step far longer than the elastic range (ks dus = 100 tau_m, where an explicit update would
  // overshoot to -99 tau_m) lands on the bounding strength.
  auto [low, lowState] = cyContactAt(j, 1e3);
  updateContinuouslyYielding(j, low, lowState, 0.0, 1e-4);
  EXPECT_GT(low.shearStress, 0.0);
  EXPECT_LE(low.shearStress, 1e3 * std::tan(j.initialFriction));
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
  const double tau = c.shearStress, bound = 1e6 * std::tan(y.effectiveFriction);
  // Reversal: r = tau / tau_m with tau_m = -bound now, so F = 1 at the turn: the slope is ks.
  updateContinuouslyYielding(j, c, y, 0.0, -1e-9);
  EXPECT_DOUBLE_EQ(y.reversalRatio, tau / -bound);
  EXPECT_NEAR((c.shearStress - tau) / -1e-9, 1e9, 1e9 * 1e-5);
  c.elasticNormalStress = c.normalStress = 1e6;
  // Straight back: r = tau / tau_m is near 1 and capped at 0.75, so the slope is
  // ks (1 - tau/tau_m) / 0.25.
  const double before = c.shearStress, boundNow = 1e6 * std::tan(y.effectiveFriction);
  updateContinuouslyYielding(j, c, y, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(y.reversalRatio, 0.75);
  EXPECT_NEAR((c.shearStress - before) / 1e-9, 1e9 * (1.0 - before / boundNow) / 0.25, 1e9 * 1e-5);
  // Opening forgets the reversal: reclosed, the joint starts afresh.
  updateContinuouslyYielding(j, c, y, -2e-3, 0.0);
  EXPECT_TRUE(c.open);
  EXPECT_EQ(y.reversalRatio, 0.0);
  EXPECT_EQ(y.shearDirection, 0);
}

TEST(JointLaws, ContinuouslyYieldingDilatesWithThePlasticShearAboveTheBasicFriction) {
  VDEC_REQUIREMENTS("REQ-JOINT-007");
  JointMaterial j = continuouslyYielding();
  auto [c, y] = cyContactAt(j, 1e6);
  c.shearStress = 0.8e6;  // apparent friction atan(0.8) = 38.66 degrees > phi = 30
  const double plasticBefore = y.plasticShear;
  const double work = updateContinuouslyYielding(j, c, y, 0.0, 1e-6);
  const double plastic = y.plasticShear - plasticBefore;
  EXPECT_GT(plastic, 0.0);
  const double meanTau = 0.5 * (0.8e6 + c.shearStress);
  const double opening = std::tan(std::atan(meanTau / 1e6) - j.friction) * plastic;
  EXPECT_NEAR(c.elasticNormalStress, 1e6 + 1e9 * opening, 1e-6);
  // Dissipation sn dus_p (tan(phi + i) - tan(i)) > 0: the plastic work exceeds the dilation's.
  EXPECT_NEAR(work, meanTau * plastic - 1e6 * opening, 1e-12);
  EXPECT_GT(work, 0.0);
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

TEST(JointLaws, AChangeOfContactLengthKeepsTheSpringsEnergy) {
  VDEC_REQUIREMENTS("REQ-CONTACT-006");
  JointMaterial coulomb;
  coulomb.law = JointLaw::CoulombSlip;
  coulomb.kn = 1e9;
  coulomb.ks = 4e8;
  JointMaterial cy = continuouslyYielding();
  cy.knCoefficient = 1e6;
  cy.knExponent = 0.5;
  cy.ksCoefficient = 2e5;
  cy.ksExponent = 0.6;
  for (const JointMaterial& j : {coulomb, cy}) {
    for (const double sn : {2e5, 4e6}) {  // below and above the CY joint's knee (1 MPa)
      for (const double ratio : {50.0, 0.02, 1.7}) {  // L0 / L1: a face to a corner, back, a little
        Contact c;
        c.normalStress = c.elasticNormalStress = sn;
        c.shearStress = -0.3 * sn;
        c.length = 0.5;
        const double before = c.length * jointSpringEnergy(j, c);
        keepSpringEnergyAcrossLength(j, c, ratio);
        c.length /= ratio;
        EXPECT_NEAR(c.length * jointSpringEnergy(j, c), before, 1e-12 * before) << "ratio " << ratio << " sn " << sn;
        EXPECT_EQ(c.elasticNormalStress, c.normalStress);
        EXPECT_LT(c.shearStress, 0.0);  // the shear keeps its sign
      }
    }
  }
}

TEST(JointLaws, ContinuouslyYieldingNormalStressStaysOnItsCurveWhateverTheStep) {
  VDEC_REQUIREMENTS("REQ-JOINT-008");
  JointMaterial j = continuouslyYielding();
  // kn = 1e6 sn^0.5 or 1e3 sn: both overtake kn0 at 1 MPa, after 1 mm of closure.
  for (const auto& [an, en] : {std::pair{1e6, 0.5}, std::pair{1e3, 1.0}}) {
    j.knCoefficient = an;
    j.knExponent = en;
    // One step across the knee and far beyond, then back in two steps past zero (open), and
    // closed again: every state lies on the loading curve of the closure reached.
    auto [c, y] = cyContactAt(j, 0.0);
    double closure = 0.0;
    for (const double dun : {4e-3, -1.5e-3, -3.0e-3, 0.7e-3, 2e-3}) {
      updateContinuouslyYielding(j, c, y, dun, 0.0);
      closure += dun;
      EXPECT_NEAR(c.elasticNormalStress, cyNormalStressOfClosure(j, closure),
                  1e-12 * std::abs(cyNormalStressOfClosure(j, closure)) + 1e-6)
          << "en " << en << " closure " << closure;
      EXPECT_NEAR(cyClosureOfNormalStress(j, c.elasticNormalStress), closure, 1e-15 + 1e-12 * std::abs(closure));
    }
  }
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
  // The stiffness the grown-stiffness check compares with the time step's.
  auto [c, y] = cyContactAt(j, 0.0);
  c.normalStress = c.elasticNormalStress = 9e6;
  EXPECT_DOUBLE_EQ(cyStiffness(j, c), 3e9);
}
