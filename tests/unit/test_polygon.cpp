#include <cmath>

#include "core/errors.hpp"
#include "geometry/polygon.hpp"
#include "requirements.hpp"

using namespace vdec;

namespace {
Polygon rectangle(double x0, double y0, double w, double h) {
  return {{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}};
}
std::string geometryMessage(const Polygon& p, double d) {
  try {
    validateBlockPolygon(p, d, "block 'b1'");
  } catch (const GeometryError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Polygon, RectangleAreaCentroidAndPolarMomentAreExact) {
  VDEC_REQUIREMENTS("REQ-GEOM-001");
  const Polygon r = rectangle(2.0, -1.0, 3.0, 2.0);
  EXPECT_DOUBLE_EQ(signedArea(r), 6.0);
  EXPECT_DOUBLE_EQ(centroid(r).x, 3.5);
  EXPECT_DOUBLE_EQ(centroid(r).y, 0.0);
  EXPECT_NEAR(polarSecondMoment(r), 6.0 * (9.0 + 4.0) / 12.0, 1e-12);
}

TEST(Polygon, TrianglePropertiesFarFromOriginKeepPrecision) {
  VDEC_REQUIREMENTS("REQ-GEOM-001");
  // Right triangle with legs a, b: J about the centroid = a b (a^2 + b^2) / 36.
  const double x0 = 1e6, y0 = -2e6, a = 3.0, b = 4.0;
  const Polygon t{{x0, y0}, {x0 + a, y0}, {x0, y0 + b}};
  EXPECT_NEAR(signedArea(t), 6.0, 1e-8);
  EXPECT_NEAR(centroid(t).x, x0 + 1.0, 1e-9);
  EXPECT_NEAR(centroid(t).y, y0 + 4.0 / 3.0, 1e-9);
  EXPECT_NEAR(polarSecondMoment(t), a * b * (a * a + b * b) / 36.0, 1e-6);
}

TEST(Polygon, InvalidPolygonsAreRejectedNamingTheBlock) {
  VDEC_REQUIREMENTS("REQ-GEOM-002");
  EXPECT_NE(geometryMessage({{0, 0}, {0, 1}, {1, 1}, {1, 0}}, 0.01).find("clockwise"), std::string::npos);
  EXPECT_NE(geometryMessage({{0, 0}, {1, 1}, {1, 0}, {0, 1}}, 0.01).find("self-intersecting"), std::string::npos);
  EXPECT_NE(geometryMessage({{0, 0}, {2, 0}, {1, 0.2}, {2, 2}, {0, 2}}, 0.01).find("convex blocks only"),
            std::string::npos);
  EXPECT_NE(geometryMessage({{0, 0}, {1, 0}, {2, 0}}, 0.01).find("zero area"), std::string::npos);
  EXPECT_NE(geometryMessage({{0, 0}, {1, 0}}, 0.01).find("at least 3"), std::string::npos);
  EXPECT_NE(geometryMessage(rectangle(0, 0, 1, 0.015), 0.01).find("twice the rounding length"), std::string::npos);
  EXPECT_NE(geometryMessage({{0, 0}, {0, 1}, {1, 1}, {1, 0}}, 0.01).find("block 'b1'"), std::string::npos);
  EXPECT_EQ(geometryMessage(rectangle(0, 0, 1, 1), 0.01), "");
}

TEST(Polygon, SplitConvexConservesAreaAndChordIsClipped) {
  VDEC_REQUIREMENTS("REQ-GEOM-003");
  const Polygon square = rectangle(0, 0, 2, 2);
  const auto parts = splitConvex(square, {0.0, 0.5}, normalized(Vec2{1.0, 0.3}));
  ASSERT_TRUE(parts.has_value());
  EXPECT_NEAR(signedArea(parts->first) + signedArea(parts->second), 4.0, 1e-12);
  EXPECT_GT(signedArea(parts->first), 0.0);
  EXPECT_GT(signedArea(parts->second), 0.0);
  EXPECT_FALSE(splitConvex(square, {0.0, 3.0}, {1.0, 0.0}).has_value());
  const auto chord = chordParameters(square, {-1.0, 1.0}, {1.0, 0.0});
  ASSERT_TRUE(chord.has_value());
  EXPECT_NEAR(chord->first, 1.0, 1e-12);
  EXPECT_NEAR(chord->second, 3.0, 1e-12);
}
