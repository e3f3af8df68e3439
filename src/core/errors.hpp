#pragma once
// Errors the user can act on. Each class carries its own process exit code so that scripts
// and the verification harness can tell bad input from numerical trouble.
#include <stdexcept>
#include <string>

namespace vdec {

enum class ExitCode : int {
  Ok = 0,
  Internal = 1,
  Usage = 2,
  SceneInput = 3,         // syntax, unknown key, wrong type, missing key, out-of-range value
  Geometry = 4,           // invalid polygon, overlapping blocks, edge shorter than the rounding
  Instability = 5,        // NaN or mechanical energy growing beyond the energy supplied
  ContactOverlap = 6,     // overlap beyond half the rounding length
  Output = 7,             // results could not be written
  Interrupted = 8,        // SIGINT or SIGTERM: stopped between two steps, results so far written
  NotInEquilibrium = 9,   // a phase with require_equilibrium ended on its cycle or time limit
  Restart = 10,           // a state file that cannot be continued: unreadable, damaged, foreign, other scene
};

class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ExitCode code() const { return code_; }

 private:
  ExitCode code_;
};

struct SceneError : Error {
  explicit SceneError(const std::string& m) : Error(ExitCode::SceneInput, m) {}
};
struct GeometryError : Error {
  explicit GeometryError(const std::string& m) : Error(ExitCode::Geometry, m) {}
};
struct InstabilityError : Error {
  explicit InstabilityError(const std::string& m) : Error(ExitCode::Instability, m) {}
};
struct OverlapError : Error {
  explicit OverlapError(const std::string& m) : Error(ExitCode::ContactOverlap, m) {}
};
struct EquilibriumError : Error {
  explicit EquilibriumError(const std::string& m) : Error(ExitCode::NotInEquilibrium, m) {}
};
struct RestartError : Error {
  explicit RestartError(const std::string& m) : Error(ExitCode::Restart, m) {}
};
struct OutputError : Error {
  explicit OutputError(const std::string& m) : Error(ExitCode::Output, m) {}
};

}  // namespace vdec
