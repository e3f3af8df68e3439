#pragma once
// Numbers in messages, as the user would write them.
#include <cmath>
#include <sstream>
#include <string>

namespace vdec {

// 1e-09, not 0.000000.
inline std::string shown(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A count, or an estimate of one, as a whole number (in exponent form beyond 1e15).
inline std::string shownCount(double v) {
  return std::abs(v) < 1e15 ? std::to_string(static_cast<long long>(std::ceil(v))) : shown(v);
}

}  // namespace vdec
