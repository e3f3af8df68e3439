#pragma once
// The state file of a phased run (vdec run --save, --restart): everything needed to continue the
// run after a phase, bitwise as if it had not stopped. docs/user-manual/command-line.md#save-and-restart
// describes the format and why it is our own.
#include <string>

#include "io/scene_reader.hpp"
#include "run/cycle.hpp"

namespace vdec {

// The file format's version: raised whenever the layout of what is saved changes.
inline constexpr unsigned kStateFormatVersion = 3;

// Writes the state after `phasesDone` phases of `scene` to `path` atomically. Throws OutputError.
void writeState(const std::string& path, const Scene& scene, Model& model, Cycle& cycle, int phasesDone);

// Loads a state written by writeState into a model and cycle built from `scene`, and returns the
// number of phases done. Throws RestartError naming the file and what is wrong: not readable,
// not a vdec state file, another format version or layout, damaged (checksum), truncated, or
// saved from a scene whose settings or phases up to the save differ from `scene`'s.
int readState(const std::string& path, const Scene& scene, Model& model, Cycle& cycle);

}  // namespace vdec
