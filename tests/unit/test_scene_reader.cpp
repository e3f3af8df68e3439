#include <cmath>
#include <regex>

#include "core/errors.hpp"
#include "requirements.hpp"
#include "scene_fixture.hpp"

using namespace vdec;
using vdec::testing::blockOnBase;
using vdec::testing::sceneFromText;
using vdec::testing::writeSceneFile;

namespace {
// The message of the SceneError the text raises ("" if none).
std::string sceneError(const std::string& text, const std::string& name) {
  try {
    sceneFromText(text, name);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}
}  // namespace

TEST(SceneReader, ReadsBlocksMaterialsAndDerivedProperties) {
  VDEC_REQUIREMENTS("REQ-IO-001");
  const Scene s = sceneFromText(blockOnBase(), "valid");
  ASSERT_EQ(s.model.blocks.size(), 2);
  EXPECT_EQ(s.model.blocks.name[1], "top");
  EXPECT_DOUBLE_EQ(s.model.blocks.mass[1], 2500.0);
  EXPECT_NEAR(s.model.blocks.inertia[1], 2500.0 * 2.0 / 12.0, 1e-9);
  EXPECT_EQ(s.model.blocks.driven[0], DriveAll);
  EXPECT_DOUBLE_EQ(s.model.gravity.y, -10.0);
  EXPECT_EQ(s.sha256.size(), 64u);
  EXPECT_NEAR(s.settings.frac, 0.1, 0.0);  // default
}

TEST(SceneReader, UnknownKeyIsAnErrorNamingFileLineAndKey) {
  VDEC_REQUIREMENTS("REQ-IO-002");
  const std::string text = replaced(blockOnBase(), "rounding = 0.01", "rounding = 0.01\nroundng = 0.02");
  const std::string e = sceneError(text, "unknown-key");
  EXPECT_TRUE(std::regex_search(e, std::regex(R"(unknown-key\.toml:5: key 'model\.roundng': unknown key)"))) << e;
}

TEST(SceneReader, WrongTypeIsAnErrorNamingTheKey) {
  VDEC_REQUIREMENTS("REQ-IO-002");
  const std::string e = sceneError(replaced(blockOnBase(), "density = 2500.0", "density = \"heavy\""), "wrong-type");
  EXPECT_TRUE(std::regex_search(e, std::regex(R"(wrong-type\.toml:\d+: key 'block_material\[0\]\.density': must be a number)"))) << e;
}

TEST(SceneReader, MissingRequiredKeyIsAnError) {
  VDEC_REQUIREMENTS("REQ-IO-002");
  const std::string e = sceneError(replaced(blockOnBase(), "kn = 1e8\n", ""), "missing");
  EXPECT_NE(e.find("key 'joint_material[0].kn': is required"), std::string::npos) << e;
  const std::string noStop = sceneError(replaced(blockOnBase(), "[stop]\ncycles = 10\n", ""), "no-stop");
  EXPECT_NE(noStop.find("'stop': is required"), std::string::npos) << noStop;
}

TEST(SceneReader, OutOfRangeValuesAreErrors) {
  VDEC_REQUIREMENTS("REQ-IO-002");
  EXPECT_NE(sceneError(replaced(blockOnBase(), "friction = 30.0", "friction = 95.0"), "range1").find("[0, 90)"),
            std::string::npos);
  EXPECT_NE(sceneError(replaced(blockOnBase(), "kn = 1e8", "kn = -1e8"), "range2").find("must be > 0"),
            std::string::npos);
  EXPECT_NE(sceneError(blockOnBase("", "cohesion = -1.0\n"), "range3").find("must be >= 0"), std::string::npos);
  EXPECT_NE(sceneError(replaced(blockOnBase(), "cycles = 10", "cycles = 0"), "range4").find("must be > 0"),
            std::string::npos);
}

TEST(SceneReader, SyntaxErrorNamesTheLine) {
  VDEC_REQUIREMENTS("REQ-IO-002");
  const std::string e = sceneError(replaced(blockOnBase(), "rounding = 0.01", "rounding = = 0.01"), "syntax");
  EXPECT_TRUE(std::regex_search(e, std::regex(R"(syntax\.toml:4: )"))) << e;
}

TEST(SceneReader, ReferencesToUnknownNamesAreErrors) {
  VDEC_REQUIREMENTS("REQ-IO-002");
  EXPECT_NE(sceneError(replaced(blockOnBase(), "material = \"rock\"\nvertices = [[-0.5", "material = \"granite\"\nvertices = [[-0.5"), "material")
                .find("no block material named 'granite'"),
            std::string::npos);
  const std::string history = blockOnBase() + "[[history]]\nname = \"x\"\nquantity = \"block.x\"\nblock = \"lid\"\n";
  EXPECT_NE(sceneError(history, "history").find("no block named 'lid'"), std::string::npos);
  const std::string quantity = blockOnBase() + "[[history]]\nname = \"x\"\nquantity = \"block.z\"\nblock = \"top\"\n";
  EXPECT_NE(sceneError(quantity, "quantity").find("unknown quantity 'block.z'"), std::string::npos);
}

TEST(SceneReader, InvalidPolygonIsAGeometryErrorNamingTheBlock) {
  VDEC_REQUIREMENTS("REQ-GEOM-002");
  try {
    sceneFromText(replaced(blockOnBase(), "[[-0.5, 0.0], [0.5, 0.0], [0.5, 1.0], [-0.5, 1.0]]",
                           "[[-0.5, 0.0], [-0.5, 1.0], [0.5, 1.0], [0.5, 0.0]]"),
                  "clockwise");
    FAIL();
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("block 'top'"), std::string::npos) << e.what();
  }
}

TEST(SceneReader, OverridesReplaceKeysAndAreRecorded) {
  VDEC_REQUIREMENTS("REQ-IO-003");
  const std::string path = writeSceneFile(blockOnBase(), "override");
  const Scene s = readScene(path, {"solver.frac=0.35", "model.gravity=[1.0, -5.0]"});
  EXPECT_DOUBLE_EQ(s.settings.frac, 0.35);
  EXPECT_DOUBLE_EQ(s.model.gravity.x, 1.0);
  ASSERT_EQ(s.overrides.size(), 2u);
  EXPECT_THROW(readScene(path, {"solver.frac"}), SceneError);
  EXPECT_THROW(readScene(path, {"block.frac=1"}), SceneError);  // an array of tables, not indexed
  EXPECT_THROW(readScene(path, {"block[5].name=\"x\""}), SceneError);
  const Scene indexed = readScene(path, {"joint_material[0].friction=20.0", "block[1].velocity=[1.0, 0.0]"});
  EXPECT_NEAR(indexed.model.jointMaterials[0].tanFriction, std::tan(20.0 * M_PI / 180.0), 1e-15);
  EXPECT_EQ(indexed.model.blocks.velocity[1].x, 1.0);
}

TEST(SceneReader, RegionIsCutIntoNamedBlocks) {
  VDEC_REQUIREMENTS("REQ-GEOM-003");
  const std::string text = R"(
[model]
rounding = 0.01
[stop]
cycles = 1
[[block_material]]
name = "rock"
density = 2000.0
[[joint_material]]
name = "j"
kn = 1e9
ks = 1e9
[[region]]
name = "wall"
material = "rock"
vertices = [[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0]]
[[region.joint_set]]
angle = 90.0
spacing = 1.0
[[region.crack]]
from = [-1.0, 1.0]
to = [5.0, 1.0]
)";
  const Scene s = sceneFromText(text, "region");
  EXPECT_EQ(s.model.blocks.size(), 8);
  EXPECT_EQ(s.model.blocks.name[0], "wall.1");
  // A joint direction beyond a turn either way, or a variation beyond a right angle, is refused
  // (-1e308 degrees reached an undefined conversion while the region's size was estimated).
  EXPECT_NE(sceneError(replaced(text, "angle = 90.0", "angle = -1e308"), "angle").find("must be in [-360, 360] degrees"),
            std::string::npos);
  EXPECT_NE(sceneError(replaced(text, "angle = 90.0", "angle = 90.0\nangle_variation = 91.0"), "variation")
                .find("key 'region[0].joint_set[0].angle_variation': must be in [0, 90] degrees"),
            std::string::npos);
  double mass = 0.0;
  for (double m : s.model.blocks.mass) mass += m;
  EXPECT_NEAR(mass, 2000.0 * 8.0, 1e-9);
}

TEST(SceneReader, OverrideErrorsNameTheOverride) {
  VDEC_REQUIREMENTS("REQ-IO-003");
  const std::string path = writeSceneFile(blockOnBase(), "override-error");
  try {
    readScene(path, {"solver.frac=-0.5"});
    FAIL();
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("--set 'solver.frac=-0.5'"), std::string::npos) << what;
    EXPECT_NE(what.find("key 'solver.frac'"), std::string::npos) << what;
  }
  auto message = [&](const std::string& override) {
    try {
      readScene(path, {override});
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("solver.frob=1").find("--set 'solver.frob=1': key 'solver.frob': unknown key"), std::string::npos);
  EXPECT_NE(message("block[-1].name=\"x\"").find("bad index"), std::string::npos);
  // Small values are shown as written, not rounded to zero.
  EXPECT_NE(message("model.rounding=-1e-9").find("got -1e-09"), std::string::npos) << message("model.rounding=-1e-9");
}

TEST(SceneReader, RunLimitsAndJointAssignmentsAreChecked) {
  VDEC_REQUIREMENTS("REQ-IO-002,REQ-RUN-001");
  // A stop table with nothing in it names the table and its line.
  const std::string empty = sceneError(replaced(blockOnBase(), "cycles = 10", ""), "stop-empty");
  EXPECT_TRUE(std::regex_search(empty, std::regex(R"(stop-empty\.toml:6: \[stop\]: set at least one)"))) << empty;
  // A ratio alone could run for ever.
  const std::string ratio = sceneError(replaced(blockOnBase(), "cycles = 10", "ratio = 1e-5"), "stop-ratio");
  EXPECT_NE(ratio.find("key 'stop.ratio': needs a limit"), std::string::npos) << ratio;
  // The same joint assigned twice.
  const std::string assignment = "[[joint_assignment]]\nblocks = [\"top\", \"base\"]\njoint = \"joint\"\n";
  const std::string twice = sceneError(blockOnBase() + assignment + assignment, "assigned-twice");
  EXPECT_NE(twice.find("already assigned"), std::string::npos) << twice;
  EXPECT_TRUE(std::regex_search(twice, std::regex(R"(assigned-twice\.toml:\d+: key 'joint_assignment\[1\]\.blocks')"))) << twice;
}

TEST(SceneReader, ContinuouslyYieldingPropertiesAreReadAndCheckedByName) {
  VDEC_REQUIREMENTS("REQ-JOINT-007, REQ-JOINT-008, REQ-IO-002");
  const std::string cy = "law = \"continuously-yielding\"\nroughness = 5e-4\ninitial_friction = 40.0\n"
                         "kn_coefficient = 1e6\nkn_exponent = 0.5\n";
  const Scene s = sceneFromText(blockOnBase("", cy), "cy-valid");
  const JointMaterial& j = s.model.jointMaterials[0];
  EXPECT_EQ(j.law, JointLaw::ContinuouslyYielding);
  EXPECT_NEAR(j.friction, 30.0 * M_PI / 180.0, 1e-15);
  EXPECT_NEAR(j.initialFriction, 40.0 * M_PI / 180.0, 1e-15);
  EXPECT_DOUBLE_EQ(j.roughness, 5e-4);
  EXPECT_DOUBLE_EQ(j.knExponent, 0.5);
  auto error = [&](const std::string& from, const std::string& to, const std::string& name) {
    return sceneError(replaced(blockOnBase("", cy), from, to), name);
  };
  const std::string exponent = error("kn_exponent = 0.5", "kn_exponent = 1.5", "cy-exponent");
  EXPECT_TRUE(std::regex_search(exponent, std::regex(R"(cy-exponent\.toml:\d+: key 'joint_material\[0\]\.kn_exponent': must be in \[0, 1\])")))
      << exponent;
  EXPECT_NE(error("roughness = 5e-4", "roughness = 0.0", "cy-roughness").find("'joint_material[0].roughness': must be > 0"),
            std::string::npos);
  EXPECT_NE(error("initial_friction = 40.0", "initial_friction = 20.0", "cy-initial").find("initial_friction': must be in [friction, 90)"),
            std::string::npos);
  EXPECT_NE(error("friction = 30.0", "friction = 0.0", "cy-friction").find("friction': must be in (0, 90)"),
            std::string::npos);
  EXPECT_NE(error("roughness = 5e-4", "roughness = 5e-4\ncohesion = 1e5", "cy-cohesion").find("does not apply to the continuously-yielding law"),
            std::string::npos);
  EXPECT_NE(error("kn_coefficient = 1e6\n", "", "cy-orphan").find("kn_exponent': needs kn_coefficient"), std::string::npos);
}

TEST(SceneReader, VelocityHistoryNeedsADrivenDegreeOfFreedom) {
  VDEC_REQUIREMENTS("REQ-MOTION-003, REQ-IO-002");
  const std::string top = "vertices = [[-0.5, 0.0], [0.5, 0.0], [0.5, 1.0], [-0.5, 1.0]]\n";
  const std::string driven = top + "fix = [\"x\"]\nvelocity = [1e-3, 0.0]\nvelocity_history = { kind = \"sine\", frequency = 2.0 }\n";
  const Scene s = sceneFromText(replaced(blockOnBase(), top, driven), "history-valid");
  ASSERT_EQ(s.model.blocks.velocityHistory[1], 0);
  EXPECT_NEAR(s.model.timeFunctions[0](0.125), 1.0, 1e-12);
  const std::string e = sceneError(replaced(blockOnBase(), top, top + "velocity_history = { kind = \"constant\" }\n"), "history-free");
  EXPECT_TRUE(std::regex_search(e, std::regex(R"(history-free\.toml:\d+: key 'block\[1\]\.velocity_history': scales the velocity of fixed)")))
      << e;
}

TEST(SceneReader, ZoneFractionIsReadAndChecked) {
  VDEC_REQUIREMENTS("REQ-MC-003, REQ-IO-002");
  EXPECT_DOUBLE_EQ(sceneFromText(blockOnBase("[solver]\nzone_fraction = 0.5\n"), "zone-fraction").settings.zoneFraction, 0.5);
  EXPECT_DOUBLE_EQ(sceneFromText(blockOnBase(), "zone-fraction-default").settings.zoneFraction, 1.0);
  const std::string e = sceneError(blockOnBase("[solver]\nzone_fraction = 0.0\n"), "zone-fraction-zero");
  EXPECT_TRUE(std::regex_search(e, std::regex(R"(zone-fraction-zero\.toml:\d+: key 'solver\.zone_fraction': must be in \(0, 10\])")))
      << e;
}
