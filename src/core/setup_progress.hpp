#pragma once
// A progress line on stderr for set-up work that can take long (cutting a region into many
// blocks, zoning a large block), so that a long set-up is not silent. Shown only when stderr is
// a terminal, as the cycle's progress line is, and redrawn at most four times a second.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace vdec {

class SetupProgress {
 public:
  SetupProgress() : enabled_(isatty(STDERR_FILENO) != 0) {}
  SetupProgress(const SetupProgress&) = delete;
  SetupProgress& operator=(const SetupProgress&) = delete;
  ~SetupProgress() {
    if (shown_) std::fputs("\n", stderr);
  }
  // Draws `text` now when `now` is set (the start of a long task), else when 250 ms have passed.
  void show(const std::string& text, bool now = false) {
    if (!enabled_) return;
    const auto t = std::chrono::steady_clock::now();
    if (!now && t - last_ < std::chrono::milliseconds(250)) return;
    last_ = t;
    std::fprintf(stderr, "\r%s\033[K", text.c_str());
    std::fflush(stderr);
    shown_ = true;
  }

 private:
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace vdec
