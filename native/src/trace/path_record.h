#pragma once
// What one pass of paths leaves behind: for every path, its events in path order, enough to
// evaluate the sensor value for ANY set of open elements (same paths, no linear model).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "trace/cell_point.h"
#include "trace/event_value.h"

namespace fenestra {

// An event counts when every element of its `open` list is open and every element of its
// `closed` list is closed. Light that needs one element open, the commonest event, names that
// element itself (kOwnCondition); other lists live in SensorRecord::conditions, event after event
// in path order, each after a header entry holding its counts (kStoredConditions).
// Six bytes: the value (16 bits, EventValue), and the element (24 bits) with the flags (8).
struct PathEvent {
  EventValue stored;  // luminance-weighted contribution (sky units x sr; lux for a sky in cd/m^2)
  uint16_t low = 0, high = 0;  // element | flags << 24, in two halves (keeps the event 2-aligned)

  // An escape (no flag of kind): the path reaches element(); if it is open the path leaves through
  //   it, gathers this event's value (and that of the escape parts right after it whose conditions
  //   hold) and nothing later counts.
  // A part (kEscapePart) of the escape before it, element() the same: light found beyond that
  //   element after meeting other elements, through them (open) or off them (closed).
  // Light (kLight; a sky hit or a next-event estimate): element() is the one element it needs
  //   open with kOwnCondition (its point is the event's point), else -1.
  static constexpr uint8_t kEscapePart = 1, kLight = 2, kOwnCondition = 4, kStoredConditions = 8;
  static constexpr uint32_t kNoElement = 0xFFFFFFu;  // 24 bits
  static constexpr int32_t kMaxElements = static_cast<int32_t>(kNoElement);  // element ids below this

  // `dither`: the rounding fraction of the value (event_dither).
  static PathEvent make(float value, int32_t element, uint8_t flags, uint32_t dither) {
    const uint32_t e = element < 0 ? kNoElement : static_cast<uint32_t>(element);
    const uint32_t word = e | static_cast<uint32_t>(flags) << 24;
    PathEvent event;
    event.stored = EventValue::round(value, dither);
    event.low = static_cast<uint16_t>(word), event.high = static_cast<uint16_t>(word >> 16);
    return event;
  }
  float value() const { return stored.get(); }
  void set_value(float value, uint32_t dither) { stored = EventValue::round(value, dither); }
  uint32_t word() const { return static_cast<uint32_t>(low) | static_cast<uint32_t>(high) << 16; }
  int32_t element() const {
    const uint32_t bits = word();
    const uint32_t e = bits & kNoElement;
    return e == kNoElement ? -1 : static_cast<int32_t>(e);
  }
  uint8_t flags() const { return static_cast<uint8_t>(high >> 8); }
  bool is_escape() const { return !(flags() & (kEscapePart | kLight)); }
  bool is_escape_part() const { return flags() & kEscapePart; }
  bool is_light() const { return flags() & kLight; }
  bool own_condition() const { return flags() & kOwnCondition; }
  bool stored_conditions() const { return flags() & kStoredConditions; }
};

static_assert(sizeof(PathEvent) == 6, "a path event is a 16-bit value and one word");

// The conditions of one event: `open` elements then `closed` ones, entries first .. first + count()
// of SensorRecord::conditions (and condition_points), or the event's own element.
struct EventConditions {
  const int32_t* stored = nullptr;
  int32_t own = -1;
  uint32_t first = 0;
  uint8_t open = 0, closed = 0;
  int count() const { return open + closed; }
  int32_t operator[](int i) const { return stored ? stored[i] : own; }
};

// An element a path met, and where: an escape's element, or a condition of an event.
struct MetElement {
  int32_t element = -1;
  CellPoint point;
};

struct SensorRecord {
  std::vector<uint32_t> path_begin{0};  // events of path p: [path_begin[p], path_begin[p + 1])
  std::vector<uint32_t> path_conditions_begin{0};  // its conditions from here, event after event
  std::vector<PathEvent> events;
  std::vector<int32_t> conditions;
  // Parallel to `events` (escapes and their parts: where the path met the element) and to
  // `conditions` (where the element was crossed or met), as places in the element's cell: any
  // open region of the domain, not only whole elements, can be evaluated (path_value_in_region).
  std::vector<CellPoint> event_points;
  std::vector<CellPoint> condition_points;
  // An annual pass only (`sourced`), parallel to `events`: the light source of each event (a sky
  // patch or a sun cluster, AnnualSources) and its daylight coefficient, the value it has with
  // that source at unit strength (`value` is then its value under the scene's design sky).
  bool sourced = false;
  std::vector<uint16_t> event_sources;
  std::vector<float> event_coefficients;

  // Identifies the path being appended (its sensor and index), so that equal values in different
  // paths round independently (EventValue); not stored.
  uint64_t path_key = 0;

  size_t path_count() const { return path_begin.size() - 1; }
  void end_path() {
    path_begin.push_back(static_cast<uint32_t>(events.size()));
    path_conditions_begin.push_back(static_cast<uint32_t>(conditions.size()));
  }
  // Appends light that needs the `open` elements open and the `closed` ones closed.
  void add_light(float value, const MetElement* open, size_t open_count, const MetElement* closed, size_t closed_count);
  // Appends an escape through `at` (or, `part`, light beyond it under the given conditions).
  void add_escape(float value, const MetElement& at, bool part, const MetElement* open, size_t open_count,
                  const MetElement* closed, size_t closed_count);
  // Calls visit(i, event, conditions) for the events i of path p in order (EventConditions);
  // stops when visit returns false.
  template <typename Visit>
  void walk(size_t p, Visit visit) const {
    uint32_t c = path_conditions_begin[p];
    for (uint32_t i = path_begin[p], end = path_begin[p + 1]; i < end; ++i) {
      const PathEvent& e = events[i];
      EventConditions ec;
      if (e.own_condition()) {
        ec.own = e.element(), ec.open = 1;
      } else if (e.stored_conditions()) {
        const uint32_t header = static_cast<uint32_t>(conditions[c]);
        ec.open = static_cast<uint8_t>(header & 0xFF), ec.closed = static_cast<uint8_t>(header >> 8);
        ec.first = c + 1;
        ec.stored = conditions.data() + ec.first;
        c = ec.first + ec.count();
      }
      if (!visit(i, e, ec)) return;
    }
  }
  void append(const SensorRecord& other);
  // Reserves exactly what appending parts[0 .. count) will need.
  void reserve_for(const SensorRecord* parts, size_t count);
  // Whether conditions (as walk() gives them) hold for the open mask.
  static bool holds(const EventConditions& c, const std::vector<uint8_t>& open);
  size_t memory_bytes() const {
    return (path_begin.capacity() + path_conditions_begin.capacity()) * sizeof(uint32_t) + events.capacity() * (sizeof(PathEvent) + sizeof(CellPoint)) +
           conditions.capacity() * (sizeof(int32_t) + sizeof(CellPoint)) +
           event_sources.capacity() * sizeof(uint16_t) + event_coefficients.capacity() * sizeof(float);
  }

 private:
  void add_event(float value, int32_t element, uint8_t flags, const MetElement* open, size_t open_count,
                 const MetElement* closed, size_t closed_count);
  // The rounding fraction of the event about to be appended (EventValue).
  uint32_t dither_of_next(float value, int32_t element, uint8_t flags) const;
};

// Asks the memory for the start of path p's events and conditions ahead of reading them: the
// solver reads a few paths of each sensor out of millions, and waits on memory, not arithmetic.
inline void prefetch_path(const SensorRecord& r, size_t p) {
  const PathEvent* events = r.events.data() + r.path_begin[p];
  const int32_t* conditions = r.conditions.data() + r.path_conditions_begin[p];
  __builtin_prefetch(events);
  __builtin_prefetch(reinterpret_cast<const char*>(events) + 64);
  __builtin_prefetch(conditions);
  __builtin_prefetch(conditions + 16);
}

// Elements path p's value can depend on (its escapes' and its conditions'), sorted, without repeats.
void path_elements(const SensorRecord& record, size_t p, std::vector<int32_t>* out);

// Value of path p of `record` when exactly the elements with open[k] != 0 are open.
double path_value(const SensorRecord& record, size_t p, const std::vector<uint8_t>& open);

// Calls count(i) for every event i of path p whose light reaches the sensor, given which of its
// points are open: event_open(i) for the escape that is event i (or the one condition light event i
// keeps itself, kOwnCondition), condition_open(j) for entry j of the conditions.
template <typename EventOpen, typename ConditionOpen, typename Count>
void for_each_counting_event(const SensorRecord& r, size_t p, EventOpen event_open, ConditionOpen condition_open,
                             Count count) {
  auto holds = [&](uint32_t i, const EventConditions& c) {
    if (!c.stored) return c.open == 0 || static_cast<bool>(event_open(i));  // none, or its own element
    for (uint32_t j = c.first; j < c.first + c.open; ++j)
      if (!condition_open(j)) return false;
    for (uint32_t j = c.first + c.open; j < c.first + c.count(); ++j)
      if (condition_open(j)) return false;
    return true;
  };
  bool gathering = false;  // the parts of the escape the path left through
  r.walk(p, [&](uint32_t i, const PathEvent& e, const EventConditions& c) {
    if (gathering) {
      if (!e.is_escape_part()) return false;
      if (holds(i, c)) count(i);
      return true;
    }
    if (e.is_light()) {
      if (holds(i, c)) count(i);
    } else if (e.is_escape() && event_open(i)) {
      count(i);
      gathering = true;
    }
    return true;
  });
}

// Value of path p from which of its points are open (see for_each_counting_event).
template <typename EventOpen, typename ConditionOpen>
double path_value_by_point(const SensorRecord& r, size_t p, EventOpen event_open, ConditionOpen condition_open) {
  double sum = 0.0;
  for_each_counting_event(r, p, event_open, condition_open, [&](uint32_t i) { sum += r.events[i].value(); });
  return sum;
}

// Calls count(i) for every counting event of path p when the domain is open where
// is_open(element, point) holds (point: a CellPoint of that element).
template <typename IsOpen, typename Count>
void for_each_counting_event_in_region(const SensorRecord& r, size_t p, IsOpen is_open, Count count) {
  for_each_counting_event(
      r, p, [&](uint32_t i) { return is_open(r.events[i].element(), r.event_points[i]); },
      [&](uint32_t i) { return is_open(r.conditions[i], r.condition_points[i]); }, count);
}

// Value of path p when the domain is open where is_open(element, point) holds: the point is
// where the path met the element. With is_open(k, point) = open[k], this is path_value.
template <typename IsOpen>
double path_value_in_region(const SensorRecord& r, size_t p, IsOpen is_open) {
  return path_value_by_point(
      r, p, [&](uint32_t i) { return is_open(r.events[i].element(), r.event_points[i]); },
      [&](uint32_t i) { return is_open(r.conditions[i], r.condition_points[i]); });
}

}  // namespace fenestra
