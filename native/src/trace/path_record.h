#pragma once
// What one pass of paths leaves behind: for every path, its events in path order, enough to
// evaluate the sensor value for ANY set of open elements (same paths, no linear model).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace fenestra {

// An event counts when every element of its `open` list is open and every element of its
// `closed` list is closed (the lists live in SensorRecord::conditions, open ones first).
struct PathEvent {
  float value;             // luminance-weighted contribution (sky units x sr; lux for a sky in cd/m^2)
  int32_t element;         // >= 0: an escape: the path reaches this element; if it is open the path
                           //       leaves through it, gathers this event's value (and that of the
                           //       escape parts right after it whose conditions hold) and nothing
                           //       later counts. Parts are light found beyond the element that met
                           //       other elements: through them (open) or off them (closed).
                           // -1:   light (sky hit or next-event estimate).
  uint32_t conditions_begin;
  uint16_t open_count;     // elements that must be open (e.g. crossed by a shadow ray)
  uint8_t closed_count;    // elements that must be closed (reflected off outside)
  uint8_t flags;           // kEscapePart

  static constexpr uint8_t kEscapePart = 1;
  bool is_escape() const { return element >= 0 && !(flags & kEscapePart); }
  bool is_escape_part() const { return element >= 0 && (flags & kEscapePart); }
  bool is_light() const { return element < 0; }
};

struct SensorRecord {
  std::vector<uint32_t> path_begin{0};  // events of path p: [path_begin[p], path_begin[p + 1])
  std::vector<PathEvent> events;
  std::vector<int32_t> conditions;

  size_t path_count() const { return path_begin.size() - 1; }
  void end_path() { path_begin.push_back(static_cast<uint32_t>(events.size())); }
  void append(const SensorRecord& other);
  // Whether event e's conditions hold for the open mask.
  bool holds(const PathEvent& e, const std::vector<uint8_t>& open) const;
  size_t memory_bytes() const {
    return path_begin.capacity() * sizeof(uint32_t) + events.capacity() * sizeof(PathEvent) +
           conditions.capacity() * sizeof(int32_t);
  }
};

// Value of path p of `record` when exactly the elements with open[k] != 0 are open.
double path_value(const SensorRecord& record, size_t p, const std::vector<uint8_t>& open);

}  // namespace fenestra
