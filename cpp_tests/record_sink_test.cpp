// The record sink counts what it drops (as pbrt counts with its statistics): light that is not a
// finite number, and light or sub-paths past the limit of conditions; counts of the sub-paths'
// sinks reach the path's.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "trace/record_sink.h"

namespace fenestra {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// One element, the unit square of panel 0.
std::vector<Element> one_cell() {
  Element e;
  e.u0 = 0, e.u1 = 1, e.v0 = 0, e.v1 = 1;
  return {e};
}

TEST(RecordSink, NonFiniteLightIsDroppedAndCounted) {
  RecordSink sum = RecordSink::sum();
  sum.light(2.0f, nullptr, 0, 0);
  sum.light(kNan, nullptr, 0, 0);
  sum.light(kInf, nullptr, 0, 0);
  sum.light(-kInf, nullptr, 0, 0);
  sum.light(Rgb(1.0f, kNan, 1.0f), nullptr, 0, 0);
  sum.light(0.0f, nullptr, 0, 0);  // no light: nothing dropped
  EXPECT_EQ(sum.total(), 2.0);
  EXPECT_EQ(sum.dropped().non_finite, 4u);
  EXPECT_EQ(sum.dropped().truncated_conditions, 0u);
  EXPECT_TRUE(sum.dropped().any());
}

TEST(RecordSink, RecordedPathCountsItsSubPathsDrops) {
  const std::vector<Element> cells = one_cell();
  SensorRecord record;
  RecordSink path = RecordSink::record(&record, &cells);
  const Crossing k{0, {0.5f, 0.5f}};
  // A portal sample's sub-path found light and a NaN ...
  RecordSink through = RecordSink::outside();
  through.light(3.0f, nullptr, 0, 0);
  through.light(kNan, nullptr, 0, 0);
  path.light_through(k, through);
  // ... and an escape's sub-path an infinite value.
  RecordSink beyond = RecordSink::outside();
  beyond.light(kInf, nullptr, 0, 0);
  path.escape(k, beyond);
  record.end_path();
  EXPECT_EQ(path.dropped().non_finite, 2u);
  EXPECT_EQ(record.events.size(), 2u);  // the light through k, and the escape (its value 0)
  for (const PathEvent& e : record.events) EXPECT_TRUE(std::isfinite(e.value()));
}

TEST(RecordSink, ConditionsPastTheLimitAreCounted) {
  RecordSink outside = RecordSink::outside();
  const Crossing k{0, {0.5f, 0.5f}};
  for (int i = 0; i < RecordSink::kMaxConditions; ++i) ASSERT_TRUE(outside.reflect_off(k));
  EXPECT_EQ(outside.dropped().truncated_conditions, 0u);
  EXPECT_FALSE(outside.reflect_off(k));  // the sub-path stops here
  EXPECT_FALSE(outside.can_pass(false));
  outside.light(1.0f, &k, 1, 0);  // light that would need one more condition
  EXPECT_EQ(outside.dropped().truncated_conditions, 2u);
  outside.count_truncated();  // a shadow ray across more than kMaxCrossed elements
  EXPECT_EQ(outside.dropped().truncated_conditions, 3u);
  // A sink that takes the sub-path in takes its counts.
  RecordSink parent = RecordSink::outside();
  parent.absorb(outside);
  EXPECT_EQ(parent.dropped().truncated_conditions, 3u);
  EXPECT_EQ(parent.dropped().non_finite, 0u);
}

TEST(RecordSink, DroppedWarningOnlyWhenSomethingWasDropped) {
  EXPECT_EQ(dropped_warning(DropCounts{}), "");
  const std::string w = dropped_warning(DropCounts{2, 0});
  EXPECT_NE(w.find("2 light values that were not finite numbers"), std::string::npos) << w;
  EXPECT_EQ(w.find("met more than"), std::string::npos) << w;
  const std::string t = dropped_warning(DropCounts{0, 1});
  EXPECT_NE(t.find("1 light value or sub-path that met more than 32 elements"), std::string::npos) << t;
}

}  // namespace
}  // namespace fenestra
