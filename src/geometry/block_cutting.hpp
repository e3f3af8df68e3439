#pragma once
// Cutting a region into blocks with single cracks and statistically generated joint sets
// (NUREG/CR-5429 1.1.2: joint sets by angle, spacing, trace length and gap, each a mean with
// an optional random variation). A crack or joint segment only splits a block it crosses
// completely; a segment ending inside a block leaves it whole, as in UDEC.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "geometry/polygon.hpp"

namespace vdec {

struct CrackSpec {
  Vec2 from, to;
};

// Each quantity is mean + variation * u, u uniform on [-1, 1] from the region's seeded stream.
struct JointSetSpec {
  double angleDeg = 0.0, angleVariationDeg = 0.0;
  double spacing = 1.0, spacingVariation = 0.0;
  double trace = 0.0, traceVariation = 0.0;  // trace <= 0 means joints cross the whole region
  double gap = 0.0, gapVariation = 0.0;
  Vec2 origin;                               // one joint of the set passes through it
};

struct RegionSpec {
  std::string name;
  Polygon boundary;
  std::vector<CrackSpec> cracks;
  std::vector<JointSetSpec> jointSets;
  std::uint64_t seed = 1;
};

// Applies cracks first, then joint sets in order. The same spec and seed give the same blocks,
// in the same order, on every machine (the random stream is mt19937_64, whose output the C++
// standard fixes, mapped to [-1, 1] by our own formula, not by a library distribution); the
// order is that of cutting the whole list of blocks with each segment in turn, each split
// block replaced by its two parts. `progress`, when given, is called after each joint line with
// the number of blocks so far.
std::vector<Polygon> cutRegion(const RegionSpec& region, const std::function<void(std::size_t blocks)>& progress = {});

// The same pieces in the same order, by trying every block with every segment: quadratic in the
// number of blocks (81 s for 1e6 blocks where cutRegion takes 3 s); kept to test cutRegion against.
std::vector<Polygon> cutRegionBlockByBlock(const RegionSpec& region);

// What cutting a region will make, estimated from its outline and joint sets before any cut, so
// that a scene asking for millions of blocks is refused up front: `blocks` bounds the pieces of
// crossing joint lines (1 + cracks + lines + crossings of lines of different sets; finite traces
// make fewer), `segments` the crack and joint segments to cut with.
struct RegionEstimate {
  double blocks = 1.0;
  double segments = 0.0;
};
RegionEstimate estimateRegion(const RegionSpec& region);

// Splits every block that the segment crosses completely.
void cutBlocksWithSegment(std::vector<Polygon>& blocks, Vec2 a, Vec2 b);

}  // namespace vdec
