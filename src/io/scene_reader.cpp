#include "io/scene_reader.hpp"

#include <toml++/toml.h>

#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "io/scene_sections.hpp"
#include "io/sha256.hpp"
#include "io/table_reader.hpp"

namespace vdec {

namespace {

void applyOverride(toml::table& root, const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError("--set '" + text + "': expected key.path=value, e.g. solver.frac=0.2");
  const std::string path = text.substr(0, eq);
  toml::table parsed;
  try {
    parsed = toml::parse("value = " + text.substr(eq + 1), "--set '" + text + "'");
  } catch (const toml::parse_error& e) {
    throw SceneError("--set '" + text + "': the value is not valid TOML: " + std::string(e.description()));
  }
  toml::table* table = &root;
  std::size_t start = 0;
  for (;;) {
    const auto dot = path.find('.', start);
    std::string part = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    // "name[i]" selects the i-th table of an array of tables, e.g. joint_material[0].cohesion.
    long index = -1;
    if (const auto open = part.find('['); open != std::string::npos && part.back() == ']') {
      const std::string digits = part.substr(open + 1, part.size() - open - 2);
      if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9)
        throw SceneError("--set '" + text + "': bad index in '" + part + "': a table number from 0");
      index = std::stol(digits);
      part = part.substr(0, open);
    }
    if (part.empty()) throw SceneError("--set '" + text + "': empty key in '" + path + "'");
    if (dot == std::string::npos) {
      if (index >= 0) throw SceneError("--set '" + text + "': the last key cannot be indexed");
      table->insert_or_assign(part, std::move(*parsed.get("value")));  // moved: keeps its source
      return;
    }
    toml::node* next = table->get(part);
    if (index >= 0) {
      toml::array* array = next ? next->as_array() : nullptr;
      if (!array || !array->is_array_of_tables() || index >= static_cast<long>(array->size()))
        throw SceneError("--set '" + text + "': '" + part + "' has no table [" + std::to_string(index) + "]");
      next = array->get(static_cast<std::size_t>(index));
    } else if (!next) {
      table->insert(part, toml::table{});
      next = table->get(part);
    }
    if (!next->is_table())
      throw SceneError("--set '" + text + "': '" + part + "' is not a table; name a table key such as "
                       "solver.frac, or one table of an array such as joint_material[0].cohesion");
    table = next->as_table();
    start = dot + 1;
  }
}

// SHA-256 of the scene as parsed (overrides applied) with its first k phases, k = 0 .. n: a
// restart may append phases, but what ran before the save must be what the scene says.
std::vector<std::string> phasePrefixHashes(const toml::table& root) {
  const toml::array* phases = root["phase"].as_array();
  const std::size_t n = phases ? phases->size() : 0;
  std::vector<std::string> hashes;
  for (std::size_t k = 0; k <= n; ++k) {
    toml::table copy = root;
    if (phases) {
      toml::array kept;
      for (std::size_t i = 0; i < k; ++i) kept.push_back(*phases->get(i));
      copy.insert_or_assign("phase", std::move(kept));
    }
    std::ostringstream text;
    text << toml::toml_formatter(copy);
    hashes.push_back(sha256Hex(text.str()));
  }
  return hashes;
}

}  // namespace

SceneDefinition parseScene(const toml::table& root, const std::string& path) {
  SceneDefinition scene;
  TableReader top(root, "", path);
  scene.root = top.origin();
  scene.title = top.string("title", "");
  readMaterials(top, scene);
  readRunSettings(top, scene);
  readBlocks(top, scene);
  readBoundaries(top, scene);
  readFluid(top, scene);
  readHeat(top, scene);
  readStructures(top, scene);
  readPhases(top, scene);
  readHistories(top, scene);
  top.finish();
  return scene;
}

Scene readScene(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw SceneError(path + ": cannot open the scene file");
  std::stringstream buffer;
  buffer << stream.rdbuf();
  const std::string bytes = buffer.str();
  toml::table root;
  try {
    root = toml::parse(bytes, path);
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << path << ":" << e.source().begin.line << ": " << e.description();
    throw SceneError(s.str());
  }
  for (const std::string& o : overrides) applyOverride(root, o);
  Scene scene = buildScene(parseScene(root, path));
  scene.path = path;
  scene.sha256 = sha256Hex(bytes);
  scene.overrides = overrides;
  scene.phasePrefixSha256 = phasePrefixHashes(root);
  return scene;
}

}  // namespace vdec
