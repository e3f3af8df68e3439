#include "geometry/block_cutting.hpp"
#include "requirements.hpp"

using namespace vdec;

namespace {
double totalArea(const std::vector<Polygon>& blocks) {
  double a = 0.0;
  for (const auto& b : blocks) a += signedArea(b);
  return a;
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
  JointSetSpec horizontal;
  horizontal.angleDeg = 0.0;
  horizontal.spacing = 1.0;
  JointSetSpec vertical = horizontal;
  vertical.angleDeg = 90.0;
  r.jointSets = {horizontal, vertical};
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
