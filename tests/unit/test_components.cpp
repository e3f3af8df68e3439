// The cycle's step is its components' force stages, then their motion stages, each in the
// components' order, and only those the scene needs; the step is the smallest of their limits.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "motion/rigid_motion.hpp"
#include "requirements.hpp"
#include "run/cycle.hpp"
#include "scene_fixture.hpp"
#include "zone/cst.hpp"

using namespace vdec;
using vdec::testing::blockOnBaseDefinition;

namespace {

// A 3 m x 1 m zoned base held at its bottom, with a rigid block resting on it.
SceneDefinition blockOnZonedBase(bool pressedTop) {
  SceneDefinition s = blockOnBaseDefinition();
  BlockMaterial& rock = s.blockMaterials[0].material;
  rock.bulk = 5e9;
  rock.shear = 3e9;
  BlockDefinition& base = s.blocks[0];
  base.fix = 0;
  base.zoning.kind = ZoningDefinition::Kind::Structured;
  base.zoning.nx = 6;
  base.zoning.ny = 2;
  BoundaryDefinition& held = s.boundaries.emplace_back();
  held.block = "base";
  held.y = {-1.0, -1.0};
  held.fix = DriveX | DriveY;
  if (pressedTop) {
    BoundaryDefinition& side = s.boundaries.emplace_back();
    side.block = "base";
    side.x = {1.5, 1.5};
    side.loaded = true;
    side.stress = {-1e5, 0.0, 0.0};
  }
  return s;
}

std::vector<std::string> stagesOf(Scene& scene) {
  scene.settings.stop.cycles = 2;
  Cycle cycle(scene.model, scene.settings, {});
  return cycle.run().stages;
}

}  // namespace

TEST(Components, ARigidSceneRunsContactsThenRigidMotionAtTheRigidBlocksStep) {
  VDEC_REQUIREMENTS("REQ-RUN-006");
  Scene scene = buildScene(blockOnBaseDefinition());
  const double limit = rigidBlockTimeStep(scene.model, scene.settings.frac);
  EXPECT_EQ(stagesOf(scene), (std::vector<std::string>{"contact-detection", "contact-forces", "rigid-block-motion"}));
  Scene fresh = buildScene(blockOnBaseDefinition());
  Cycle cycle(fresh.model, fresh.settings, {});
  EXPECT_EQ(cycle.timeStep(), limit);
}

TEST(Components, ForceStagesOfEveryComponentRunBeforeAnyMotionStage) {
  VDEC_REQUIREMENTS("REQ-RUN-006");
  Scene scene = buildScene(blockOnZonedBase(true));
  EXPECT_EQ(stagesOf(scene), (std::vector<std::string>{"contact-detection", "contact-forces", "zone-forces",
                                                       "boundary-tractions", "rigid-block-motion",
                                                       "gridpoint-motion"}));
  // Without a loaded edge (fixed gridpoints need no stage) the boundaries component has none.
  Scene unloaded = buildScene(blockOnZonedBase(false));
  EXPECT_EQ(stagesOf(unloaded), (std::vector<std::string>{"contact-detection", "contact-forces", "zone-forces",
                                                          "rigid-block-motion", "gridpoint-motion"}));
}

TEST(Components, TheStepIsTheSmallestOfTheComponentsLimits) {
  VDEC_REQUIREMENTS("REQ-RUN-006");
  // The zoned base with the free rigid block on it: the rigid blocks' and the zones' limits both
  // count; scaling the zones' fraction moves the step from one to the other.
  for (const double zoneFraction : {10.0, 1e-3}) {
    SceneDefinition definition = blockOnZonedBase(false);
    definition.settings.zoneFraction = zoneFraction;
    definition.settings.frac = 0.01;
    Scene scene = buildScene(definition);
    Cycle cycle(scene.model, scene.settings, {});  // forms the gridpoint masses and stiffnesses
    const double rigid = rigidBlockTimeStep(scene.model, scene.settings.frac);
    const double zones = zoneFraction * zoneTimeStep(scene.model);
    EXPECT_EQ(cycle.timeStep(), std::min(rigid, zones)) << zoneFraction;
    EXPECT_EQ(zoneFraction > 1.0, rigid < zones) << "each limit decides once: " << rigid << " " << zones;
  }
}
