#include <cmath>
#include <numbers>

#include "boundary/time_function.hpp"
#include "requirements.hpp"

using namespace vdec;

TEST(TimeFunction, EachKindAtKnownTimes) {
  VDEC_REQUIREMENTS("REQ-ZONE-012");
  TimeFunction constant;
  EXPECT_EQ(constant(12.5), 1.0);
  TimeFunction linear;
  linear.kind = TimeFunction::Kind::Linear;
  linear.start = 0.5;
  linear.rate = 2.0;
  EXPECT_DOUBLE_EQ(linear(0.25), 1.0);  // 0.5 + 2 x 0.25
  TimeFunction sine;
  sine.kind = TimeFunction::Kind::Sine;
  sine.frequency = 50.0;
  EXPECT_NEAR(sine(0.005), 1.0, 1e-15);  // a quarter period
  sine.phase = std::numbers::pi / 2;
  EXPECT_NEAR(sine(0.0), 1.0, 1e-15);
  TimeFunction cosine;
  cosine.kind = TimeFunction::Kind::Cosine;
  cosine.frequency = 2.0;
  EXPECT_NEAR(cosine(0.25), -1.0, 1e-15);  // half a period
  TimeFunction table;
  table.kind = TimeFunction::Kind::Table;
  table.t = {0.0, 1.0, 3.0};
  table.f = {0.0, 2.0, -2.0};
  EXPECT_DOUBLE_EQ(table(0.5), 1.0);
  EXPECT_DOUBLE_EQ(table(2.0), 0.0);
  EXPECT_DOUBLE_EQ(table(-1.0), 0.0);  // held at the ends
  EXPECT_DOUBLE_EQ(table(9.0), -2.0);
}
