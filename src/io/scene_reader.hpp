#pragma once
// Reads a scene file (TOML) into a Model and its run settings. Every error names the file, the
// line and the key. docs/user-manual/scene-format.md documents every key.
#include <string>
#include <vector>

#include "core/cycle.hpp"
#include "core/history.hpp"
#include "core/model.hpp"

namespace vdec {

struct Scene {
  std::string title;
  std::string path;
  std::string sha256;                  // of the file's bytes
  std::vector<std::string> overrides;  // --set key=value, applied after reading the file
  Model model;
  RunSettings settings;
  std::vector<HistorySpec> histories;
  std::vector<std::string> warnings;   // printed by the command line, kept in results.json
};

// Throws SceneError (bad file, syntax, key, type or value) or GeometryError (bad polygon).
Scene readScene(const std::string& path, const std::vector<std::string>& overrides = {});

}  // namespace vdec
