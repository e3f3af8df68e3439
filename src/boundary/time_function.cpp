#include "boundary/time_function.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vdec {

double TimeFunction::operator()(double time) const {
  switch (kind) {
    case Kind::Constant: return 1.0;
    case Kind::Linear: return start + rate * time;
    case Kind::Sine: return std::sin(2.0 * std::numbers::pi * frequency * time + phase);
    case Kind::Cosine: return std::cos(2.0 * std::numbers::pi * frequency * time + phase);
    case Kind::Table: {
      if (time <= t.front()) return f.front();
      if (time >= t.back()) return f.back();
      const auto it = std::upper_bound(t.begin(), t.end(), time);
      const std::size_t k = static_cast<std::size_t>(it - t.begin());
      const double w = (time - t[k - 1]) / (t[k] - t[k - 1]);
      return (1.0 - w) * f[k - 1] + w * f[k];
    }
  }
  return 1.0;
}

}  // namespace vdec
