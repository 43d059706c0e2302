#include "trace/path_record.h"

namespace fenestra {

void SensorRecord::append(const SensorRecord& other) {
  const uint32_t event_base = static_cast<uint32_t>(events.size());
  const uint32_t crossed_base = static_cast<uint32_t>(crossed.size());
  for (size_t p = 1; p < other.path_begin.size(); ++p) path_begin.push_back(other.path_begin[p] + event_base);
  for (PathEvent e : other.events) {
    e.crossed_begin += crossed_base;
    events.push_back(e);
  }
  crossed.insert(crossed.end(), other.crossed.begin(), other.crossed.end());
}

double path_value(const SensorRecord& record, size_t p, const std::vector<uint8_t>& open) {
  double sum = 0.0;
  for (uint32_t i = record.path_begin[p]; i < record.path_begin[p + 1]; ++i) {
    const PathEvent& e = record.events[i];
    if (e.is_escape()) {
      if (open[e.element]) return sum + e.value;
      continue;
    }
    bool counts = true;
    for (uint32_t c = 0; c < e.crossed_count && counts; ++c) counts = open[record.crossed[e.crossed_begin + c]] != 0;
    if (counts) sum += e.value;
  }
  return sum;
}

}  // namespace fenestra
