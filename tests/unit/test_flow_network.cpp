// The domain network of fracture flow: its loops around the voids, their areas, its order, and
// the fluid's conservation through the flow and through changes of the network.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "flow/flow_network.hpp"
#include "flow/fracture_flow.hpp"
#include "requirements.hpp"
#include "run/cycle.hpp"
#include "scene_fixture.hpp"

using namespace vdec;
using vdec::testing::sceneFromText;

namespace {

constexpr double kAperture = 1e-4, kRounding = 0.01;

std::string fluidScene(const std::string& blocks, const std::string& extra = "") {
  return R"(
[model]
rounding = 0.01
[stop]
cycles = 1
[fluid]
bulk_modulus = 2e9
viscosity = 1e-3
[[joint_material]]
name = "j"
kn = 1e10
ks = 1e10
friction = 30.0
aperture = 1e-4
residual_aperture = 1e-5
[[block_material]]
name = "rock"
density = 2500.0
young = 10e9
poisson = 0.25
)" + blocks + extra;
}

std::string rigidBlock(const std::string& name, double x0, double y0, double x1, double y1) {
  auto p = [](double x, double y) { return "[" + std::to_string(x) + ", " + std::to_string(y) + "]"; };
  return "[[block]]\nname = \"" + name + "\"\nmaterial = \"rock\"\nvertices = [" + p(x0, y0) + ", " + p(x1, y0) + ", " +
         p(x1, y1) + ", " + p(x0, y1) + "]\nfix = [\"x\", \"y\", \"rotation\"]\n";
}

}  // namespace

TEST(FlowNetwork, ATwoBlockJointIsOneDomainBetweenTwoMouthsHoldingItsHydraulicVolume) {
  VDEC_REQUIREMENTS("REQ-FLOW-001, REQ-FLOW-002");
  Scene scene = sceneFromText(fluidScene(rigidBlock("lower", 0, -1, 2, 0) + rigidBlock("upper", 0, 0, 2, 1)), "two");
  Cycle cycle(scene.model, scene.settings, {});
  const FlowState& f = scene.model.flow;
  ASSERT_EQ(f.domains.size(), 1u);
  ASSERT_EQ(f.knots.size(), 2u);
  for (const FlowKnot& k : f.knots) EXPECT_TRUE((k.domain[0] < 0) != (k.domain[1] < 0)) << "each knot a mouth";
  // The whole joint at the aperture a0 (the blocks just touch): L a0, to round-off. The mouths'
  // knots sit at the rounded corners, d in from the ends; the domain reaches to the corners.
  EXPECT_NEAR(f.domains[0].area, 2.0 * kAperture, 1e-15);
  EXPECT_NEAR(f.domains[0].centre.x, 1.0, 1e-12);
}

TEST(FlowNetwork, FourBlocksMeetingAtAPointGiveFourJointsAndTheirIntersection) {
  VDEC_REQUIREMENTS("REQ-FLOW-001");
  Scene scene = sceneFromText(fluidScene(rigidBlock("a", 0, 0, 1, 1) + rigidBlock("b", 1, 0, 2, 1) +
                                         rigidBlock("c", 0, 1, 1, 2) + rigidBlock("d", 1, 1, 2, 2)),
                              "four");
  Cycle cycle(scene.model, scene.settings, {});
  const FlowState& f = scene.model.flow;
  ASSERT_EQ(f.domains.size(), 5u);
  // The intersection: the domain centred at (1, 1), bounded by the four joints' inner ends; it
  // holds what the four joints hold within the contacts' reach of the crossing, not an area of
  // its own. Each joint arm: one domain from its mouth to the crossing.
  const auto centre = std::find_if(f.domains.begin(), f.domains.end(), [](const FlowDomain& d) {
    return std::abs(d.centre.x - 1.0) < 1e-9 && std::abs(d.centre.y - 1.0) < 1e-9;
  });
  ASSERT_NE(centre, f.domains.end());
  double arms = 0.0;
  for (const FlowDomain& d : f.domains)
    if (&d != &*centre) arms += d.area;
  // Four arms of length 1 at the aperture a0; the crossing holds the arms' last d each, 4 d a0.
  const double joints = 4.0 * kAperture;
  EXPECT_NEAR(arms + centre->area, joints, 1e-12 * joints) << "the network holds the joints' volume, no more, no less";
  EXPECT_NEAR(centre->area, 4.0 * kRounding * kAperture, 1e-12 * joints);
}

TEST(FlowNetwork, DomainIdsAndAreasDoNotDependOnTheOrderOfTheContacts) {
  VDEC_REQUIREMENTS("REQ-FLOW-001");
  Scene scene = sceneFromText(fluidScene(rigidBlock("a", 0, 0, 1, 1) + rigidBlock("b", 1, 0, 2, 1) +
                                         rigidBlock("c", 0, 1, 1, 2) + rigidBlock("d", 1, 1, 2, 2)),
                              "order");
  Cycle cycle(scene.model, scene.settings, {});
  Model& m = scene.model;
  const std::vector<FlowDomain> before = m.flow.domains;
  std::reverse(m.contacts.begin(), m.contacts.end());
  buildFlowNetwork(m, false);
  ASSERT_EQ(m.flow.domains.size(), before.size());
  for (std::size_t d = 0; d < before.size(); ++d) {
    EXPECT_EQ(m.flow.domains[d].key, before[d].key);
    EXPECT_EQ(m.flow.domains[d].area, before[d].area);
    EXPECT_EQ(m.flow.domains[d].centre.x, before[d].centre.x);
    EXPECT_EQ(m.flow.domains[d].centre.y, before[d].centre.y);
  }
}

TEST(FlowNetwork, TheFluidBalanceClosesToRoundOffInACoupledRunWhoseNetworkChanges) {
  VDEC_REQUIREMENTS("REQ-FLOW-003");
  // A rigid block driven along a zoned base with fluid held at the left mouth: its corners pass
  // the base's gridpoints, contacts come and go, and the network with them.
  const std::string blocks = R"(
[[block]]
name = "base"
material = "rock"
vertices = [[0.0, -1.0], [4.0, -1.0], [4.0, 0.0], [0.0, 0.0]]
zoning = { nx = 8, ny = 2 }
[[block]]
name = "slider"
material = "rock"
vertices = [[0.0, 0.0], [1.3, 0.0], [1.3, 1.0], [0.0, 1.0]]
fix = ["x", "y", "rotation"]
velocity = [40.0, 0.0]
[[boundary]]
block = "base"
y = [-1.0, -1.0]
fix = ["x", "y"]
[[flow_boundary]]
box = [-0.1, -0.1, 4.1, 0.1]
pressure = 1e5
)";
  Scene scene = sceneFromText(fluidScene(blocks), "balance");
  scene.model.flow.fluid.bulkModulus = 2e6;
  scene.settings.stop.cycles = 3000;
  Cycle cycle(scene.model, scene.settings, {});
  cycle.run();
  const FlowTotals& t = scene.model.flow.totals;
  EXPECT_GT(t.networkChanges, 10) << "the set-up must exercise the passing of fluid between networks";
  EXPECT_GT(t.inflow, 1e-7);
  EXPECT_LT(std::abs(flowImbalance(scene.model)), 1e-12 * (t.inflow + t.outflow + t.initialContent + t.created));
}
