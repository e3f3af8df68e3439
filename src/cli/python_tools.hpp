#pragma once
// `vdec plot` and `vdec sweep` are Python programs (matplotlib draws the pictures; a sweep is a
// pool of `vdec run` processes or a Slurm job array), reached through the one front end so that
// a user types `vdec` for everything (docs/user-manual/command-line.md).
#include <string>
#include <vector>

namespace vdec {

// Replaces this process by `python3 -m vdec_TOOL ARGS...` with the source tree's python/ and
// verification/harness on PYTHONPATH and VDEC_EXECUTABLE naming this executable (unless set).
// Returns only on failure to start the interpreter, with the exit code to give.
int runPythonTool(const std::string& tool, const std::vector<std::string>& args);

}  // namespace vdec
