#pragma once
// Broad phase of contact detection: the pairs of axis-aligned boxes that overlap.
#include <utility>
#include <vector>

namespace vdec {

// Buffers of the uniform grid, kept between calls so that a scan allocates nothing new.
struct BroadPhaseGrid {
  std::vector<int> cellStart, cellBlocks, cellFill;
};

// Each overlapping pair (a, b), a < b, once; in no particular order.
std::vector<std::pair<int, int>> overlappingPairs(const std::vector<double>& minX, const std::vector<double>& maxX,
                                                  const std::vector<double>& minY, const std::vector<double>& maxY,
                                                  BroadPhaseGrid& grid);

}  // namespace vdec
