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
