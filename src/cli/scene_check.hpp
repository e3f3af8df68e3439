#pragma once
// `vdec check SCENE`: reads and builds a scene and prints what a run would do with it, without
// running it (docs/user-manual/command-line.md#check).
#include <string>
#include <vector>

namespace vdec {

// Prints the scene's blocks, zones, materials, contacts at the start, time step and its limits,
// the stages of a step and the run's stops and phases to stdout; returns 0. A scene error
// throws as in a run. With a vtkDirectory, also writes the built model as the run's cycle-0 VTK
// snapshot there (snapshot_000000000.vtu and model.pvd), for a picture of the set-up.
int checkScene(const std::string& path, const std::vector<std::string>& overrides,
               const std::string& vtkDirectory = "");

}  // namespace vdec
