#include "cli/python_tools.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "core/errors.hpp"

// Set by CMake: the interpreter that has Debian's python3-matplotlib and python3-numpy, and the
// folders holding the tools' packages.
#ifndef VDEC_PYTHON
#define VDEC_PYTHON "/usr/bin/python3"
#endif
#ifndef VDEC_PYTHON_PATH
#define VDEC_PYTHON_PATH ""
#endif

namespace vdec {

int runPythonTool(const std::string& tool, const std::vector<std::string>& args) {
  std::string path = VDEC_PYTHON_PATH;
  if (const char* existing = std::getenv("PYTHONPATH"); existing != nullptr && *existing != '\0')
    path += std::string(":") + existing;
  setenv("PYTHONPATH", path.c_str(), 1);
  if (std::getenv("VDEC_EXECUTABLE") == nullptr) {
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) setenv("VDEC_EXECUTABLE", self.c_str(), 1);
  }
  std::vector<std::string> words{VDEC_PYTHON, "-m", "vdec_" + tool};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  std::fflush(nullptr);
  execv(VDEC_PYTHON, argv.data());
  std::fprintf(stderr, "vdec: error: cannot start %s for `vdec %s`: %s (install python3 with bash scripts/setup.sh)\n",
               VDEC_PYTHON, tool.c_str(), std::strerror(errno));
  return static_cast<int>(ExitCode::Usage);
}

}  // namespace vdec
