#pragma once
// `vdec check SCENE`: reads and builds a scene and prints what a run would do with it, without
// running it (docs/user-manual/command-line.md#check).
#include <string>
#include <vector>

namespace vdec {

// Prints the scene's blocks, zones, materials, contacts at the start, time step and its limits,
// the stages of a step and the run's stops and phases to stdout; returns 0. A scene error
// throws as in a run.
int checkScene(const std::string& path, const std::vector<std::string>& overrides);

}  // namespace vdec
