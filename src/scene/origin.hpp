#pragma once
// Where a scene definition came from: the table and the line of each of its keys, so that an
// error found while the model is built still names the file, the line and the key. A definition
// made in code has no file; its errors name the table only.
#include <map>
#include <string>
#include <string_view>

#include "core/errors.hpp"

namespace vdec {

struct Origin {
  std::string file;    // the scene file; "" for a definition made in code
  int line = 0;        // of the table; 0 when a --set override made it, or in code
  std::string table;   // "file:line" of the table (or the --set override that made it); "" in code
  std::string prefix;  // the table's name, e.g. block[3]
  std::map<std::string, std::string, std::less<>> keys;  // key -> "file:line" of its value

  std::string qualified(std::string_view key) const {
    return prefix.empty() ? std::string(key) : prefix + "." + std::string(key);
  }
  // "file:line: [prefix]", for messages raised elsewhere (geometry checks).
  std::string location() const { return (table.empty() ? "" : table + ": ") + "[" + prefix + "]"; }
  [[noreturn]] void fail(std::string_view key, const std::string& message) const {
    const auto it = keys.find(key);
    const std::string& at = it != keys.end() ? it->second : table;
    throw SceneError((at.empty() ? "" : at + ": ") + "key '" + qualified(key) + "': " + message);
  }
  [[noreturn]] void failTable(const std::string& message) const { throw SceneError(location() + ": " + message); }
};

}  // namespace vdec
