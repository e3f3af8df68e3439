// libFuzzer target of the scene reader: each input is written to a scene file and read by
// readScene (the section parsers, then the builder). A defect by scene_reader_check.hpp's
// rule aborts, so libFuzzer keeps the input; so do sanitizer findings and signals.
// Built by -DVDEC_FUZZ=ON with clang; run by scripts/fuzz.sh (docs/verification.md).
#include <unistd.h>

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "scene_reader_check.hpp"

namespace {

// Beside the data files the repository's scenes name (scripts/fuzz.sh mirrors them into
// VDEC_FUZZ_SCENE_DIR's parent), so that mutants of those scenes reach their boundary tables.
std::string scenePath() {
  const char* dir = std::getenv("VDEC_FUZZ_SCENE_DIR");
  const std::filesystem::path base = dir ? std::filesystem::path(dir) : std::filesystem::temp_directory_path();
  return (base / ("fuzz-" + std::to_string(getpid()) + ".toml")).string();
}

bool numberChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-' || c == '_'; }

// [begin, end) of each number of a TOML text: a digit that no name or number precedes, with
// its sign, up to the first character no number holds.
std::vector<std::pair<std::size_t, std::size_t>> numbers(const std::string& text) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (!std::isdigit(static_cast<unsigned char>(text[i]))) continue;
    std::size_t begin = i;
    if (begin > 0 && (text[begin - 1] == '-' || text[begin - 1] == '+')) --begin;
    if (begin > 0 && numberChar(text[begin - 1])) continue;
    std::size_t end = i;
    while (end < text.size() && numberChar(text[end])) ++end;
    out.emplace_back(begin, end);
    i = end;
  }
  return out;
}

}  // namespace

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t maxSize);

// One mutation in four replaces a number of the scene by a hostile value (a non-finite or
// extreme number, an integer beyond 32 bits, another type): byte mutations rarely turn "0.5"
// into "nan", and no coverage rewards them for it, yet that is the input readers get wrong.
extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t maxSize,
                                               unsigned int seed) {
  static const char* const hostile[] = {"nan", "-nan", "inf", "-inf", "1e308", "-1e308", "1e-320", "4294967296",
                                        "-4294967296", "2147483648", "9223372036854775807", "-1", "0", "0.0",
                                        "\"x\"", "[]", "true", "{}"};
  std::minstd_rand random(seed);
  if (random() % 4 != 0) return LLVMFuzzerMutate(data, size, maxSize);
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto found = numbers(text);
  if (found.empty()) return LLVMFuzzerMutate(data, size, maxSize);
  const auto [begin, end] = found[random() % found.size()];
  const std::string mutated = text.substr(0, begin) + hostile[random() % std::size(hostile)] + text.substr(end);
  if (mutated.size() > maxSize) return LLVMFuzzerMutate(data, size, maxSize);
  std::memcpy(data, mutated.data(), mutated.size());
  return mutated.size();
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = scenePath();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) {
      std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
      std::abort();
    }
  }
  const std::string defect = vdec::fuzz::readerDefect(path);
  if (!defect.empty()) {
    std::fprintf(stderr, "fuzz: scene reader defect: %s\n", defect.c_str());
    std::abort();
  }
  return 0;
}
