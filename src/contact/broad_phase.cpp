#include "contact/broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace vdec {

std::vector<std::pair<int, int>> overlappingPairs(const std::vector<double>& minX, const std::vector<double>& maxX,
                                                  const std::vector<double>& minY, const std::vector<double>& maxY,
                                                  BroadPhaseGrid& g) {
  const int n = static_cast<int>(minX.size());
  if (n < 2) return {};
  // A uniform grid of cells the size of a typical block (the median box extent): each block is
  // listed in the cells its box overlaps, and a pair is tested only in the cell holding the
  // lower-left corner of the two boxes' intersection, so that it is found once. A sweep along
  // one axis would compare every block with a whole column of a regular lattice.
  std::vector<double> extent(n);
  double loX = INFINITY, loY = INFINITY, hiX = -INFINITY, hiY = -INFINITY;
  for (int b = 0; b < n; ++b) {
    extent[b] = std::max(maxX[b] - minX[b], maxY[b] - minY[b]);
    loX = std::min(loX, minX[b]);
    loY = std::min(loY, minY[b]);
    hiX = std::max(hiX, maxX[b]);
    hiY = std::max(hiY, maxY[b]);
  }
  std::nth_element(extent.begin(), extent.begin() + n / 2, extent.end());
  double cell = std::max(extent[n / 2], 1e-300);
  // A few huge blocks among tiny ones must not make the grid huge: at most about 4 cells a block.
  const double area = (hiX - loX) * (hiY - loY);
  cell = std::max({cell, std::sqrt(area / (4.0 * n)), (hiX - loX) / (4.0 * n), (hiY - loY) / (4.0 * n)});
  const int nx = std::max(1, static_cast<int>((hiX - loX) / cell) + 1);
  const int ny = std::max(1, static_cast<int>((hiY - loY) / cell) + 1);
  // Clamped before the conversion, so that no coordinate can overflow it.
  auto column = [&](double x) { return static_cast<int>(std::clamp((x - loX) / cell, 0.0, nx - 1.0)); };
  auto row = [&](double y) { return static_cast<int>(std::clamp((y - loY) / cell, 0.0, ny - 1.0)); };
  g.cellStart.assign(static_cast<std::size_t>(nx) * ny + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    for (int b = 0; b < n; ++b)
      for (int iy = row(minY[b]); iy <= row(maxY[b]); ++iy)
        for (int ix = column(minX[b]); ix <= column(maxX[b]); ++ix) {
          const std::size_t c = static_cast<std::size_t>(iy) * nx + ix;
          if (pass == 0) ++g.cellStart[c + 1];
          else g.cellBlocks[g.cellFill[c]++] = b;
        }
    if (pass == 0) {
      for (std::size_t c = 0; c + 1 < g.cellStart.size(); ++c) g.cellStart[c + 1] += g.cellStart[c];
      g.cellBlocks.resize(g.cellStart.back());
      g.cellFill.assign(g.cellStart.begin(), g.cellStart.end() - 1);
    }
  }
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t c = 0; c + 1 < g.cellStart.size(); ++c) {
    const int ix = static_cast<int>(c % nx), iy = static_cast<int>(c / nx);
    for (int i = g.cellStart[c]; i < g.cellStart[c + 1]; ++i) {
      const int a = g.cellBlocks[i];
      for (int k = i + 1; k < g.cellStart[c + 1]; ++k) {
        const int b = g.cellBlocks[k];
        if (minX[b] > maxX[a] || minX[a] > maxX[b] || minY[b] > maxY[a] || minY[a] > maxY[b]) continue;
        if (column(std::max(minX[a], minX[b])) != ix || row(std::max(minY[a], minY[b])) != iy) continue;
        pairs.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
  }
  return pairs;
}

}  // namespace vdec
