#pragma once
// Scenes for unit tests: defined in code and made by the builder (scene/scene_builder.hpp), or,
// for the tests of the reader itself, written as TOML and read through the real reader.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <cmath>
#include <string>

#include "io/scene_reader.hpp"
#include "scene/scene_builder.hpp"

namespace vdec::testing {

// A folder of this test process's own, so that test runs side by side (two build trees, two
// worktrees) do not write over each other's scene files.
inline std::filesystem::path unitTestFolder() {
  return std::filesystem::temp_directory_path() / ("vdec-unit-" + std::to_string(::getpid()));
}

inline std::string writeSceneFile(const std::string& text, const std::string& name) {
  const auto dir = unitTestFolder();
  std::filesystem::create_directories(dir);
  const auto path = (dir / (name + ".toml")).string();
  std::ofstream(path) << text;
  return path;
}

inline Scene sceneFromText(const std::string& text, const std::string& name = "scene") {
  return readScene(writeSceneFile(text, name));
}

// A 1 m x 1 m block ("top", density 2500) resting on a fixed 3 m x 1 m base, touching at y = 0.
inline std::string blockOnBase(const std::string& extraModel = "", const std::string& joint = "") {
  return R"(
[model]
gravity = [0.0, -10.0]
rounding = 0.01
)" + extraModel + R"(
[stop]
cycles = 10
[[block_material]]
name = "rock"
density = 2500.0
[[joint_material]]
name = "joint"
kn = 1e8
ks = 1e8
friction = 30.0
)" + joint + R"(
[[block]]
name = "base"
material = "rock"
vertices = [[-1.5, -1.0], [1.5, -1.0], [1.5, 0.0], [-1.5, 0.0]]
fix = ["x", "y", "rotation"]
[[block]]
name = "top"
material = "rock"
vertices = [[-0.5, 0.0], [0.5, 0.0], [0.5, 1.0], [-0.5, 1.0]]
)";
}

// blockOnBase() in code: a definition to change before it is built, e.g. settings.frac.
inline SceneDefinition blockOnBaseDefinition() {
  SceneDefinition s;
  s.model.gravity = {0.0, -10.0};
  s.model.rounding = 0.01;
  s.settings.stop.cycles = 10;
  BlockMaterial& rock = s.blockMaterials.emplace_back().material;
  rock.name = "rock";
  rock.density = 2500.0;
  JointMaterial& joint = s.jointMaterials.emplace_back().material;
  joint.name = "joint";
  joint.kn = joint.ks = 1e8;
  joint.tanFriction = std::tan(radians(30.0));
  auto block = [&](const std::string& name, Polygon vertices) -> BlockDefinition& {
    BlockDefinition& b = s.blocks.emplace_back();
    b.name = name;
    b.material = "rock";
    b.vertices = std::move(vertices);
    b.origin.prefix = "block '" + name + "'";
    return b;
  };
  block("base", {{-1.5, -1.0}, {1.5, -1.0}, {1.5, 0.0}, {-1.5, 0.0}}).fix = DriveAll;
  block("top", {{-0.5, 0.0}, {0.5, 0.0}, {0.5, 1.0}, {-0.5, 1.0}});
  return s;
}

}  // namespace vdec::testing
