#pragma once
// Reads a scene file (TOML) into its definitions (scene/scene_definition.hpp), one file per
// section (io/scene_sections.hpp), and builds the model from them (scene/scene_builder.hpp).
// Every error names the file, the line and the key. docs/user-manual/scene-format.md documents
// every key.
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "scene/scene_builder.hpp"
#include "scene/scene_definition.hpp"

namespace vdec {

// The definitions of a parsed scene (overrides already applied); `path` names it in errors and
// places the CSV tables it refers to.
SceneDefinition parseScene(const toml::table& root, const std::string& path);

// Throws SceneError (bad file, syntax, key, type or value) or GeometryError (bad polygon).
Scene readScene(const std::string& path, const std::vector<std::string>& overrides = {});

}  // namespace vdec
