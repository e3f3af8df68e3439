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

TEST(TimeFunction, AnIntegratedTableIsItsIntegralFromZeroAtKnownTimes) {
  VDEC_REQUIREMENTS("REQ-BOUNDARY-002");
  // An acceleration record: 2 m/s^2 rising from 0 at t = 0 to 2 at t = 1, falling to -2 at t = 3.
  TimeFunction record;
  record.kind = TimeFunction::Kind::Table;
  record.t = {0.0, 1.0, 3.0};
  record.f = {0.0, 2.0, -2.0};
  record.integrate();
  EXPECT_DOUBLE_EQ(record(0.0), 0.0);
  EXPECT_DOUBLE_EQ(record(0.5), 0.25);      // the integral of 2 t: t^2
  EXPECT_DOUBLE_EQ(record(1.0), 1.0);
  EXPECT_DOUBLE_EQ(record(2.0), 2.0);       // + the triangle 1 x 2 / 2 from 1 to 2
  EXPECT_DOUBLE_EQ(record(3.0), 1.0);       // and back down by as much
  EXPECT_DOUBLE_EQ(record(4.0), -1.0);      // -2 held after the last row
  // A record starting before 0 is integrated from 0 all the same: 1 m/s^2 throughout.
  TimeFunction early;
  early.kind = TimeFunction::Kind::Table;
  early.t = {-2.0, 5.0};
  early.f = {1.0, 1.0};
  early.integrate();
  EXPECT_DOUBLE_EQ(early(0.0), 0.0);
  EXPECT_DOUBLE_EQ(early(3.0), 3.0);
  // One starting after 0: its first value held from 0.
  TimeFunction late;
  late.kind = TimeFunction::Kind::Table;
  late.t = {1.0, 2.0};
  late.f = {3.0, 3.0};
  late.integrate();
  EXPECT_DOUBLE_EQ(late(0.5), 1.5);
  EXPECT_DOUBLE_EQ(late(2.0), 6.0);
}
