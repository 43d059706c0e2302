#pragma once
// What one pass of paths leaves behind: for every path, its events in path order, enough to
// evaluate the sensor value for ANY set of open elements exactly (same random numbers).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace fenestra {

struct PathEvent {
  float value;             // luminance-weighted contribution (sky units x sr; lux for a sky in cd/m^2)
  int32_t element;         // >= 0: the path reaches this element; if it is open the path leaves
                           //       through it with `value` and nothing later counts.
                           // -1: light (sky hit or next-event estimate) that counts when every
                           //       element in `crossed` is open (always, when `crossed` is empty).
  uint32_t crossed_begin;  // into SensorRecord::crossed
  uint32_t crossed_count;
  bool is_escape() const { return element >= 0; }
};

struct SensorRecord {
  std::vector<uint32_t> path_begin{0};  // events of path p: [path_begin[p], path_begin[p + 1])
  std::vector<PathEvent> events;
  std::vector<int32_t> crossed;

  size_t path_count() const { return path_begin.size() - 1; }
  void end_path() { path_begin.push_back(static_cast<uint32_t>(events.size())); }
  void append(const SensorRecord& other);
  size_t memory_bytes() const {
    return path_begin.capacity() * sizeof(uint32_t) + events.capacity() * sizeof(PathEvent) +
           crossed.capacity() * sizeof(int32_t);
  }
};

// Value of path p of `record` when exactly the elements with open[k] != 0 are open.
double path_value(const SensorRecord& record, size_t p, const std::vector<uint8_t>& open);

}  // namespace fenestra
