#include "boundary/time_function.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vdec {

void TimeFunction::integrate() {
  integrated = true;
  antiderivative.assign(t.size(), 0.0);
  for (std::size_t k = 1; k < t.size(); ++k)
    antiderivative[k] = antiderivative[k - 1] + 0.5 * (f[k - 1] + f[k]) * (t[k] - t[k - 1]);
  atZero = tableAntiderivative(0.0);
}

double TimeFunction::tableAntiderivative(double time) const {
  // The record held at its end values outside its rows, as the table itself is.
  if (time <= t.front()) return f.front() * (time - t.front());
  if (time >= t.back()) return antiderivative.back() + f.back() * (time - t.back());
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), time) - t.begin());
  const double s = time - t[k - 1], span = t[k] - t[k - 1];
  return antiderivative[k - 1] + f[k - 1] * s + 0.5 * (f[k] - f[k - 1]) * s * s / span;
}

double TimeFunction::operator()(double time) const {
  switch (kind) {
    case Kind::Constant: return 1.0;
    case Kind::Linear: return start + rate * time;
    case Kind::Sine: return std::sin(2.0 * std::numbers::pi * frequency * time + phase);
    case Kind::Cosine: return std::cos(2.0 * std::numbers::pi * frequency * time + phase);
    case Kind::Table: {
      if (integrated) return tableAntiderivative(time) - atZero;
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
