#include "trace/record_sink.h"

#include <algorithm>
#include <cmath>

namespace fenestra {

std::string dropped_warning(const DropCounts& d) {
  if (!d.any()) return "";
  std::string parts;
  if (d.non_finite > 0)
    parts = std::to_string(d.non_finite) + " light value" + (d.non_finite == 1 ? "" : "s") +
            " that were not finite numbers (NaN or infinite radiance: check the sky and the materials)";
  if (d.truncated_conditions > 0)
    parts += (parts.empty() ? "" : " and ") + std::to_string(d.truncated_conditions) + " light value" +
             (d.truncated_conditions == 1 ? "" : "s") + " or sub-path" + (d.truncated_conditions == 1 ? "" : "s") +
             " that met more than " + std::to_string(RecordSink::kMaxConditions) +
             " elements outside the room (stacked panels of the opening domain, or a fine element grid in a thick "
             "wall)";
  return "the tracer left out " + parts + "; the results do not count them (\"dropped\" in the output)";
}

void RecordSink::light(float v, const Crossing* crossed, int count, uint16_t source) {
  if (!std::isfinite(v)) {
    ++dropped_.non_finite;
    return;
  }
  if (!(v > 0.0f)) return;
  Part& current = parts_[current_];
  if (record_) {
    push(v, -1, {}, 0, crossed, count, nullptr, 0, source);
  } else if (by_source_ && count == 0) {
    by_source_->push_back({source, v});
  } else if (count == 0 && (current.source == source || current.value == 0.0)) {
    current.value += v;
    current.source = source;
  } else if (condition_count() + count <= kMaxConditions) {
    // Outside, a shadow ray through other elements: light that needs them open as well (or, in
    // an annual pass, light of another source under the same conditions).
    Part part = current;
    part.value = v;
    part.source = source;
    auto closed = part.conditions.begin() + part.open_count;
    std::copy_backward(closed, closed + part.closed_count, closed + part.closed_count + count);
    std::copy(crossed, crossed + count, closed);
    part.open_count += static_cast<uint8_t>(count);
    parts_.push_back(part);
  } else {
    ++dropped_.truncated_conditions;
  }
}

RecordSink RecordSink::passing(const Crossing& j, bool through_face) const {
  RecordSink child = RecordSink::outside();
  Part& part = child.parts_[0];
  part = parts_[current_];
  part.value = 0.0;
  if (through_face) ++part.passes;
  auto closed = part.conditions.begin() + part.open_count;  // open conditions stay first
  std::copy_backward(closed, closed + part.closed_count, closed + part.closed_count + 1);
  part.conditions[part.open_count++] = j;
  return child;
}

void RecordSink::absorb(const RecordSink& child) {
  for (const Part& part : child.parts_)
    if (part.value != 0.0) parts_.push_back(part);
  dropped_ += child.dropped_;
}

bool RecordSink::reflect_off(const Crossing& j) {
  if (condition_count() >= kMaxConditions) {
    ++dropped_.truncated_conditions;
    return false;
  }
  Part next = parts_[current_];
  next.value = 0.0;
  next.conditions[next.open_count + next.closed_count++] = j;
  parts_.push_back(next);
  current_ = parts_.size() - 1;
  return true;
}

void RecordSink::escape(const Crossing& k, const RecordSink& outside) {
  dropped_ += outside.dropped_;
  push(finite(outside.parts_[0].value), k.element, k.point, 0, nullptr, 0, nullptr, 0, outside.parts_[0].source);
  for (size_t n = 1; n < outside.parts_.size(); ++n) {
    const Part& part = outside.parts_[n];
    if (part.value == 0.0) continue;
    push(finite(part.value), k.element, k.point, PathEvent::kEscapePart, part.conditions.data(), part.open_count,
         part.conditions.data() + part.open_count, part.closed_count, part.source);
  }
}

void RecordSink::light_through(const Crossing& k, const RecordSink& outside) {
  dropped_ += outside.dropped_;
  for (const Part& part : outside.parts_) {
    if (!std::isfinite(part.value)) {
      ++dropped_.non_finite;
      continue;
    }
    if (!(part.value > 0.0)) continue;
    std::array<Crossing, kMaxConditions + 1> open;
    open[0] = k;
    std::copy(part.conditions.begin(), part.conditions.begin() + part.open_count, open.begin() + 1);
    push(static_cast<float>(part.value), -1, {}, 0, open.data(), part.open_count + 1,
         part.conditions.data() + part.open_count, part.closed_count, part.source);
  }
}

float RecordSink::finite(double v) {
  if (std::isfinite(v)) return static_cast<float>(v);
  ++dropped_.non_finite;
  return 0.0f;
}

void RecordSink::push(float v, int element, const PanelPoint& at, uint8_t flags, const Crossing* open,
                      size_t open_count, const Crossing* closed, size_t closed_count, uint16_t source) {
  static_assert(kMaxCrossed <= kMaxConditions + 1, "a shadow ray's crossings must fit an event's conditions");
  std::array<MetElement, kMaxConditions + 1> met;
  for (size_t i = 0; i < open_count; ++i) met[i] = this->met(open[i]);
  for (size_t i = 0; i < closed_count; ++i) met[open_count + i] = this->met(closed[i]);
  if (element < 0)
    record_->add_light(v, met.data(), open_count, met.data() + open_count, closed_count);
  else
    record_->add_escape(v, this->met({element, at}), flags & PathEvent::kEscapePart, met.data(), open_count,
                        met.data() + open_count, closed_count);
  if (record_->sourced) record_->event_sources.push_back(source);
}

}  // namespace fenestra
