#include "trace/path_record.h"

#include <algorithm>

namespace fenestra {

void SensorRecord::append(const SensorRecord& other) {
  const uint32_t event_base = static_cast<uint32_t>(events.size());
  const uint32_t condition_base = static_cast<uint32_t>(conditions.size());
  for (size_t p = 1; p < other.path_begin.size(); ++p) path_begin.push_back(other.path_begin[p] + event_base);
  for (PathEvent e : other.events) {
    e.conditions_begin += condition_base;
    events.push_back(e);
  }
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
  events.reserve(event_count);
  event_points.reserve(event_count);
  conditions.reserve(condition_count);
  condition_points.reserve(condition_count);
  event_sources.reserve(sources);
  event_coefficients.reserve(coefficients);
}

bool SensorRecord::holds(const PathEvent& e, const std::vector<uint8_t>& open) const {
  const int32_t* c = conditions.data() + e.conditions_begin;
  for (uint16_t i = 0; i < e.open_count; ++i)
    if (!open[c[i]]) return false;
  for (uint16_t i = 0; i < e.closed_count; ++i)
    if (open[c[e.open_count + i]]) return false;
  return true;
}

void path_elements(const SensorRecord& r, size_t p, std::vector<int32_t>* out) {
  out->clear();
  for (uint32_t i = r.path_begin[p]; i < r.path_begin[p + 1]; ++i) {
    const PathEvent& e = r.events[i];
    if (e.element >= 0) out->push_back(e.element);
    const int32_t* c = r.conditions.data() + e.conditions_begin;
    out->insert(out->end(), c, c + e.open_count + e.closed_count);
  }
  std::sort(out->begin(), out->end());
  out->erase(std::unique(out->begin(), out->end()), out->end());
}

double path_value(const SensorRecord& record, size_t p, const std::vector<uint8_t>& open) {
  double sum = 0.0;
  const uint32_t end = record.path_begin[p + 1];
  for (uint32_t i = record.path_begin[p]; i < end; ++i) {
    const PathEvent& e = record.events[i];
    if (e.is_light()) {
      if (record.holds(e, open)) sum += e.value;
    } else if (e.is_escape() && open[e.element]) {
      sum += e.value;
      for (uint32_t j = i + 1; j < end && record.events[j].is_escape_part(); ++j)
        if (record.holds(record.events[j], open)) sum += record.events[j].value;
      return sum;
    }
  }
  return sum;
}

}  // namespace fenestra
