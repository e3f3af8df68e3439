#pragma once
// Builds scenes from TOML text for unit tests (through the real reader, so tests exercise the
// same path as users).
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/scene_reader.hpp"

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

}  // namespace vdec::testing
