#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "contact/broad_phase.hpp"
#include "contact/contact_detection.hpp"
#include "contact/contact_geometry.hpp"
#include "core/errors.hpp"
#include "requirements.hpp"
#include "scene_fixture.hpp"

using namespace vdec;
using vdec::testing::blockOnBaseDefinition;
using vdec::testing::sceneFromText;

namespace {
// Moves block b rigidly to a centroid and rotation and updates its vertices.
void place(Model& m, int b, Vec2 centroid, double rotation) {
  m.blocks.centroid[b] = centroid;
  m.blocks.rotation[b] = rotation;
  placeBlockVertices(m, b);
}
}  // namespace

TEST(ContactGeometry, RightAngleCornerArcHasRadiusDAndCentreOnTheBisector) {
  VDEC_REQUIREMENTS("REQ-CONTACT-001");
  Scene s = buildScene(blockOnBaseDefinition());
  const Model& m = s.model;
  const int corner = m.blocks.firstVertex[1];  // (-0.5, 0) of "top"
  EXPECT_NEAR(m.vertices.geometry[corner].arcRadius, 0.01, 1e-15);
  EXPECT_NEAR(m.vertices.geometry[corner].arcCentre.x, -0.49, 1e-12);
  EXPECT_NEAR(m.vertices.geometry[corner].arcCentre.y, 0.01, 1e-12);
}

TEST(ContactGeometry, EdgeToEdgeContactIsTwoCornerEdgeContactsOfHalfLength) {
  VDEC_REQUIREMENTS("REQ-CONTACT-002");
  Scene s = buildScene(blockOnBaseDefinition());
  Model& m = s.model;
  ContactDetection detection;
  detection.initialise(m);
  ASSERT_EQ(m.contacts.size(), 2u);
  for (const Contact& c : m.contacts) {
    EXPECT_EQ(c.blockA, 1);
    EXPECT_EQ(c.featureKind, FeatureKind::Edge);
    EXPECT_NEAR(contactGeometry(m, c).normal.y, 1.0, 1e-15);
    EXPECT_NEAR(c.overlap, 0.0, 1e-15);
    const FeatureHit hit = nearestFeature(m, c.corner, c.blockB);
    EXPECT_NEAR(contactLength(m, c.corner, hit, false), 0.5, 1e-12);
  }
}

TEST(ContactGeometry, NormalVariesContinuouslyAsABlockRollsOverACorner) {
  VDEC_REQUIREMENTS("REQ-CONTACT-001");
  // The top block's corner slides around the base's corner at (1.5, 0): the contact passes from
  // the base's top edge, over its rounded corner, to its side edge. The normal must turn
  // smoothly: no jump larger than a small multiple of the step in position.
  Scene s = buildScene(blockOnBaseDefinition());
  Model& m = s.model;
  const int top = 1;
  const int corner = m.blocks.firstVertex[top];  // bottom-left corner of "top"
  const Vec2 arcOffset = m.vertices.localArcCentre[corner];
  const double rA = m.vertices.geometry[corner].arcRadius, rB = m.vertices.geometry[m.blocks.firstVertex[0] + 2].arcRadius;
  const Vec2 baseArc = m.vertices.geometry[m.blocks.firstVertex[0] + 2].arcCentre;
  Vec2 previous{0.0, 0.0};
  double largestTurn = 0.0;
  const int steps = 2000;
  for (int i = 0; i <= steps; ++i) {
    // Move the corner's arc centre along a quarter circle around the base's corner arc, at a
    // distance rA + rB (touching), from above the top edge to beside the side edge.
    const double angle = std::numbers::pi / 2.0 * (1.2 - 1.4 * i / steps);
    const Vec2 target = baseArc + (rA + rB) * Vec2{std::cos(angle), std::sin(angle)};
    place(m, top, target - arcOffset, 0.0);
    const FeatureHit hit = nearestFeature(m, corner, 0);
    ASSERT_TRUE(std::isfinite(hit.overlap));
    if (i > 0) largestTurn = std::max(largestTurn, std::acos(std::clamp(dot(hit.normal, previous), -1.0, 1.0)));
    previous = hit.normal;
  }
  const double angularStep = std::numbers::pi / 2.0 * 1.4 / steps;
  EXPECT_LE(largestTurn, 1.01 * angularStep);
}

TEST(ContactGeometry, CornerToCornerNormalJoinsTheArcCentres) {
  VDEC_REQUIREMENTS("REQ-CONTACT-001");
  Scene s = buildScene(blockOnBaseDefinition());
  Model& m = s.model;
  const int corner = m.blocks.firstVertex[1];
  const int baseCorner = m.blocks.firstVertex[0] + 2;  // (1.5, 0)
  // Put the top block's bottom-left arc diagonally above-right of the base's top-right arc.
  const Vec2 direction = normalized(Vec2{1.0, 1.0});
  const double touch = m.vertices.geometry[corner].arcRadius + m.vertices.geometry[baseCorner].arcRadius - 1e-4;
  const Vec2 target = m.vertices.geometry[baseCorner].arcCentre + touch * direction;
  place(m, 1, target - m.vertices.localArcCentre[corner], 0.0);
  const FeatureHit hit = nearestFeature(m, corner, 0);
  EXPECT_EQ(hit.kind, FeatureKind::Corner);
  EXPECT_EQ(hit.feature, baseCorner);
  EXPECT_NEAR(hit.normal.x, direction.x, 1e-12);
  EXPECT_NEAR(hit.normal.y, direction.y, 1e-12);
  EXPECT_NEAR(hit.overlap, 1e-4, 1e-12);
  // Following from a neighbouring feature finds the same.
  const FeatureHit followed = followFeature(m, corner, 0, m.blocks.firstVertex[0] + 1, FeatureKind::Edge);
  EXPECT_EQ(followed.feature, baseCorner);
  EXPECT_EQ(followed.kind, FeatureKind::Corner);
}

TEST(ContactGeometry, TwoTouchingCornersMakeOneContact) {
  VDEC_REQUIREMENTS("REQ-CONTACT-002");
  // Two equal blocks stacked exactly: corners meet corners; each pair must give one contact.
  Scene s = sceneFromText(R"(
[model]
rounding = 0.01
[stop]
cycles = 1
[[block_material]]
name = "rock"
density = 2500.0
[[joint_material]]
name = "j"
kn = 1e8
ks = 1e8
[[block]]
name = "lower"
material = "rock"
vertices = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
fix = ["x", "y", "rotation"]
[[block]]
name = "upper"
material = "rock"
vertices = [[0.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]]
)", "stacked");
  ContactDetection detection;
  detection.initialise(s.model);
  EXPECT_EQ(s.model.contacts.size(), 2u);
  double length = 0.0;
  for (const Contact& c : s.model.contacts) length += c.length > 0 ? c.length : contactLength(s.model, c.corner, contactGeometry(s.model, c), false);
  EXPECT_NEAR(length, 1.0, 1e-9);
}

TEST(ContactGeometry, OverlappingBlocksAtTheStartAreAnErrorNamingThem) {
  VDEC_REQUIREMENTS("REQ-CONTACT-003");
  SceneDefinition scene = blockOnBaseDefinition();
  scene.blocks[1].vertices = {{-0.5, -0.003}, {0.5, -0.003}, {0.5, 1.0}, {-0.5, 1.0}};
  Scene s = buildScene(scene);
  ContactDetection detection;
  try {
    detection.initialise(s.model);
    FAIL() << "overlap not detected";
  } catch (const GeometryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'top'"), std::string::npos) << what;
    EXPECT_NE(what.find("'base'"), std::string::npos) << what;
  }
}

TEST(ContactGeometry, BlocksCrossingLikeAPlusSignAreAnErrorNamingThem) {
  VDEC_REQUIREMENTS("REQ-CONTACT-003");
  // No corner of either block is inside the other: only their edges cross.
  Scene s = sceneFromText(R"(
[model]
rounding = 0.01
[stop]
cycles = 1
[[block_material]]
name = "rock"
density = 2500.0
[[joint_material]]
name = "j"
kn = 1e8
ks = 1e8
[[block]]
name = "across"
material = "rock"
vertices = [[-2.0, -0.5], [2.0, -0.5], [2.0, 0.5], [-2.0, 0.5]]
[[block]]
name = "upright"
material = "rock"
vertices = [[-0.5, -2.0], [0.5, -2.0], [0.5, 2.0], [-0.5, 2.0]]
)", "plus");
  ContactDetection detection;
  try {
    detection.initialise(s.model);
    FAIL() << "crossing not detected";
  } catch (const GeometryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'across'"), std::string::npos) << what;
    EXPECT_NE(what.find("'upright'"), std::string::npos) << what;
  }
}

TEST(ContactDetection, GridBroadPhaseFindsEveryOverlappingPairOnceAsAllPairsDoes) {
  VDEC_REQUIREMENTS("REQ-CONTACT-004");
  // Boxes of sizes over three orders of magnitude, a lattice-like cluster, and one box spanning
  // everything (a base block): the grid must find exactly the pairs a test of all pairs finds.
  std::vector<double> minX, maxX, minY, maxY;
  std::uint64_t state = 12345;
  auto uniform = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  auto add = [&](double x, double y, double w, double h) {
    minX.push_back(x);
    maxX.push_back(x + w);
    minY.push_back(y);
    maxY.push_back(y + h);
  };
  for (int i = 0; i < 400; ++i) {
    const double size = std::pow(10.0, -2.0 + 3.0 * uniform());
    add(50.0 * uniform(), 50.0 * uniform(), size, size * (0.5 + uniform()));
  }
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 10; ++j) add(60.0 + i - 0.01, j - 0.01, 1.02, 1.02);  // touching lattice
  add(-1.0, -5.0, 100.0, 4.99);                                                // the base
  BroadPhaseGrid grid;
  auto found = overlappingPairs(minX, maxX, minY, maxY, grid);
  std::sort(found.begin(), found.end());
  EXPECT_TRUE(std::adjacent_find(found.begin(), found.end()) == found.end()) << "a pair found twice";
  std::vector<std::pair<int, int>> expected;
  const int n = static_cast<int>(minX.size());
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      if (!(minX[b] > maxX[a] || minX[a] > maxX[b] || minY[b] > maxY[a] || minY[a] > maxY[b])) expected.emplace_back(a, b);
  EXPECT_EQ(found, expected);
  EXPECT_GT(expected.size(), 500u);
  // Reused buffers give the same answer again.
  auto again = overlappingPairs(minX, maxX, minY, maxY, grid);
  std::sort(again.begin(), again.end());
  EXPECT_EQ(again, expected);
}
