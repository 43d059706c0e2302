// Exact evaluation of recorded paths for any set of open elements.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace fenestra
