// A path event's 16-bit value: within one step of the value, and unbiased.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "trace/event_value.h"
#include "trace/path_record.h"

namespace fenestra {
namespace {

constexpr double kStep = 1.0 / 256.0;  // relative: 8 mantissa bits kept

TEST(EventValue, ValuesWithEightMantissaBitsAreExact) {
  for (float v : {0.0f, 1.0f, 0.5f, 3.0f, 255.0f, 511.0f, std::ldexp(1.0f, -100), std::ldexp(1.5f, 100)})
    for (uint32_t dither : {0u, 1u, 0x4000u, 0x7FFFu, 0xFFFFFFFFu}) EXPECT_EQ(EventValue::round(v, dither).get(), v) << v;
}

TEST(EventValue, RoundsToANeighbourWithinOneStep) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> log_value(-30.0, 30.0);
  for (int i = 0; i < 100000; ++i) {
    const float v = static_cast<float>(std::pow(10.0, log_value(rng)));
    const float stored = EventValue::round(v, static_cast<uint32_t>(rng())).get();
    ASSERT_LE(std::abs(stored - v), kStep * v) << v;
    // Down rounds toward zero, up to the next pattern: the value lies between them.
    const float down = EventValue::round(v, 0).get(), up = EventValue::round(v, EventValue::kDroppedMask).get();
    ASSERT_LE(down, v);
    ASSERT_GE(up, v);
    ASSERT_TRUE(stored == down || stored == up) << v;
  }
}

// The rounding is unbiased: over many values, the mean of stored / value is 1 within 4 standard
// errors of that mean (each ratio's spread is measured, not assumed), with the dither the records
// use (event_dither of the value and its place).
TEST(EventValue, StochasticRoundingIsUnbiased) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> value(1.0f, 2.0f);  // one binade: steps of 2^-8 in absolute
  constexpr int n = 400000;
  double sum = 0.0, sum_sq = 0.0;
  for (int i = 0; i < n; ++i) {
    const float v = value(rng);
    const double error = (EventValue::round(v, event_dither(v, static_cast<uint64_t>(i % 7))).get() - v) / v;
    sum += error, sum_sq += error * error;
  }
  const double mean = sum / n, se = std::sqrt((sum_sq / n - mean * mean) / (n - 1));
  EXPECT_GT(se, 0.0);
  EXPECT_LT(std::abs(mean), 4.0 * se) << "mean relative error " << mean << " +- " << se;
  // A rounding to nearest would leave about 1/sqrt(12) of a step; stochastic rounding more, and
  // never more than half a step in RMS.
  EXPECT_LT(std::sqrt(sum_sq / n), 0.5 * kStep);
}

// The same value recorded in many paths at the same place (a uniform sky reaching one element):
// the path's key decorrelates the roundings, so their mean is the value, within 4 standard errors.
TEST(EventValue, RepeatedValuesAreUnbiasedAcrossPaths) {
  const double step = kStep;  // at 1.0
  const float v = static_cast<float>(1.0 + 0.3 * step);  // 30 % of a step above a pattern
  SensorRecord r;
  const MetElement met{0, CellPoint{}};
  constexpr int n = 20000;
  for (int p = 0; p < n; ++p) {
    r.path_key = static_cast<uint64_t>(p);
    r.add_light(v, &met, 1, nullptr, 0);
    r.end_path();
  }
  double sum = 0.0;
  for (const PathEvent& e : r.events) sum += e.value();
  const double se = step * std::sqrt(0.3 * 0.7 / n);  // Bernoulli(0.3) steps
  EXPECT_LT(std::abs(sum / n - v), 4.0 * se) << sum / n - v;
}

TEST(EventValue, NegativeOrNonFiniteValuesAreRefused) {
  EXPECT_THROW(EventValue::round(-1.0f, 0), std::logic_error);
  EXPECT_THROW(EventValue::round(std::numeric_limits<float>::quiet_NaN(), 0), std::logic_error);
  EXPECT_THROW(EventValue::round(std::numeric_limits<float>::infinity(), 0), std::logic_error);
  EXPECT_EQ(EventValue::round(std::numeric_limits<float>::max(), 0x7FFF).bits(), EventValue::kLargest);
}

}  // namespace
}  // namespace fenestra
