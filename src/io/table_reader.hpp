#pragma once
// Reading one TOML table of a scene: typed getters that remember which keys were used, so that
// unknown keys are errors, and errors that name the file and line (or the --set override) and
// the key.
#include <toml++/toml.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "core/shown.hpp"
#include "core/vec2.hpp"
#include "geometry/polygon.hpp"
#include "scene/origin.hpp"

namespace vdec {


// Reads one TOML table, remembering which keys were used so that unknown ones are errors.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string prefix, const std::string& file)
      : table_(table), prefix_(std::move(prefix)), file_(file) {}

  [[noreturn]] void fail(std::string_view key, const std::string& message) const {
    const toml::node* node = table_.get(key);
    throw SceneError(where(node ? node->source() : table_.source()) + ": key '" + qualified(key) + "': " + message);
  }
  // file:line of the table, and its name, for messages raised elsewhere (geometry checks).
  std::string location() const { return where(table_.source()) + ": [" + prefix_ + "]"; }
  // An error about the table as a whole, e.g. a choice among keys none of which is there.
  [[noreturn]] void failTable(const std::string& message) const {
    throw SceneError(where(table_.source()) + ": [" + prefix_ + "]: " + message);
  }
  // file:line, or the --set override a value came from (its source path is the override text).
  std::string where(const toml::source_region& source) const {
    if (source.path && *source.path != file_) return file_ + ": " + *source.path;
    if (source.begin.line == 0) return file_ + ": a table made by --set";
    return file_ + ":" + std::to_string(source.begin.line);
  }
  std::string qualified(std::string_view key) const {
    return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
  }
  bool has(std::string_view key) {
    used_.insert(std::string(key));
    return table_.get(key) != nullptr;
  }
  const toml::node* node(std::string_view key) {
    used_.insert(std::string(key));
    return table_.get(key);
  }

  double number(std::string_view key) {
    const toml::node* n = node(key);
    if (!n) fail(key, "is required");
    if (!n->is_number()) fail(key, "must be a number");
    return finiteNumber(*n, key, "");
  }
  double number(std::string_view key, double fallback) { return has(key) ? number(key) : fallback; }
  double positive(std::string_view key) {
    const double v = number(key);
    if (!(v > 0)) fail(key, "must be > 0, got " + shown(v));
    return v;
  }
  double nonNegative(std::string_view key, double fallback) {
    const double v = number(key, fallback);
    if (v < 0) fail(key, "must be >= 0, got " + shown(v));
    return v;
  }
  double angleDegrees(std::string_view key, double fallback) {
    const double v = number(key, fallback);
    if (v < 0 || v >= 90) fail(key, "must be in [0, 90) degrees, got " + shown(v));
    return v;
  }
  long long integer(std::string_view key) {
    const toml::node* n = node(key);
    if (!n) fail(key, "is required");
    if (!n->is_integer()) fail(key, "must be an integer");
    return *n->value<long long>();
  }
  // An integer checked against its range before it is narrowed or used as a divisor: a value
  // past the range must be refused here, not wrapped (every = 4294967296 once became 0).
  long long integer(std::string_view key, long long lo, long long hi) {
    const long long v = integer(key);
    if (v < lo || v > hi)
      fail(key, "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
    return v;
  }
  std::string string(std::string_view key) {
    const toml::node* n = node(key);
    if (!n) fail(key, "is required");
    if (!n->is_string()) fail(key, "must be a string");
    return *n->value<std::string>();
  }
  std::string string(std::string_view key, const std::string& fallback) { return has(key) ? string(key) : fallback; }
  bool boolean(std::string_view key, bool fallback) {
    const toml::node* n = node(key);
    if (!n) return fallback;
    if (!n->is_boolean()) fail(key, "must be true or false");
    return *n->value<bool>();
  }
  Vec2 vec2(std::string_view key, Vec2 fallback) { return has(key) ? vec2(key) : fallback; }
  Vec2 vec2(std::string_view key) {
    const std::vector<double> v = numbers(key, 2, "must be an array of two numbers, e.g. [0.0, 1.0]");
    return {v[0], v[1]};
  }
  // An array of exactly `count` finite numbers; `shape` is the message for any other value.
  std::vector<double> numbers(std::string_view key, std::size_t count, const std::string& shape) {
    const toml::node* n = node(key);
    if (!n) fail(key, "is required");
    const toml::array* a = n->as_array();
    if (!a || a->size() != count) fail(key, shape);
    std::vector<double> out;
    for (std::size_t i = 0; i < count; ++i) {
      if (!(*a)[i].is_number()) fail(key, shape);
      out.push_back(finiteNumber((*a)[i], key, "value " + std::to_string(i)));
    }
    return out;
  }
  Polygon polygon(std::string_view key) {
    const toml::node* n = node(key);
    if (!n) fail(key, "is required");
    const toml::array* a = n->as_array();
    if (!a) fail(key, "must be an array of [x, y] points");
    Polygon p;
    for (const toml::node& point : *a) {
      const toml::array* xy = point.as_array();
      const std::string which = "point " + std::to_string(p.size());
      if (!xy || xy->size() != 2 || !(*xy)[0].is_number() || !(*xy)[1].is_number())
        fail(key, "must be an array of [x, y] points; " + which + " is not");
      p.push_back({finiteNumber((*xy)[0], key, which + " x"), finiteNumber((*xy)[1], key, which + " y")});
    }
    return p;
  }
  // An array of [a, b] pairs of finite numbers, flattened; `shape` is the message for any other value.
  std::vector<double> pairs(std::string_view key, const std::string& shape) {
    const toml::node* n = node(key);
    if (!n) fail(key, "is required");
    const toml::array* a = n->as_array();
    if (!a) fail(key, shape);
    std::vector<double> out;
    for (std::size_t i = 0; i < a->size(); ++i) {
      const toml::array* pair = (*a)[i].as_array();
      if (!pair || pair->size() != 2 || !(*pair)[0].is_number() || !(*pair)[1].is_number()) fail(key, shape);
      for (std::size_t k = 0; k < 2; ++k)
        out.push_back(finiteNumber((*pair)[k], key, "pair " + std::to_string(i) + " value " + std::to_string(k)));
    }
    return out;
  }
  std::vector<std::string> strings(std::string_view key) {
    const toml::node* n = node(key);
    if (!n) fail(key, "is required");
    const toml::array* a = n->as_array();
    if (!a) fail(key, "must be an array of strings");
    std::vector<std::string> out;
    for (const toml::node& s : *a) {
      if (!s.is_string()) fail(key, "must be an array of strings");
      out.push_back(*s.value<std::string>());
    }
    return out;
  }
  // Array of tables, e.g. [[block]]; absent means empty.
  std::vector<std::pair<const toml::table*, std::string>> tables(std::string_view key) {
    std::vector<std::pair<const toml::table*, std::string>> out;
    const toml::node* n = node(key);
    if (!n) return out;
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables()) fail(key, "must be an array of tables, written [[" + qualified(key) + "]]");
    for (std::size_t i = 0; i < a->size(); ++i)
      out.emplace_back((*a)[i].as_table(), qualified(key) + "[" + std::to_string(i) + "]");
    return out;
  }
  std::optional<TableReader> subtable(std::string_view key) {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (!n->is_table()) fail(key, "must be a table, written [" + qualified(key) + "]");
    return TableReader(*n->as_table(), qualified(key), file_);
  }
  // Unknown keys are errors: a misspelt key must never be silently ignored.
  void finish() const {
    for (auto&& [key, value] : table_)
      if (!used_.count(std::string(key.str()))) {
        throw SceneError(where(value.source()) + ": key '" + qualified(key.str()) + "': unknown key");
      }
  }
  // Where the table and each of its keys are, for errors found once the scene is read.
  Origin origin() const {
    Origin o;
    o.file = file_;
    o.line = static_cast<int>(table_.source().begin.line);
    o.table = where(table_.source());
    o.prefix = prefix_;
    for (auto&& [key, value] : table_) o.keys.emplace(std::string(key.str()), where(value.source()));
    return o;
  }
  const toml::table& table() const { return table_; }
  const std::string& file() const { return file_; }

 private:
  // Every number of a scene passes here: TOML's nan, inf and -inf are refused where they are
  // read, naming the line of the value itself and, inside an array, which of its values
  // (`element`, e.g. "point 2 x"). An integer is rounded to the nearest double (toml++ would
  // refuse one that a double does not hold exactly).
  double finiteNumber(const toml::node& n, std::string_view key, const std::string& element) const {
    const double v = n.is_integer() ? static_cast<double>(n.as_integer()->get()) : n.as_floating_point()->get();
    if (!std::isfinite(v))
      throw SceneError(where(n.source()) + ": key '" + qualified(key) + "': " + (element.empty() ? "" : element + " ") +
                       "must be finite, got " + shown(v));
    return v;
  }

  const toml::table& table_;
  std::string prefix_;
  std::string file_;
  std::set<std::string> used_;
};

}  // namespace vdec
