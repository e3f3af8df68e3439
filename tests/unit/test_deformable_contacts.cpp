// Contacts on deformable blocks: outline gridpoints as corners, forces shared along edges,
// contact lengths that partition a joint between both sides, rigid-deformable contacts.

#include <cmath>
#include <numbers>

#include "core/thread_team.hpp"
#include "contact/contact_geometry.hpp"
#include "run/cycle.hpp"
#include "core/errors.hpp"
#include "requirements.hpp"
#include "scene_fixture.hpp"

using namespace vdec;
using vdec::testing::sceneFromText;

namespace {

constexpr double kPressure = 1e5;  // Pa on the top of the stack
constexpr double kJointStiffness = 1e10;  // Pa/m

// An elastic rock (E = 10 GPa, nu = 0.25) and a Coulomb joint of stiffness kn = ks = k.
std::string rockAndJoint(double k) {
  return R"(
[[block_material]]
name = "rock"
density = 2500.0
young = 10e9
poisson = 0.25
[[joint_material]]
name = "joint"
kn = )" + std::to_string(k) + "\nks = " + std::to_string(k) + "\nfriction = 30.0\n";
}

// Two elastic 1 m x 1 m blocks, one on the other, zoned lowerNx x 2 and upperNx x 3; the bottom
// on rollers (one gridpoint held in x), a pressure on top, the sides free. A bonded joint.
std::string stackScene(int lowerNx, int upperNx, const std::string& extra = "") {
  return R"(
[model]
rounding = 0.01
[solver]
adaptive_damping = true
[stop]
ratio = 1e-10
cycles = 100000
)" + rockAndJoint(kJointStiffness) + R"(cohesion = 1e6
tension = 1e6
[[block]]
name = "lower"
material = "rock"
vertices = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
zoning = { nx = )" + std::to_string(lowerNx) + R"(, ny = 2 }
[[block]]
name = "upper"
material = "rock"
vertices = [[0.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]]
zoning = { nx = )" + std::to_string(upperNx) + R"(, ny = 3 }
[[boundary]]
block = "lower"
y = [0.0, 0.0]
fix = ["y"]
[[boundary]]
block = "lower"
x = [0.0, 0.0]
y = [0.0, 0.0]
fix = ["x"]
[[boundary]]
block = "upper"
y = [2.0, 2.0]
pressure = )" + std::to_string(kPressure) + "\n" + extra;
}

// A 2 m x 1 m deformable base zoned nx x 2 under a rigid block of the given corners, with
// gravity; `excavation` may remove zones of the base.
std::string blockOnZonedBase(int nx, const std::string& topVertices, const std::string& excavation = "") {
  return R"(
[model]
rounding = 0.01
gravity = [0.0, -10.0]
[solver]
adaptive_damping = true
[stop]
ratio = 1e-9
cycles = 200000
)" + rockAndJoint(1e10) + R"(
[[block]]
name = "base"
material = "rock"
vertices = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]
zoning = { nx = )" + std::to_string(nx) + R"(, ny = 2 }
[[block]]
name = "top"
material = "rock"
vertices = )" + topVertices + R"(
[[boundary]]
block = "base"
y = [0.0, 0.0]
fix = ["x", "y"]
)" + excavation;
}

struct Relaxed {
  Model model;
  RunReport report;
};

Relaxed relax(const std::string& text, const std::string& name) {
  Scene s = sceneFromText(text, name);
  Cycle cycle(s.model, s.settings, {});
  RunReport r = cycle.run();
  return {s.model, r};
}

double contactNormalStress(const Model& m, const Contact& c) { return m.normalForce(c) / c.length; }

}  // namespace

TEST(DeformableContacts, JointedStackCarriesAUniformStressOnMatchingAndMismatchedZonings) {
  VDEC_REQUIREMENTS("REQ-ZONE-014, REQ-ZONE-015");
  // Uniform stress is exact for constant-strain triangles, and the joint passes it on only if
  // the contact lengths partition the joint (no stretch carried twice, none left out) and the
  // forces reach the gridpoints as a uniform traction would. What remains is geometric, of the
  // order of the strains (1e-5): the tolerances are 2e-5 of the pressure.
  for (const auto& [lowerNx, upperNx] : {std::pair{2, 2}, std::pair{4, 3}, std::pair{2, 5}}) {
    SCOPED_TRACE("lower nx " + std::to_string(lowerNx) + ", upper nx " + std::to_string(upperNx));
    const Relaxed run = relax(stackScene(lowerNx, upperNx), "stack");
    const Model& m = run.model;
    ASSERT_EQ(run.report.errorCode, 0) << run.report.error;
    ASSERT_EQ(run.report.stopReason, "ratio");
    for (int z = 0; z < m.zones.size(); ++z) {
      EXPECT_NEAR(m.zones.syy[z], -kPressure, 2e-5 * kPressure) << "zone " << z;
      EXPECT_NEAR(m.zones.sxx[z], 0.0, 2e-5 * kPressure) << "zone " << z;
      EXPECT_NEAR(m.zones.sxy[z], 0.0, 2e-5 * kPressure) << "zone " << z;
    }
    double totalNormalForce = 0.0, totalLength = 0.0;
    for (const Contact& c : m.contacts) {
      EXPECT_FALSE(c.open);
      EXPECT_NEAR(contactNormalStress(m, c), kPressure, 2e-5 * kPressure);
      totalNormalForce += m.normalForce(c);
      totalLength += c.length;
    }
    // The joint's length (1 m, stretched by the lateral strain nu (1 + nu) p / E = 3.1e-6) is
    // shared out among the contacts of both sides exactly once.
    EXPECT_NEAR(totalLength, 1.0, 1e-5);
    EXPECT_NEAR(totalNormalForce, kPressure, 1e-5 * kPressure);
    // Every gridpoint of the upper block's base lies p / kn below the lower block's face under
    // it: the joint's closure.
    const Gridpoints& g = m.gridpoints;
    for (int i = 0; i < g.size(); ++i) {
      if (m.blocks.name[g.block[i]] != "upper" || g.initialPosition[i].y != 1.0) continue;
      double below = NAN;
      for (int k = 0; k < g.size(); ++k)
        if (m.blocks.name[g.block[k]] == "lower" && g.initialPosition[k].y == 1.0 &&
            std::abs(g.initialPosition[k].x - g.initialPosition[i].x) < 1e-12)
          below = g.position[k].y - g.initialPosition[k].y;
      if (std::isnan(below)) continue;  // no lower gridpoint right under this one
      const double closure = below - (g.position[i].y - g.initialPosition[i].y);
      EXPECT_NEAR(closure, kPressure / kJointStiffness, 2e-5 * kPressure / kJointStiffness) << "gridpoint " << i;
    }
  }
}

TEST(DeformableContacts, RigidBlockRestsOnADeformableBase) {
  VDEC_REQUIREMENTS("REQ-ZONE-014");
  // A rigid 1 m x 0.5 m block (density 2500, g = 10) on the middle of a deformable 2 m x 1 m
  // base zoned 5 x 2: the base's zones under it carry its weight, and its rounded corners and
  // the base's gridpoints under it share the contact length.
  const Relaxed run = relax(blockOnZonedBase(5, "[[0.5, 1.0], [1.5, 1.0], [1.5, 1.5], [0.5, 1.5]]"), "rigid-on-deformable");
  const Model& m = run.model;
  ASSERT_EQ(run.report.errorCode, 0) << run.report.error;
  ASSERT_EQ(run.report.stopReason, "ratio");
  const double weight = 2500.0 * 0.5 * 10.0;
  double normal = 0.0, length = 0.0;
  int onBaseGridpoints = 0;
  for (const Contact& c : m.contacts) {
    normal += m.normalForce(c) * std::abs(contactGeometry(m, c).normal.y);
    length += c.length;
    onBaseGridpoints += m.vertices.gridpoint[c.corner] >= 0;
  }
  EXPECT_NEAR(normal, weight, 1e-6 * weight);
  EXPECT_NEAR(length, 1.0, 1e-3);  // the block's face, 1 m, shared out once
  EXPECT_EQ(onBaseGridpoints, 2);  // the base's gridpoints at x = 0.8 and 1.2 (and the top's 2 corners)
  EXPECT_EQ(m.contacts.size(), 4u);
  // Equilibrium of the base: its zones' mean vertical stress over the bottom row times the
  // width carries the block's weight plus the upper half of the base's own.
  double forceOnBottom = 0.0, area = 0.0;
  for (int z = 0; z < m.zones.size(); ++z) {
    const auto& n = m.zones.gridpoint[z];
    const Vec2 centre = (1.0 / 3.0) * (m.gridpoints.initialPosition[n[0]] + m.gridpoints.initialPosition[n[1]] +
                                       m.gridpoints.initialPosition[n[2]]);
    if (centre.y > 0.5) continue;
    const Vec2 p0 = m.gridpoints.position[n[0]], p1 = m.gridpoints.position[n[1]], p2 = m.gridpoints.position[n[2]];
    const double a = 0.5 * cross(p1 - p0, p2 - p0);
    forceOnBottom += m.zones.syy[z] * a;
    area += a;
  }
  // Mean syy over the bottom half times the width equals minus the load at mid-height of
  // that half: the block's weight and the base's weight above y = 0.25.
  const double expected = -(weight + 2500.0 * 10.0 * 2.0 * 0.75);
  EXPECT_NEAR(forceOnBottom / area * 2.0, expected, 1e-3 * std::abs(expected));
}

TEST(DeformableContacts, ResultsAreBitwiseTheSameOnOneAndTwoThreads) {
  VDEC_REQUIREMENTS("REQ-ZONE-004, REQ-ZONE-014");
  auto runWith = [](int threads) {
    ThreadTeam::instance().setThreadCount(threads);
    Scene s = sceneFromText(stackScene(24, 32), "stack-threads");
    s.settings.stop = {};
    s.settings.stop.cycles = 400;
    Cycle cycle(s.model, s.settings, {});
    const RunReport r = cycle.run();
    EXPECT_EQ(r.errorCode, 0) << r.error;
    return s.model;
  };
  const Model one = runWith(1), two = runWith(2);
  ThreadTeam::instance().setThreadCount(1);
  ASSERT_EQ(one.contacts.size(), two.contacts.size());
  for (int i = 0; i < one.gridpoints.size(); ++i) {
    EXPECT_EQ(one.gridpoints.position[i].x, two.gridpoints.position[i].x);
    EXPECT_EQ(one.gridpoints.position[i].y, two.gridpoints.position[i].y);
  }
  for (std::size_t c = 0; c < one.contacts.size(); ++c) EXPECT_EQ(one.contacts[c].normalStress, two.contacts[c].normalStress);
}

TEST(DeformableContacts, SlidingAcrossMismatchedGridpointsKeepsTheFrictionalStrength) {
  VDEC_REQUIREMENTS("REQ-ZONE-014");
  // The upper block of the stack pushed along the joint (friction 30 degrees, no cohesion) by a
  // velocity on its left side: its gridpoints pass over the lower block's and contacts move from
  // edge to edge; at the end every contact slips with its shear force at tan(30) times its
  // normal force, and the energy account closes.
  const std::string scene = stackScene(4, 3, R"(
[[boundary]]
block = "upper"
x = [0.0, 0.0]
velocity_x = 0.05
)");
  std::string frictional = scene;
  frictional.replace(frictional.find("cohesion = 1e6\ntension = 1e6\n"), 28, "");
  Scene s = sceneFromText(frictional, "stack-slide");
  s.settings.stop = {};
  s.settings.stop.time = 4.0;  // 0.2 m of slip: most of a zone of either block
  Cycle cycle(s.model, s.settings, {});
  const RunReport r = cycle.run();
  ASSERT_EQ(r.errorCode, 0) << r.error;
  const Model& m = s.model;
  double normal = 0.0;
  int closed = 0;
  for (const Contact& c : m.contacts) {
    if (c.open) continue;
    ++closed;
    normal += m.normalForce(c);
    EXPECT_TRUE(c.slipping);
    EXPECT_NEAR(std::abs(m.shearForce(c)), std::tan(std::numbers::pi / 6) * m.normalForce(c), 1e-9 * m.normalForce(c));
  }
  EXPECT_GE(closed, 6);
  // The pressure came on suddenly and the slide keeps adaptive damping low, so the upper block
  // still bounces a little on the joint: its total normal force is the pressure within 5 %.
  EXPECT_NEAR(normal, kPressure, 0.05 * kPressure);
  EXPECT_GT(r.energy.slipDissipation, 0.0);
  EXPECT_LT(r.energy.largestExcess, 0.05);
}

TEST(DeformableContacts, OutlinesTooShortForTheRoundingOrTouchingThemselvesAreErrors) {
  VDEC_REQUIREMENTS("REQ-ZONE-005, REQ-ZONE-014");
  // Outline segments of 0.5 m from each block corner: a rounding of 0.6 m does not fit.
  std::string narrow = stackScene(2, 2);
  narrow.replace(narrow.find("rounding = 0.01"), 15, "rounding = 0.6");
  try {
    sceneFromText(narrow, "stack-rounding");
    FAIL() << "a rounding longer than the outline's segments was accepted";
  } catch (const GeometryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("block 'lower'"), std::string::npos) << what;
    EXPECT_NE(what.find("too short for the rounding"), std::string::npos) << what;
  }
  // An excavation leaving two zones of one block that meet only at a gridpoint.
  const std::string pinched = stackScene(2, 2, R"(
[[excavation]]
polygon = [[0.5, 0.0], [1.01, 0.0], [1.01, 0.5], [0.5, 0.5]]
[[excavation]]
polygon = [[-0.01, 0.5], [0.5, 0.5], [0.5, 1.01], [-0.01, 1.01]]
)");
  try {
    sceneFromText(pinched, "stack-pinched");
    FAIL() << "an outline touching itself was accepted";
  } catch (const GeometryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("block 'lower': its outline touches itself at the gridpoint at (0.5, 0.5)"), std::string::npos)
        << what;
  }
}

TEST(DeformableContacts, JointedKirschApproachesTheIntactPlateAsTheJointStiffens) {
  VDEC_REQUIREMENTS("REQ-ZONE-015");
  // DB-KIRSCH-JOINTED (the Kirsch plate of DB-KIRSCH cut along 45 degrees by a bonded joint,
  // zoned alike on both sides) against DB-KIRSCH itself: at every gridpoint the displacement
  // differs from the intact plate's only by what the joint's compliance adds, about
  // (E / kn) / a of the displacement (1e-3 at kn = 1e13, where E / kn = 1 mm): ten times the
  // stiffness, a tenth of the difference.
  const std::string problems = std::string(VDEC_PROBLEMS_DIR) + "/";
  auto relaxed = [&](const std::string& problem, const std::vector<std::string>& overrides) {
    Scene s = readScene(problems + problem + "/scene.toml", overrides);
    s.settings.stop = {};
    s.settings.stop.ratio = 1e-6;
    s.settings.stop.cycles = 200000;
    Cycle cycle(s.model, s.settings, {});
    const RunReport r = cycle.run();
    EXPECT_EQ(r.stopReason, "ratio") << problem << ": " << r.error;
    return s.model;
  };
  const Model intact = relaxed("DB-KIRSCH", {});
  auto largestDifference = [&](const Model& jointed) {
    double largest = 0.0, scale = 0.0;
    const Gridpoints& gi = intact.gridpoints;
    const Gridpoints& gj = jointed.gridpoints;
    for (int i = 0; i < gi.size(); ++i) scale = std::max(scale, norm(gi.position[i] - gi.initialPosition[i]));
    int matched = 0;
    for (int k = 0; k < gj.size(); ++k) {
      for (int i = 0; i < gi.size(); ++i) {
        if (norm(gi.initialPosition[i] - gj.initialPosition[k]) > 1e-9) continue;
        largest = std::max(largest, norm((gj.position[k] - gj.initialPosition[k]) - (gi.position[i] - gi.initialPosition[i])));
        ++matched;
      }
    }
    EXPECT_EQ(matched, gj.size());  // the same zoning: every gridpoint of the jointed plate has its twin
    return largest / scale;
  };
  const double stiff = largestDifference(relaxed("DB-KIRSCH-JOINTED", {}));
  const double softer = largestDifference(relaxed("DB-KIRSCH-JOINTED", {"joint_material[0].kn=1e12", "joint_material[0].ks=1e12"}));
  EXPECT_LT(stiff, 1e-3);
  EXPECT_NEAR(softer / stiff, 10.0, 1.5);
}

TEST(DeformableContacts, TheDirectSolveWithJointsReachesTheRelaxedEquilibrium) {
  VDEC_REQUIREMENTS("REQ-ZONE-009, REQ-ZONE-014");
  // The direct solve assembles closed joints as springs on the relative displacement of the
  // gridpoints they join. On DB-KIRSCH-JOINTED it must land where dynamic relaxation lands (the
  // relaxation stopped at a ratio of 1e-6, its floor with this stiff joint being 5e-7), and
  // then hold: the explicit cycles that follow stop at once on a ratio the relaxation cannot
  // reach.
  const std::string scene = std::string(VDEC_PROBLEMS_DIR) + "/DB-KIRSCH-JOINTED/scene.toml";
  auto run = [&](bool direct) {
    Scene s = readScene(scene, {direct ? "solver.static_solve=true" : "solver.static_solve=false"});
    s.settings.stop = {};
    s.settings.stop.ratio = direct ? 1e-8 : 1e-6;
    s.settings.stop.cycles = 200000;
    Cycle cycle(s.model, s.settings, {});
    const RunReport r = cycle.run();
    EXPECT_EQ(r.stopReason, "ratio") << r.error;
    return std::make_pair(s.model, r);
  };
  const auto [relaxed, relaxedReport] = run(false);
  const auto [direct, directReport] = run(true);
  EXPECT_LE(directReport.cycles, 10);
  EXPECT_GT(relaxedReport.cycles, 1000);
  double largest = 0.0, scale = 0.0;
  for (int i = 0; i < relaxed.gridpoints.size(); ++i) {
    const Vec2 u = relaxed.gridpoints.position[i] - relaxed.gridpoints.initialPosition[i];
    scale = std::max(scale, norm(u));
    largest = std::max(largest, norm((direct.gridpoints.position[i] - direct.gridpoints.initialPosition[i]) - u));
  }
  // The relaxation's own distance from equilibrium at its stop (a ratio of 1e-6) and the
  // O(strain) = 1e-6 geometric terms the linear solve leaves for the cycles; 1.3e-6 measured:
  // 1e-5 of the largest displacement.
  EXPECT_LT(largest, 1e-5 * scale);
  ASSERT_EQ(direct.contacts.size(), relaxed.contacts.size());
  for (std::size_t c = 0; c < direct.contacts.size(); ++c)
    EXPECT_NEAR(direct.contacts[c].normalStress, relaxed.contacts[c].normalStress, 1e-4 * 1e4) << "contact " << c;  // 1e-4 of |S_x|
  EXPECT_LT(directReport.energy.largestExcess, 1e-6);  // the joints' energy counts as given
}

TEST(DeformableContacts, TheDirectSolveRefusesContinuouslyYieldingJoints) {
  VDEC_REQUIREMENTS("REQ-ZONE-009, REQ-ZONE-014");
  // A joint whose stiffness grows with its normal stress is no linear spring.
  std::string text = stackScene(2, 2);
  text.replace(text.find("adaptive_damping = true"), 23, "adaptive_damping = true\nstatic_solve = true");
  const std::size_t joint = text.find("[[joint_material]]");
  text.replace(joint, text.find("[[block]]") - joint, R"([[joint_material]]
name = "joint"
law = "continuously-yielding"
kn = 1e10
ks = 1e10
friction = 30.0
initial_friction = 40.0
roughness = 1e-3
)");
  Scene s = sceneFromText(text, "stack-direct-cy");
  try {
    Cycle cycle(s.model, s.settings, {});
    FAIL() << "a static solve with a continuously yielding joint was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("the direct solve takes joints as linear springs, and joint material 'joint' "
                                         "is continuously yielding"), std::string::npos)
        << e.what();
  }
}

TEST(DeformableContacts, TheTimeStepIncludesTheJointsStiffness) {
  VDEC_REQUIREMENTS("REQ-MC-006, REQ-ZONE-014");
  // 1.3-26: an outline gridpoint's stiffness gains max(kn, ks) times its two outline segments,
  // so a joint 1000 times stiffer than the rock over a zone shortens the step; interior
  // gridpoints keep their zones' stiffness.
  auto prepared = [](const std::string& kn) {
    std::string text = stackScene(2, 2);
    for (const std::string key : {"kn = ", "ks = "}) {
      const std::size_t at = text.find(key);
      text.replace(at, text.find('\n', at) - at, key + kn);
    }
    Scene s = sceneFromText(text, "stack-step-" + kn);
    Cycle cycle(s.model, s.settings, {});
    return std::make_pair(s.model, cycle.timeStep());
  };
  const auto [soft, softStep] = prepared("1e3");
  const auto [stiff, stiffStep] = prepared("1e13");
  const Vertices& vx = stiff.vertices;
  std::vector<char> outline(stiff.gridpoints.size(), 0);
  for (int v = 0; v < vx.size(); ++v) {
    const int g = vx.gridpoint[v];
    outline[g] = 1;
    const double segments = vx.geometry[v].edgeLength + vx.geometry[vx.prev[v]].edgeLength;
    EXPECT_NEAR(stiff.gridpoints.stiffness[g] - soft.gridpoints.stiffness[g], (1e13 - 1e3) * segments, 1e-9 * 1e13 * segments);
  }
  for (int g = 0; g < stiff.gridpoints.size(); ++g) {
    if (!outline[g]) {
      EXPECT_EQ(stiff.gridpoints.stiffness[g], soft.gridpoints.stiffness[g]);
    }
  }
  double expected = INFINITY;
  for (int g = 0; g < stiff.gridpoints.size(); ++g)
    expected = std::min(expected, 2.0 * std::sqrt(stiff.gridpoints.mass[g] / stiff.gridpoints.stiffness[g]));
  EXPECT_DOUBLE_EQ(stiffStep, expected);  // 1.3-25 with the joints' term
  EXPECT_LT(stiffStep, 0.2 * softStep);
}

// A rigid 0.3 m block on the base's left end, x = 0.1 to 0.4.
const std::string kSmallTop = "[[0.1, 1.0], [0.4, 1.0], [0.4, 1.3], [0.1, 1.3]]";

TEST(DeformableContacts, ABlockRestsBesideANotchInADeformableOutline) {
  VDEC_REQUIREMENTS("REQ-ZONE-014");
  // The base with the cell [0.5, 1] x [0.5, 1] excavated: a non-convex outline, where the
  // wedge of the notch's far corner also holds points above the near face. A new contact must
  // take the feature nearest the corner, not the one of least overlap (which for a convex
  // block is the same): the block rests on the left column, carried by two contacts.
  const Relaxed run = relax(blockOnZonedBase(4, kSmallTop, "[[excavation]]\npolygon = [[0.5, 0.5], [1.0, 0.5], [1.0, 1.01], [0.5, 1.01]]\n"),
                            "notched-base");
  ASSERT_EQ(run.report.errorCode, 0) << run.report.error;
  EXPECT_EQ(run.report.stopReason, "ratio");
  const Model& m = run.model;
  ASSERT_EQ(m.contacts.size(), 2u);
  double normal = 0.0;
  for (const Contact& c : m.contacts) normal += m.normalForce(c);
  EXPECT_NEAR(normal, 2500.0 * 0.09 * 10.0, 1e-6 * 2250.0);
  const int top = 1;
  EXPECT_NEAR(m.blocks.centroid[top].y, 1.15, 1e-5);  // resting, sunk by the joint's closure only
}

TEST(DeformableContacts, ADeformableBlockCutInTwoIsAnError) {
  VDEC_REQUIREMENTS("REQ-ZONE-005, REQ-ZONE-014");
  // An excavation through the whole height of the base leaves two pieces; contacts on the
  // smaller would be lost, so the scene is refused naming the block.
  try {
    sceneFromText(blockOnZonedBase(4, kSmallTop, "[[excavation]]\npolygon = [[0.5, -0.01], [1.0, -0.01], [1.0, 1.01], [0.5, 1.01]]\n"),
                  "split-base");
    FAIL() << "a deformable block in two pieces was accepted";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("block 'base' is in 2 pieces (an excavation cut it apart)"), std::string::npos)
        << e.what();
  }
}

TEST(DeformableContacts, ZonesFinerThanTheRoundingStillPartitionTheJoint) {
  VDEC_REQUIREMENTS("REQ-ZONE-015");
  // The stack scaled to 0.1 m blocks zoned 8 x 8: outline segments of 12.5 mm against a
  // rounding of 10 mm. Each contact's share of the joint is then below d, and must stand (no
  // floor of d, which would count 1.6 times the joint); the sides of the two blocks, in line at
  // the joint's ends, face no part of each other. The stack settles with a uniform joint stress.
  std::string text = stackScene(8, 8);
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]",
                                                                     "[[0.0, 0.0], [0.1, 0.0], [0.1, 0.1], [0.0, 0.1]]"},
                                 {"[[0.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]]", "[[0.0, 0.1], [0.1, 0.1], [0.1, 0.2], [0.0, 0.2]]"},
                                 {"y = [2.0, 2.0]", "y = [0.2, 0.2]"}})
    text.replace(text.find(from), from.size(), to);
  const Relaxed run = relax(text, "small-stack");
  ASSERT_EQ(run.report.errorCode, 0) << run.report.error;
  EXPECT_EQ(run.report.stopReason, "ratio");
  double length = 0.0;
  for (const Contact& c : run.model.contacts) {
    length += c.length;
    EXPECT_NEAR(contactNormalStress(run.model, c), kPressure, 1e-4 * kPressure);
  }
  EXPECT_NEAR(length, 0.1, 1e-5);
}

TEST(DeformableContacts, TheDirectSolveRefusesToCloseAnOpenJointAndReportsSlip) {
  VDEC_REQUIREMENTS("REQ-ZONE-009, REQ-ZONE-014");
  // The solve's springs are the joints closed at the start. Two blocks side by side, each held
  // at its base, 50 um apart (their joint open), the left pushed towards the right: the solve
  // would push it through the right one, which it must refuse rather than let the cycles start
  // from interpenetrating blocks.
  const std::string apart = R"(
[model]
rounding = 0.01
[solver]
adaptive_damping = true
static_solve = true
[stop]
ratio = 1e-7
cycles = 1000
)" + rockAndJoint(1e11) + R"(
[[block]]
name = "left"
material = "rock"
vertices = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
zoning = { nx = 4, ny = 4 }
[[block]]
name = "right"
material = "rock"
vertices = [[1.00005, 0.0], [2.00005, 0.0], [2.00005, 1.0], [1.00005, 1.0]]
zoning = { nx = 4, ny = 4 }
[[boundary]]
block = "left"
y = [0.0, 0.0]
fix = ["x", "y"]
[[boundary]]
block = "right"
y = [0.0, 0.0]
fix = ["x", "y"]
[[boundary]]
block = "left"
x = [0.0, 0.0]
pressure = 2e6
)";
  Scene s = sceneFromText(apart, "apart-direct");
  try {
    Cycle cycle(s.model, s.settings, {});
    FAIL() << "a direct solve through an open joint was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("the direct solve closed an open joint"), std::string::npos) << e.what();
  }
  // A cohesionless joint sheared beyond its strength: the linear springs cannot follow the slip,
  // so the solve does not converge; it says so (its residual), and the cycles finish the job.
  std::string sheared = stackScene(2, 2, "[[boundary]]\nblock = \"upper\"\ny = [2.0, 2.0]\nfix = [\"x\"]\n");
  sheared.replace(sheared.find("adaptive_damping = true"), 23, "adaptive_damping = true\nstatic_solve = true");
  sheared.replace(sheared.find("cohesion = 1e6\ntension = 1e6\n"), 28, "");
  sheared.replace(sheared.find("[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]"), 48,
                  "[[0.0, 0.0], [1.0, 0.0], [1.0, 1.8], [0.0, 0.2]]");
  sheared.replace(sheared.find("[[0.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]]"), 48,
                  "[[0.0, 0.2], [1.0, 1.8], [1.0, 2.0], [0.0, 2.0]]");
  Scene slip = sceneFromText(sheared, "stack-direct-slip");
  Cycle cycle(slip.model, slip.settings, {});
  const RunReport r = cycle.run();
  EXPECT_EQ(r.errorCode, 0) << r.error;
  EXPECT_GT(r.staticSolveResidual, 1e-3);
  EXPECT_EQ(r.stopReason, "ratio");
}

TEST(DeformableContacts, TheMeanZoneStressHistoryIsTheLoadOverTheWidth) {
  VDEC_REQUIREMENTS("REQ-MC-005");
  // model.mean_syy averages syy over all zones by their present areas: on the jointed stack
  // under 100 kPa it is -p (the stress is uniform), and model.mean_sxx is 0.
  const std::string text = stackScene(4, 3, R"(
[[history]]
name = "syy"
quantity = "model.mean_syy"
every = 1000
[[history]]
name = "sxx"
quantity = "model.mean_sxx"
every = 1000
)");
  Scene s = sceneFromText(text, "stack-mean");
  Cycle cycle(s.model, s.settings, s.histories);
  const RunReport r = cycle.run();
  ASSERT_EQ(r.errorCode, 0) << r.error;
  ASSERT_EQ(r.histories.size(), 2u);
  EXPECT_NEAR(r.histories[0].value.back(), -kPressure, 2e-5 * kPressure);
  EXPECT_NEAR(r.histories[1].value.back(), 0.0, 2e-5 * kPressure);
  // Without zones there is nothing to average: an error naming the key.
  try {
    sceneFromText(vdec::testing::blockOnBase() + "[[history]]\nname = \"s\"\nquantity = \"model.mean_syy\"\n", "rigid-mean");
    FAIL() << "a mean zone stress history without zones was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("key 'history[0].quantity': model.mean_syy averages the stress of the zones"),
              std::string::npos)
        << e.what();
  }
}
