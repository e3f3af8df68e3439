#include "geometry/block_cutting.hpp"
#include "requirements.hpp"

using namespace vdec;

namespace {
double totalArea(const std::vector<Polygon>& blocks) {
  double a = 0.0;
  for (const auto& b : blocks) a += signedArea(b);
  return a;
}
JointSetSpec jointSet(double angleDeg, double spacing, double spacingVariation = 0.0) {
  JointSetSpec set;
  set.angleDeg = angleDeg;
  set.spacing = spacing;
  set.spacingVariation = spacingVariation;
  return set;
}
RegionSpec square(double size) {
  RegionSpec r;
  r.name = "r";
  r.boundary = {{0, 0}, {size, 0}, {size, size}, {0, size}};
  return r;
}
}  // namespace

TEST(BlockCutting, CrackAcrossTheRegionSplitsItAndPartialCrackDoesNot) {
  VDEC_REQUIREMENTS("REQ-GEOM-003");
  RegionSpec r = square(4.0);
  r.cracks.push_back({{-1.0, 1.0}, {5.0, 3.0}});
  EXPECT_EQ(cutRegion(r).size(), 2u);
  RegionSpec partial = square(4.0);
  partial.cracks.push_back({{-1.0, 1.0}, {2.0, 2.0}});  // ends inside the block
  EXPECT_EQ(cutRegion(partial).size(), 1u);
}

TEST(BlockCutting, OrthogonalJointSetsMakeAGridOfEqualBlocks) {
  VDEC_REQUIREMENTS("REQ-GEOM-003");
  RegionSpec r = square(4.0);
  r.jointSets = {jointSet(0.0, 1.0), jointSet(90.0, 1.0)};
  const auto blocks = cutRegion(r);
  ASSERT_EQ(blocks.size(), 16u);
  for (const auto& b : blocks) EXPECT_NEAR(signedArea(b), 1.0, 1e-12);
}

TEST(BlockCutting, FiniteTracesOnlyCutBlocksTheyCrossCompletely) {
  VDEC_REQUIREMENTS("REQ-GEOM-003");
  RegionSpec r = square(4.0);
  JointSetSpec vertical;
  vertical.angleDeg = 90.0;
  vertical.spacing = 1.0;
  r.jointSets.push_back(vertical);  // 4 columns
  JointSetSpec horizontal;
  horizontal.spacing = 2.0;
  horizontal.origin = {0.0, 1.0};
  horizontal.trace = 1.5;  // long enough to cross one 1 m column, never two
  horizontal.gap = 10.0;   // at most one segment per joint line crosses the region
  r.jointSets.push_back(horizontal);
  const auto blocks = cutRegion(r);
  EXPECT_NEAR(totalArea(blocks), 16.0, 1e-12);
  EXPECT_GE(blocks.size(), 4u);
  EXPECT_LE(blocks.size(), 4u + 2u * 2u);  // two joint lines, each cuts at most two columns
}

TEST(BlockCutting, SameSeedGivesSameBlocksAndAnotherSeedDiffers) {
  VDEC_REQUIREMENTS("REQ-GEOM-003");
  RegionSpec r = square(10.0);
  JointSetSpec set;
  set.angleDeg = 30.0;
  set.angleVariationDeg = 10.0;
  set.spacing = 1.0;
  set.spacingVariation = 0.4;
  set.trace = 6.0;
  set.traceVariation = 2.0;
  set.gap = 1.0;
  set.gapVariation = 0.5;
  r.jointSets.push_back(set);
  r.seed = 7;
  const auto a = cutRegion(r), b = cutRegion(r);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].size(), b[i].size());
    for (std::size_t k = 0; k < a[i].size(); ++k) {
      EXPECT_EQ(a[i][k].x, b[i][k].x);
      EXPECT_EQ(a[i][k].y, b[i][k].y);
    }
  }
  r.seed = 8;
  const auto c = cutRegion(r);
  bool differs = c.size() != a.size();
  for (std::size_t i = 0; !differs && i < a.size(); ++i) differs = signedArea(a[i]) != signedArea(c[i]);
  EXPECT_TRUE(differs);
  EXPECT_NEAR(totalArea(a), 100.0, 1e-9);
}

TEST(BlockCutting, TheGridCutterGivesThePiecesOfCuttingEveryBlockInTheSameOrder) {
  VDEC_REQUIREMENTS("REQ-GEOM-003");
  // Regions of several shapes cut by cracks, crossing joint sets with variations, and traced
  // sets with gaps: the grid may only skip blocks a segment cannot split.
  const std::vector<Polygon> outlines = {
      {{0, 0}, {40, 0}, {40, 25}, {0, 25}},
      {{0, 0}, {30, -5}, {45, 10}, {35, 30}, {5, 28}, {-8, 12}},
      {{-3, -1}, {60, 2}, {20, 6}},
  };
  int compared = 0;
  for (std::size_t o = 0; o < outlines.size(); ++o)
    for (std::uint64_t seed : {1u, 7u, 12345u}) {
      RegionSpec r;
      r.boundary = outlines[o];
      r.seed = seed;
      r.cracks.push_back({{-10, 3}, {70, 9}});
      r.cracks.push_back({{10, -10}, {12, 8}});  // ends inside
      JointSetSpec a = jointSet(30.0, 1.3, 0.4);
      a.angleVariationDeg = 3.0;
      JointSetSpec b = jointSet(100.0, 1.7, 0.3);
      b.origin = {0.3, 0.1};
      JointSetSpec traced = jointSet(160.0, 2.1);
      traced.angleVariationDeg = 10.0;
      traced.trace = 4.0;
      traced.traceVariation = 2.0;
      traced.gap = 1.0;
      traced.gapVariation = 0.5;
      r.jointSets = {a, b, traced};
      const std::vector<Polygon> grid = cutRegion(r), plain = cutRegionBlockByBlock(r);
      ASSERT_EQ(grid.size(), plain.size());
      EXPECT_GT(grid.size(), 100u);
      for (std::size_t k = 0; k < grid.size(); ++k) {
        ASSERT_EQ(grid[k].size(), plain[k].size()) << "outline " << o << " seed " << seed << " piece " << k;
        for (std::size_t v = 0; v < grid[k].size(); ++v) {
          EXPECT_EQ(grid[k][v].x, plain[k][v].x);
          EXPECT_EQ(grid[k][v].y, plain[k][v].y);
        }
      }
      ++compared;
    }
  EXPECT_EQ(compared, 9);
}

TEST(BlockCutting, TheEstimateBoundsTheBlocksOfCrossingJointSets) {
  VDEC_REQUIREMENTS("REQ-IO-005");
  RegionSpec r = square(40.0);
  r.jointSets = {jointSet(30.0, 1.0, 0.2), jointSet(120.0, 1.0, 0.2)};
  const RegionEstimate e = estimateRegion(r);
  const double blocks = static_cast<double>(cutRegion(r).size());
  EXPECT_GE(e.blocks, blocks);
  EXPECT_LE(e.blocks, 4.0 * blocks);  // of the right order, to refuse scenes by it
  JointSetSpec tiny = jointSet(30.0, 1.0, 0.2);
  tiny.trace = 1e-6;
  r.jointSets = {tiny};
  EXPECT_GT(estimateRegion(r).segments, 1e9);  // refused before a single cut
}
