// Replays scene files through the fuzz target's oracle (scene_reader_check.hpp) in an ordinary
// build: tests/python/test_fuzz_regressions.py runs it on every input the fuzzer kept.
// Exit 0 when every file reads as documented, 1 (naming the files) when one does not.
#include <cstdio>

#include "scene_reader_check.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE...\n", argv[0]);
    return 2;
  }
  int defects = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string defect = vdec::fuzz::readerDefect(argv[i]);
    if (defect.empty()) continue;
    std::fprintf(stderr, "%s: %s\n", argv[i], defect.c_str());
    ++defects;
  }
  return defects ? 1 : 0;
}
