#include "trace/path_record.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace fenestra {

void SensorRecord::append(const SensorRecord& other) {
  const uint32_t event_base = static_cast<uint32_t>(events.size());
  const uint32_t condition_base = static_cast<uint32_t>(conditions.size());
  for (size_t p = 1; p < other.path_begin.size(); ++p) {
    path_begin.push_back(other.path_begin[p] + event_base);
    path_conditions_begin.push_back(other.path_conditions_begin[p] + condition_base);
  }
  events.insert(events.end(), other.events.begin(), other.events.end());
  conditions.insert(conditions.end(), other.conditions.begin(), other.conditions.end());
  event_points.insert(event_points.end(), other.event_points.begin(), other.event_points.end());
  condition_points.insert(condition_points.end(), other.condition_points.begin(), other.condition_points.end());
  sourced = sourced || other.sourced;
  event_sources.insert(event_sources.end(), other.event_sources.begin(), other.event_sources.end());
  event_coefficients.insert(event_coefficients.end(), other.event_coefficients.begin(), other.event_coefficients.end());
}

void SensorRecord::reserve_for(const SensorRecord* parts, size_t count) {
  size_t paths = path_begin.size(), event_count = events.size(), condition_count = conditions.size();
  size_t sources = event_sources.size(), coefficients = event_coefficients.size();
  for (size_t i = 0; i < count; ++i) {
    paths += parts[i].path_count();
    event_count += parts[i].events.size();
    condition_count += parts[i].conditions.size();
    sources += parts[i].event_sources.size();
    coefficients += parts[i].event_coefficients.size();
  }
  path_begin.reserve(paths);
  path_conditions_begin.reserve(paths);
  events.reserve(event_count);
  event_points.reserve(event_count);
  conditions.reserve(condition_count);
  condition_points.reserve(condition_count);
  event_sources.reserve(sources);
  event_coefficients.reserve(coefficients);
}

void SensorRecord::add_light(float value, const MetElement* open, size_t open_count, const MetElement* closed,
                             size_t closed_count) {
  if (open_count == 1 && closed_count == 0) {  // the commonest: kept in the event itself
    const uint8_t flags = PathEvent::kLight | PathEvent::kOwnCondition;
    events.push_back(PathEvent::make(value, open[0].element, flags, dither_of_next(value, open[0].element, flags)));
    event_points.push_back(open[0].point);
    return;
  }
  add_event(value, -1, PathEvent::kLight, open, open_count, closed, closed_count);
  event_points.push_back({});
}

void SensorRecord::add_escape(float value, const MetElement& at, bool part, const MetElement* open, size_t open_count,
                              const MetElement* closed, size_t closed_count) {
  add_event(value, at.element, part ? PathEvent::kEscapePart : uint8_t(0), open, open_count, closed, closed_count);
  event_points.push_back(at.point);
}

void SensorRecord::add_event(float value, int32_t element, uint8_t flags, const MetElement* open, size_t open_count,
                             const MetElement* closed, size_t closed_count) {
  if (open_count > 0xFF || closed_count > 0xFF) throw std::logic_error("SensorRecord: more than 255 conditions of a kind");
  if (element >= PathEvent::kMaxElements) throw std::logic_error("SensorRecord: element id beyond 24 bits");
  if (open_count + closed_count == 0) {
    events.push_back(PathEvent::make(value, element, flags, dither_of_next(value, element, flags)));
    return;
  }
  flags |= PathEvent::kStoredConditions;
  events.push_back(PathEvent::make(value, element, flags, dither_of_next(value, element, flags)));
  conditions.push_back(static_cast<int32_t>(open_count | closed_count << 8));  // the header
  condition_points.push_back({});
  for (const auto& [list, count] : {std::pair{open, open_count}, std::pair{closed, closed_count}})
    for (size_t i = 0; i < count; ++i) {
      conditions.push_back(list[i].element);
      condition_points.push_back(list[i].point);
    }
}

uint32_t SensorRecord::dither_of_next(float value, int32_t element, uint8_t flags) const {
  // The path and the event's place in it, not in the record: records built in pieces round alike.
  const uint64_t place = events.size() - path_begin.back();
  const uint64_t event = place << 40 | static_cast<uint64_t>(flags) << 32 | static_cast<uint32_t>(element);
  return event_dither(value, event ^ (path_key * 0x9E3779B97F4A7C15ULL));
}

bool SensorRecord::holds(const EventConditions& c, const std::vector<uint8_t>& open) {
  for (int i = 0; i < c.open; ++i)
    if (!open[c[i]]) return false;
  for (int i = c.open; i < c.count(); ++i)
    if (open[c[i]]) return false;
  return true;
}

void path_elements(const SensorRecord& r, size_t p, std::vector<int32_t>* out) {
  out->clear();
  r.walk(p, [&](uint32_t, const PathEvent& e, const EventConditions& c) {
    if (!e.is_light()) out->push_back(e.element());
    for (int i = 0; i < c.count(); ++i) out->push_back(c[i]);
    return true;
  });
  std::sort(out->begin(), out->end());
  out->erase(std::unique(out->begin(), out->end()), out->end());
}

double path_value(const SensorRecord& record, size_t p, const std::vector<uint8_t>& open) {
  return path_value_by_point(
      record, p, [&](uint32_t i) { return open[record.events[i].element()] != 0; },
      [&](uint32_t j) { return open[record.conditions[j]] != 0; });
}

}  // namespace fenestra
