// Local reinforcement: the continuously-yielding spring of its axial and shear laws.
#include <gtest/gtest.h>

#include <cmath>

#include "requirements.hpp"
#include "structure/bolts.hpp"

using namespace vdec;

TEST(Bolts, TheYieldingSpringFollowsItsClosedFormAndNeverPassesItsBound) {
  VDEC_REQUIREMENTS("REQ-STRUCT-009");
  const double K = 1e8, bound = 1e5;
  // Loaded from zero, F = K u F_max / (F_max + K u) whatever the increments (the update is the
  // law's exact integral over each one).
  for (const int steps : {1, 7, 1000}) {
    double F = 0.0;
    const double u = 0.02;
    for (int i = 0; i < steps; ++i) F = yieldingSpringForce(F, K, u / steps, bound);
    EXPECT_NEAR(F, K * u * bound / (bound + K * u), 1e-9 * bound) << steps << " increments";
  }
  // Negative increments mirror it.
  EXPECT_NEAR(yieldingSpringForce(0.0, K, -1e-3, bound), -K * 1e-3 * bound / (bound + K * 1e-3), 1e-9 * bound);
  // A huge increment approaches the bound and does not pass it; the first small one is elastic.
  EXPECT_LT(yieldingSpringForce(0.0, K, 1e3, bound), bound);
  EXPECT_GT(yieldingSpringForce(0.0, K, 1e3, bound), 0.9999 * bound);
  EXPECT_NEAR(yieldingSpringForce(0.0, K, 1e-9, bound), K * 1e-9, 2e-6 * K * 1e-9);  // the law bends by K u / F_max = 1e-6
  // A force beyond the bound (a bound lowered) falls back towards it even as the spring stretches.
  EXPECT_LT(yieldingSpringForce(2.0 * bound, K, 1e-4, bound), 2.0 * bound);
  EXPECT_GT(yieldingSpringForce(2.0 * bound, K, 1e-4, bound), bound);
  // No bound: a linear spring; a bound of zero: no force.
  EXPECT_DOUBLE_EQ(yieldingSpringForce(5.0, K, 1e-3, INFINITY), 5.0 + K * 1e-3);
  EXPECT_DOUBLE_EQ(yieldingSpringForce(5.0, K, 1e-3, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(yieldingSpringForce(5.0, K, 0.0, bound), 5.0);
}

TEST(Bolts, UnloadingAtTheBoundIsStifferAsTheLawSays) {
  VDEC_REQUIREMENTS("REQ-STRUCT-009");
  // At F = F_max a reversal has F_b = -F_max: f = |F_b - F| (F_b - F) / F_max^2 = -4, so the
  // force first falls at 4 K (1.4-48, 1.4-49 as written).
  const double K = 1e8, bound = 1e5, d = 1e-9;
  const double slope = (bound - yieldingSpringForce(bound, K, -d, bound)) / d;
  EXPECT_NEAR(slope, 4.0 * K, 1e-5 * 4.0 * K);
}
