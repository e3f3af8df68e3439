#pragma once
// Reads a scene file (TOML) into a Model and its run settings. Every error names the file, the
// line and the key. docs/user-manual/scene-format.md documents every key.
#include <cstddef>
#include <string>
#include <vector>

#include "run/cycle.hpp"
#include "run/history.hpp"
#include "core/model.hpp"

namespace vdec {

struct Scene {
  std::string title;
  std::string path;
  std::string sha256;                  // of the file's bytes
  std::vector<std::string> overrides;  // --set key=value, applied after reading the file
  // [k]: SHA-256 of the scene as parsed with only its first k [[phase]] tables (a restart's check)
  std::vector<std::string> phasePrefixSha256;
  Model model;
  RunSettings settings;
  std::vector<HistorySpec> histories;
  std::vector<std::string> warnings;   // printed by the command line, kept in results.json
};

// Limits checked before the work they bound (docs/user-manual/scene-format.md#limits): the
// blocks of a scene, with those cut from a region counted by estimateRegion before any cut
// (measured: 100,000 blocks took 15 s and 3.5 GB from reading the scene to results.json), and
// the joint segments a region is cut with.
inline constexpr std::size_t kSceneBlockLimit = 200000;
inline constexpr double kRegionSegmentLimit = 1e7;

// Throws SceneError (bad file, syntax, key, type or value) or GeometryError (bad polygon).
Scene readScene(const std::string& path, const std::vector<std::string>& overrides = {});

}  // namespace vdec
