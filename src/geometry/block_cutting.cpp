#include "geometry/block_cutting.hpp"

#include <algorithm>
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

// The two parts of `block` when the segment from a along dir (unit), of the given length,
// crosses it completely; nothing otherwise (a segment that ends inside a block leaves it whole).
std::optional<std::pair<Polygon, Polygon>> splitIfCrossed(const Polygon& block, Vec2 a, Vec2 dir, double length) {
  const auto chord = chordParameters(block, a, dir);
  const bool crossesCompletely = chord && chord->first >= -1e-12 * length && chord->second <= length * (1.0 + 1e-12);
  return crossesCompletely ? splitConvex(block, a, dir) : std::nullopt;
}

// The blocks of a region while it is cut. They stay in cutting order in a linked list (a split
// block's two parts take its place, first part first), so the pieces come out in the order and
// with the names that cutting the whole list with every segment gives. A uniform grid of cells
// over the region lists, for each cell, blocks whose outline may reach it, so that a segment
// tests only the blocks listed in the cells it crosses (the exact test, splitIfCrossed, then
// decides). When a block splits, the smaller part is listed in its own cells and the larger
// keeps the listing of the block it was, a superset of its cells: listing never has to be
// undone, and a region cut line by line from one side does not relist its shrinking remainder
// for every line. Cutting then grows with the number of blocks instead of with its square.
class GridCutter {
 public:
  GridCutter(const Polygon& region, std::size_t expectedBlocks) {
    lo_ = hi_ = region.front();
    for (const Vec2& v : region) {
      lo_ = {std::min(lo_.x, v.x), std::min(lo_.y, v.y)};
      hi_ = {std::max(hi_.x, v.x), std::max(hi_.y, v.y)};
    }
    const double width = hi_.x - lo_.x, height = hi_.y - lo_.y;
    // About one cell per expected block, at most 2^22 cells.
    const double cells = std::clamp(static_cast<double>(expectedBlocks), 1.0, 4194304.0);
    cell_ = std::sqrt(width * height / cells);
    columns_ = std::clamp(static_cast<int>(std::ceil(width / cell_)), 1, 4194304);
    rows_ = std::clamp(static_cast<int>(std::ceil(height / cell_)), 1, 4194304 / columns_);
    cell_ = std::max(width / columns_, height / rows_);
    margin_ = 1e-9 * (width + height);
    cells_.resize(static_cast<std::size_t>(columns_) * rows_);
    head_ = add(region);
  }

  void cut(Vec2 a, Vec2 b) {
    const double length = norm(b - a);
    if (length <= 0.0) return;
    const Vec2 dir = (1.0 / length) * (b - a);
    ++stamp_;
    candidates_.clear();
    const Vec2 segment[2] = {a, b};
    forEachCell(segment, 2, margin_ + 1e-9 * length, [this](std::size_t c) {
      for (int block : cells_[c])
        if (seen_[block] != stamp_) {
          seen_[block] = stamp_;
          candidates_.push_back(block);
        }
    });
    for (int block : candidates_) {
      auto parts = splitIfCrossed(polygons_[block], a, dir, length);
      if (!parts) continue;
      const bool firstSmaller = signedArea(parts->first) < signedArea(parts->second);
      polygons_[block] = std::move(firstSmaller ? parts->second : parts->first);
      const int part = add(std::move(firstSmaller ? parts->first : parts->second));
      // The new part goes before the block when it is the first part, after it otherwise.
      const int before = firstSmaller ? previous_[block] : block;
      const int after = firstSmaller ? block : next_[block];
      previous_[part] = before;
      next_[part] = after;
      if (before >= 0) next_[before] = part;
      else head_ = part;
      if (after >= 0) previous_[after] = part;
    }
  }

  std::size_t size() const { return polygons_.size(); }

  std::vector<Polygon> take() {
    std::vector<Polygon> out;
    out.reserve(polygons_.size());
    for (int b = head_; b >= 0; b = next_[b]) out.push_back(std::move(polygons_[b]));
    return out;
  }

 private:
  int add(Polygon p) {
    const int block = static_cast<int>(polygons_.size());
    polygons_.push_back(std::move(p));
    next_.push_back(-1);
    previous_.push_back(-1);
    seen_.push_back(stamp_);  // a part made by this segment is not cut by it again
    const Polygon& listed = polygons_.back();
    forEachCell(listed.data(), listed.size(), margin_, [this, block](std::size_t c) { cells_[c].push_back(block); });
    return block;
  }
  int column(double x) const {
    return std::clamp(static_cast<int>(std::floor((x - lo_.x) / cell_)), 0, columns_ - 1);
  }
  int row(double y) const { return std::clamp(static_cast<int>(std::floor((y - lo_.y) / cell_)), 0, rows_ - 1); }

  // The cells that the outline through `points` (closed when more than two), widened by
  // `margin`, reaches: in each column, the rows between its lowest and highest point there. For
  // a convex polygon that covers its inside as well, since every vertical line meets its inside
  // between two points of its outline.
  template <class Visit>
  void forEachCell(const Vec2* points, std::size_t count, double margin, Visit visit) {
    double xMin = INFINITY, xMax = -INFINITY;
    for (std::size_t i = 0; i < count; ++i) {
      xMin = std::min(xMin, points[i].x);
      xMax = std::max(xMax, points[i].x);
    }
    const int first = column(xMin - margin), last = column(xMax + margin);
    low_.assign(static_cast<std::size_t>(last - first + 1), INFINITY);
    high_.assign(low_.size(), -INFINITY);
    const std::size_t edges = count > 2 ? count : 1;
    for (std::size_t e = 0; e < edges; ++e) {
      Vec2 p = points[e], q = points[(e + 1) % count];
      if (q.x < p.x) std::swap(p, q);
      const int c0 = column(p.x - margin), c1 = column(q.x + margin);
      for (int c = c0; c <= c1; ++c) {
        // The edge's y over the part of its x-range within this column (widened).
        const double x0 = std::max(p.x, lo_.x + c * cell_ - margin);
        const double x1 = std::min(q.x, lo_.x + (c + 1) * cell_ + margin);
        double y0 = p.y, y1 = q.y;
        if (q.x > p.x) {
          const double slope = (q.y - p.y) / (q.x - p.x);
          y0 = p.y + slope * (std::clamp(x0, p.x, q.x) - p.x);
          y1 = p.y + slope * (std::clamp(x1, p.x, q.x) - p.x);
        }
        const std::size_t k = static_cast<std::size_t>(c - first);
        low_[k] = std::min(low_[k], std::min(y0, y1));
        high_[k] = std::max(high_[k], std::max(y0, y1));
      }
    }
    for (int c = first; c <= last; ++c) {
      const std::size_t k = static_cast<std::size_t>(c - first);
      if (low_[k] > high_[k]) continue;
      const int r0 = row(low_[k] - margin), r1 = row(high_[k] + margin);
      for (int r = r0; r <= r1; ++r) visit(static_cast<std::size_t>(r) * columns_ + c);
    }
  }

  Vec2 lo_, hi_;
  double cell_ = 1.0, margin_ = 0.0;
  int columns_ = 1, rows_ = 1;
  std::vector<std::vector<int>> cells_;
  std::vector<Polygon> polygons_;
  std::vector<int> next_, previous_;
  int head_ = 0;
  std::vector<unsigned> seen_;
  unsigned stamp_ = 0;
  std::vector<int> candidates_;
  std::vector<double> low_, high_;
};

// The plain cutter: every segment tries every block (cutBlocksWithSegment).
class ListCutter {
 public:
  explicit ListCutter(const Polygon& region) : blocks_{region} {}
  void cut(Vec2 a, Vec2 b) { cutBlocksWithSegment(blocks_, a, b); }
  std::size_t size() const { return blocks_.size(); }
  std::vector<Polygon> take() { return std::move(blocks_); }

 private:
  std::vector<Polygon> blocks_;
};

template <class Cutter>
void cutWithJointSet(Cutter& blocks, const Polygon& boundary, const JointSetSpec& set, UniformStream& random,
                     const std::function<void(std::size_t)>& progress) {
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
        blocks.cut(anchor + (t0 - 1.0) * dir, anchor + (t1 + 1.0) * dir);
      } else {
        // Start somewhere in the first trace+gap period before the chord so that segments are
        // not all aligned with the region's edge.
        const double period = set.trace + set.gap;
        double t = t0 - period * 0.5 * (1.0 + random.symmetric());
        while (t < t1) {
          const double trace = std::max(0.0, set.trace + set.traceVariation * random.symmetric());
          const double gap = std::max(0.0, set.gap + set.gapVariation * random.symmetric());
          if (trace > 0.0) blocks.cut(anchor + t * dir, anchor + (t + trace) * dir);
          t += std::max(trace + gap, 1e-9 * set.trace);
        }
      }
    }
    if (progress) progress(blocks.size());
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
    if (auto parts = splitIfCrossed(block, a, dir, length)) {
      result.push_back(std::move(parts->first));
      result.push_back(std::move(parts->second));
    } else {
      result.push_back(std::move(block));
    }
  }
  blocks = std::move(result);
}

RegionEstimate estimateRegion(const RegionSpec& region) {
  RegionEstimate e;
  double lines = 0.0, crossings = 0.0;
  for (const JointSetSpec& set : region.jointSets) {
    const Vec2 across = perp(Vec2{std::cos(degrees(set.angleDeg)), std::sin(degrees(set.angleDeg))});
    double lo = INFINITY, hi = -INFINITY;
    for (const Vec2& v : region.boundary) {
      lo = std::min(lo, dot(v, across));
      hi = std::max(hi, dot(v, across));
    }
    const double count = (hi - lo) / (set.spacing - set.spacingVariation) + 1.0;
    // The longest chord bounds the segments of one line: the region's diameter over the shortest
    // period (a segment advances at least 1e-9 trace).
    double diameter = 0.0;
    for (const Vec2& a : region.boundary)
      for (const Vec2& b : region.boundary) diameter = std::max(diameter, norm(b - a));
    const double period = std::max(set.trace - set.traceVariation + set.gap - set.gapVariation, 1e-9 * set.trace);
    const double perLine = set.trace > 0.0 ? diameter / period + 2.0 : 1.0;
    e.segments += count * perLine;
    // Lines of different sets cross inside the region; each crossing adds at most one block.
    crossings += count * lines;
    lines += count;
  }
  e.segments += static_cast<double>(region.cracks.size());
  e.blocks = 1.0 + static_cast<double>(region.cracks.size()) + lines + crossings;
  return e;
}

namespace {

template <class Cutter>
std::vector<Polygon> cutWith(Cutter blocks, const RegionSpec& region, const std::function<void(std::size_t)>& progress) {
  for (const CrackSpec& crack : region.cracks) blocks.cut(crack.from, crack.to);
  UniformStream random(region.seed);
  for (const JointSetSpec& set : region.jointSets) cutWithJointSet(blocks, region.boundary, set, random, progress);
  return blocks.take();
}

}  // namespace

std::vector<Polygon> cutRegion(const RegionSpec& region, const std::function<void(std::size_t blocks)>& progress) {
  const double expected = std::min(estimateRegion(region).blocks, 4194304.0);
  return cutWith(GridCutter(region.boundary, static_cast<std::size_t>(expected)), region, progress);
}

std::vector<Polygon> cutRegionBlockByBlock(const RegionSpec& region) {
  return cutWith(ListCutter(region.boundary), region, {});
}

}  // namespace vdec
