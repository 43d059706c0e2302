// Exact evaluation of recorded paths for any set of open elements.
#include <gtest/gtest.h>

#include <random>

#include "trace/flip_effects.h"
#include "trace/path_record.h"

namespace fenestra {
namespace {

// Builds a record through SensorRecord's own appenders, and keeps the same events plainly for a
// reference evaluation written straight from PathEvent's definition (with the values as stored,
// rounded to 16 bits: event_value_test checks the rounding).
struct RecordBuilder {
  struct Plain {
    float value;
    int element;
    std::vector<int32_t> open, closed;
    bool part;
  };
  SensorRecord record;
  std::vector<std::vector<Plain>> paths{{}};

  void add(float value, int element, std::vector<int32_t> open, std::vector<int32_t> closed, bool part = false) {
    auto met = [](const std::vector<int32_t>& ks) {
      std::vector<MetElement> out;
      for (int32_t k : ks) out.push_back({k, CellPoint{}});
      return out;
    };
    const std::vector<MetElement> o = met(open), c = met(closed);
    if (element < 0)
      record.add_light(value, o.data(), o.size(), c.data(), c.size());
    else
      record.add_escape(value, {element, CellPoint{}}, part, o.data(), o.size(), c.data(), c.size());
    paths.back().push_back({record.events.back().value(), element, open, closed, part});
  }
  void end_path() {
    record.end_path();
    paths.emplace_back();
  }
  // Light counts when its conditions hold; the first open escape gathers its parts whose
  // conditions hold, and nothing after counts.
  double reference_value(size_t p, const std::vector<uint8_t>& open) const {
    auto holds = [&](const Plain& e) {
      for (int32_t k : e.open)
        if (!open[k]) return false;
      for (int32_t k : e.closed)
        if (open[k]) return false;
      return true;
    };
    const std::vector<Plain>& events = paths[p];
    double sum = 0.0;
    for (size_t i = 0; i < events.size(); ++i) {
      const Plain& e = events[i];
      if (e.element < 0) {
        if (holds(e)) sum += e.value;
      } else if (!e.part && open[e.element]) {
        sum += e.value;
        for (size_t j = i + 1; j < events.size() && events[j].part; ++j)
          if (holds(events[j])) sum += events[j].value;
        return sum;
      }
    }
    return sum;
  }
};

TEST(PathRecord, LightCountsWhenItsConditionsHold) {
  RecordBuilder b;
  b.add(1.0f, -1, {}, {});         // always
  b.add(2.0f, -1, {0}, {});        // needs 0 open
  b.add(4.0f, -1, {0, 1}, {});     // a shadow ray through 0 and 1
  b.add(8.0f, -1, {1}, {2});       // through 1, after reflecting off 2
  b.end_path();
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
  b.end_path();
  EXPECT_EQ(path_value(b.record, 0, {0, 0}), 101.0);
  EXPECT_EQ(path_value(b.record, 0, {1, 0}), 1.0 + 10.0 + 20.0);
  EXPECT_EQ(path_value(b.record, 0, {1, 1}), 1.0 + 10.0 + 40.0);
  EXPECT_EQ(path_value(b.record, 0, {0, 1}), 1.0 + 100.0 + 1000.0);
}

TEST(PathRecord, AppendKeepsPathsAndConditions) {
  RecordBuilder a, b;
  a.add(1.0f, -1, {0}, {});
  a.end_path();
  b.add(2.0f, -1, {1}, {0});
  b.end_path();
  a.record.append(b.record);
  ASSERT_EQ(a.record.path_count(), 2u);
  EXPECT_EQ(path_value(a.record, 1, {0, 1}), 2.0);
  EXPECT_EQ(path_value(a.record, 1, {1, 1}), 0.0);
  EXPECT_EQ(path_value(a.record, 0, {1, 1}), 1.0);
}

// Light through one element is kept in the event itself (PathEvent::kOwnCondition), taking no
// entry in the conditions; any other light or escape stores its conditions.
TEST(PathRecord, LightThroughOneElementKeepsItsConditionInTheEvent) {
  RecordBuilder b;
  b.add(2.0f, -1, {3}, {});
  b.add(4.0f, -1, {3, 4}, {});
  b.add(8.0f, -1, {3}, {4});
  b.end_path();
  EXPECT_TRUE(b.record.events[0].own_condition());
  EXPECT_EQ(b.record.events[0].element(), 3);
  EXPECT_FALSE(b.record.events[1].own_condition());
  EXPECT_FALSE(b.record.events[2].own_condition());
  EXPECT_EQ(b.record.conditions, (std::vector<int32_t>{2, 3, 4, 1 | 1 << 8, 3, 4}));  // each list after its counts
  EXPECT_EQ(b.record.condition_points.size(), b.record.conditions.size());
  EXPECT_EQ(b.record.event_points.size(), b.record.events.size());
  EXPECT_EQ(path_value(b.record, 0, {0, 0, 0, 1, 0}), 10.0);
  EXPECT_EQ(path_value(b.record, 0, {0, 0, 0, 0, 1}), 0.0);
  EXPECT_EQ(path_value(b.record, 0, {0, 0, 0, 1, 1}), 6.0);
}

// Seeded random paths of every kind of event, appended record to record: path_value agrees with
// the reference evaluation for random masks.
TEST(PathRecord, EvaluationAgreesWithThePlainReference) {
  std::mt19937 rng(5);
  constexpr int kElements = 5;
  auto some = [&](int most) {
    std::vector<int32_t> out(rng() % (most + 1));
    for (int32_t& k : out) k = static_cast<int32_t>(rng() % kElements);
    return out;
  };
  RecordBuilder whole;
  SensorRecord appended;
  for (int part = 0; part < 3; ++part) {
    RecordBuilder b;
    for (int path = 0; path < 200; ++path) {
      const int events = 1 + static_cast<int>(rng() % 8);
      for (int e = 0; e < events; ++e) {
        const float value = 1.0f + static_cast<float>(rng() % 1000);
        const int kind = static_cast<int>(rng() % 4);  // light, light through one element, escape, part
        std::vector<int32_t> open = kind == 1 ? std::vector<int32_t>{static_cast<int32_t>(rng() % kElements)} : some(3);
        std::vector<int32_t> closed = kind == 1 ? std::vector<int32_t>{} : some(2);
        const int element = kind < 2 ? -1 : static_cast<int>(rng() % kElements);
        if (kind == 2) open.clear(), closed.clear();
        b.add(value, element, open, closed, kind == 3);
        whole.add(value, element, open, closed, kind == 3);
      }
      b.end_path();
      whole.end_path();
    }
    appended.append(b.record);
  }
  ASSERT_EQ(appended.path_count(), 600u);
  ASSERT_EQ(appended.conditions, whole.record.conditions);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<uint8_t> open(kElements);
    for (uint8_t& o : open) o = rng() % 2;
    for (size_t p = 0; p < appended.path_count(); ++p) {
      ASSERT_EQ(path_value(appended, p, open), whole.reference_value(p, open)) << "path " << p << " trial " << trial;
      ASSERT_EQ(path_value(whole.record, p, open), whole.reference_value(p, open)) << "path " << p;
    }
  }
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
      b.end_path();
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
