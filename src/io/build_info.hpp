#pragma once
// Provenance of this executable, generated at build time (cmake/build_info.cmake).
namespace vdec::build {
extern const char* const version;
extern const char* const gitCommit;   // "<sha>" or "<sha>-dirty"; "unknown" outside git
extern const char* const buildType;
extern const char* const compiler;
}  // namespace vdec::build
