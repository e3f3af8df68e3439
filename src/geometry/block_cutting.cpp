#include "geometry/block_cutting.hpp"

#include <cmath>
#include <numbers>
#include <random>

namespace vdec {

namespace {

class UniformStream {
 public:
  explicit UniformStream(std::uint64_t seed) : engine_(seed) {}
  // Uniform on [-1, 1]: the top 53 bits of one draw, as a double in [0, 1).
  double symmetric() {
    const double unit = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    return 2.0 * unit - 1.0;
  }

 private:
  std::mt19937_64 engine_;
};

double degrees(double deg) { return deg * std::numbers::pi / 180.0; }

void cutWithJointSet(std::vector<Polygon>& blocks, const Polygon& boundary, const JointSetSpec& set,
                     UniformStream& random) {
  const Vec2 meanDir{std::cos(degrees(set.angleDeg)), std::sin(degrees(set.angleDeg))};
  const Vec2 across = perp(meanDir);
  double lo = INFINITY, hi = -INFINITY;
  for (const Vec2& v : boundary) {
    lo = std::min(lo, dot(v - set.origin, across));
    hi = std::max(hi, dot(v - set.origin, across));
  }
  // First joint position at or below the region, on the lattice through the origin.
  double offset = std::floor(lo / set.spacing) * set.spacing;
  while (offset <= hi) {
    const double angle = degrees(set.angleDeg + set.angleVariationDeg * random.symmetric());
    const Vec2 dir{std::cos(angle), std::sin(angle)};
    const Vec2 anchor = set.origin + offset * across;
    if (auto chord = chordParameters(boundary, anchor, dir)) {
      const auto [t0, t1] = *chord;
      if (set.trace <= 0.0) {
        cutBlocksWithSegment(blocks, anchor + (t0 - 1.0) * dir, anchor + (t1 + 1.0) * dir);
      } else {
        // Start somewhere in the first trace+gap period before the chord so that segments are
        // not all aligned with the region's edge.
        const double period = set.trace + set.gap;
        double t = t0 - period * 0.5 * (1.0 + random.symmetric());
        while (t < t1) {
          const double trace = std::max(0.0, set.trace + set.traceVariation * random.symmetric());
          const double gap = std::max(0.0, set.gap + set.gapVariation * random.symmetric());
          if (trace > 0.0) cutBlocksWithSegment(blocks, anchor + t * dir, anchor + (t + trace) * dir);
          t += std::max(trace + gap, 1e-9 * set.trace);
        }
      }
    }
    // The scene reader guarantees spacing > variation, so every step moves forward.
    offset += set.spacing + set.spacingVariation * random.symmetric();
  }
}

}  // namespace

void cutBlocksWithSegment(std::vector<Polygon>& blocks, Vec2 a, Vec2 b) {
  const double length = norm(b - a);
  if (length <= 0.0) return;
  const Vec2 dir = (1.0 / length) * (b - a);
  std::vector<Polygon> result;
  result.reserve(blocks.size() + 1);
  for (Polygon& block : blocks) {
    const auto chord = chordParameters(block, a, dir);
    const bool crossesCompletely = chord && chord->first >= -1e-12 * length &&
                                   chord->second <= length * (1.0 + 1e-12);
    auto parts = crossesCompletely ? splitConvex(block, a, dir) : std::nullopt;
    if (parts) {
      result.push_back(std::move(parts->first));
      result.push_back(std::move(parts->second));
    } else {
      result.push_back(std::move(block));
    }
  }
  blocks = std::move(result);
}

std::vector<Polygon> cutRegion(const RegionSpec& region) {
  std::vector<Polygon> blocks{region.boundary};
  for (const CrackSpec& crack : region.cracks) cutBlocksWithSegment(blocks, crack.from, crack.to);
  UniformStream random(region.seed);
  for (const JointSetSpec& set : region.jointSets) cutWithJointSet(blocks, region.boundary, set, random);
  return blocks;
}

}  // namespace vdec
