// core/float_math.hpp: the float polynomials that replace cosf and expf in evaluators whose SIMD
// twins must give the same bytes on every target are accurate to float rounding.

#include "core/float_math.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace stochtex::float_math_test {
namespace {

TEST(FloatMath, CosineInTurnsIsAccurate) {
  for (float t = -60.0f; t < 60.0f; t += 0.0137f)
    EXPECT_NEAR(cos_turns(t), std::cos(2.0 * std::numbers::pi * static_cast<double>(t)), 3e-6) << t;
  for (float t = -0.5f; t <= 0.5f; t += 1.0f / 1024.0f)
    EXPECT_NEAR(cos_turns(t), std::cos(2.0 * std::numbers::pi * static_cast<double>(t)), 3e-7) << t;
}

TEST(FloatMath, ExponentialIsWithinTwoUlp) {
  double worst = 0.0;
  for (float x = -87.0f; x <= 88.0f; x += 0.00731f) {
    const double exact = std::exp(static_cast<double>(x));
    const double error = std::abs(exp_float(x) - exact) / exact;
    worst = std::max(worst, error);
  }
  EXPECT_LT(worst, 2.0 * 0x1p-24);  // 2 ulp of the float's significand
  EXPECT_EQ(exp_float(0.0f), 1.0f);
  EXPECT_EQ(exp_float(-0.0f), 1.0f);
  // Below e^-87 the result is 0; far beyond either end it stays finite and defined.
  EXPECT_EQ(exp_float(-87.5f), 0.0f);
  EXPECT_EQ(exp_float(-1e30f), 0.0f);
  EXPECT_EQ(exp_float(1e30f), exp_float(88.0f));
  EXPECT_TRUE(std::isfinite(exp_float(88.0f)));
}

}  // namespace
}  // namespace stochtex::float_math_test
