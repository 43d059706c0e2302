// Exact evaluation of recorded paths for any set of open elements.
#include <gtest/gtest.h>

#include <random>

#include "trace/flip_effects.h"
#include "trace/path_record.h"

namespace fenestra {
namespace {

struct RecordBuilder {
  SensorRecord record;
  void add(float value, int element, std::vector<int32_t> open, std::vector<int32_t> closed, bool part = false) {
    record.events.push_back({value, element, static_cast<uint32_t>(record.conditions.size()),
                             static_cast<uint16_t>(open.size()), static_cast<uint8_t>(closed.size()),
                             static_cast<uint8_t>(part ? PathEvent::kEscapePart : 0)});
    record.conditions.insert(record.conditions.end(), open.begin(), open.end());
    record.conditions.insert(record.conditions.end(), closed.begin(), closed.end());
  }
};

TEST(PathRecord, LightCountsWhenItsConditionsHold) {
  RecordBuilder b;
  b.add(1.0f, -1, {}, {});         // always
  b.add(2.0f, -1, {0}, {});        // needs 0 open
  b.add(4.0f, -1, {0, 1}, {});     // a shadow ray through 0 and 1
  b.add(8.0f, -1, {1}, {2});       // through 1, after reflecting off 2
  b.record.end_path();
  EXPECT_EQ(path_value(b.record, 0, {0, 0, 0}), 1.0);
  EXPECT_EQ(path_value(b.record, 0, {1, 0, 0}), 3.0);
  EXPECT_EQ(path_value(b.record, 0, {1, 1, 0}), 15.0);
  EXPECT_EQ(path_value(b.record, 0, {1, 1, 1}), 7.0);
  EXPECT_EQ(path_value(b.record, 0, {0, 1, 0}), 9.0);
}

TEST(PathRecord, FirstOpenEscapeEndsThePathAndGathersItsParts) {
  RecordBuilder b;
  b.add(1.0f, -1, {}, {});
  b.add(10.0f, 0, {}, {});              // escape through 0 ...
  b.add(20.0f, 0, {}, {1}, true);       // ... light found after reflecting off 1 outside
  b.add(40.0f, 0, {1}, {}, true);       // ... light found after going on through 1
  b.add(100.0f, -1, {}, {});            // only while 0 is closed
  b.add(1000.0f, 1, {}, {});            // escape through 1
  b.record.end_path();
  EXPECT_EQ(path_value(b.record, 0, {0, 0}), 101.0);
  EXPECT_EQ(path_value(b.record, 0, {1, 0}), 1.0 + 10.0 + 20.0);
  EXPECT_EQ(path_value(b.record, 0, {1, 1}), 1.0 + 10.0 + 40.0);
  EXPECT_EQ(path_value(b.record, 0, {0, 1}), 1.0 + 100.0 + 1000.0);
}

TEST(PathRecord, AppendKeepsPathsAndConditions) {
  RecordBuilder a, b;
  a.add(1.0f, -1, {0}, {});
  a.record.end_path();
  b.add(2.0f, -1, {1}, {0});
  b.record.end_path();
  a.record.append(b.record);
  ASSERT_EQ(a.record.path_count(), 2u);
  EXPECT_EQ(path_value(a.record, 1, {0, 1}), 2.0);
  EXPECT_EQ(path_value(a.record, 1, {1, 1}), 0.0);
  EXPECT_EQ(path_value(a.record, 0, {1, 1}), 1.0);
}

// The single-pass flip effects equal flipping each element and evaluating again, on seeded random
// paths: lights with conditions (repeated elements, both lists), escapes through the same element
// more than once, parts, parts cut off by light.
TEST(PathRecord, FlipEffectsEqualEvaluatingEachFlip) {
  std::mt19937 rng(17);
  constexpr int kElements = 6;
  auto some = [&](int most) {
    std::vector<int32_t> out(rng() % (most + 1));
    for (int32_t& k : out) k = static_cast<int32_t>(rng() % kElements);
    return out;
  };
  Contributions c;
  c.E = Eigen::MatrixXd::Zero(3, kElements);
  for (int sensor = 0; sensor < 3; ++sensor) {
    RecordBuilder b;
    for (int path = 0; path < 300; ++path) {
      const int events = 1 + static_cast<int>(rng() % 9);
      for (int e = 0; e < events; ++e) {
        const float value = 1.0f + static_cast<float>(rng() % 1000) / 10.0f;
        const int kind = static_cast<int>(rng() % 3);  // light, escape, part
        if (kind == 0) b.add(value, -1, some(3), some(2));
        if (kind == 1) b.add(value, static_cast<int>(rng() % kElements), {}, {});
        if (kind == 2) b.add(value, static_cast<int>(rng() % kElements), some(2), some(2), true);
      }
      b.record.end_path();
    }
    c.records.push_back(b.record);
  }
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<uint8_t> open(kElements);
    for (uint8_t& o : open) o = rng() % 2;
    const Eigen::MatrixXd D = flip_effects(c, open, nullptr);
    for (size_t i = 0; i < c.records.size(); ++i) {
      const SensorRecord& r = c.records[i];
      for (int k = 0; k < kElements; ++k) {
        std::vector<uint8_t> flipped = open;
        flipped[k] ^= 1;
        double expected = 0.0;
        for (size_t p = 0; p < r.path_count(); ++p) expected += path_value(r, p, flipped) - path_value(r, p, open);
        expected /= static_cast<double>(r.path_count());
        ASSERT_NEAR(D(i, k), expected, 1e-9 * (1.0 + std::abs(expected))) << "trial " << trial << " sensor " << i << " element " << k;
      }
    }
  }
}

}  // namespace
}  // namespace fenestra
