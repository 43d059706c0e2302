#pragma once
// Where a path's light goes: summed (ground truth), listed by source (ground truth of an annual
// study), recorded as events (a sensor's path, trace/path_record.h), or, for a sub-path beyond an
// element, summed by condition: light found after the sub-path went through other elements holds
// only if they are open, after reflecting off them only if closed. The integrator
// (trace/path_tracer.h) hands it light; the sink decides what is kept, and counts what it drops.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/opening_domain.h"
#include "trace/path_record.h"
#include "trace/scene_hits.h"

namespace fenestra {

// Light of one source, in an annual pass (AnnualSources index, value).
struct SourceLight {
  uint16_t source;
  double value;
};

// What the tracer dropped, as pbrt counts with its statistics: light that was not a finite number
// (NaN or infinite radiance or weight), and light or sub-paths left out because their list of
// conditions was full (RecordSink::kMaxConditions, or a shadow ray across more than kMaxCrossed
// elements). Counted per path and summed; integers, so the totals are the same for any thread count.
struct DropCounts {
  uint64_t non_finite = 0;
  uint64_t truncated_conditions = 0;

  DropCounts& operator+=(const DropCounts& o) {
    non_finite += o.non_finite;
    truncated_conditions += o.truncated_conditions;
    return *this;
  }
  bool any() const { return non_finite > 0 || truncated_conditions > 0; }
};

// The warning a front end shows when the tracer dropped anything, in the user's words; empty when
// it dropped nothing.
std::string dropped_warning(const DropCounts& dropped);

class RecordSink {
 public:
  // Conditions of one part: an oblique segment through a thick wall crosses several elements' tubes.
  static constexpr int kMaxConditions = 32;
  // Element faces (inner or outer) a sub-path may go on through, beyond its own; crossings from one
  // element's tube into its neighbour's inside the wall are limited by kMaxConditions only.
  static constexpr int kMaxPassed = 3;

  static RecordSink sum() { return RecordSink(nullptr, false); }
  // `cells`: the domain's elements, where the record keeps its points (CellPoint).
  static RecordSink record(SensorRecord* record, const std::vector<Element>* cells) {
    RecordSink sink(record, false);
    sink.cells_ = cells;
    return sink;
  }
  static RecordSink outside() { return RecordSink(nullptr, true); }
  // Closed mode, light listed by source as it arrives (an annual study with the openings cut).
  static RecordSink by_source(std::vector<SourceLight>* out) {
    RecordSink sink(nullptr, false);
    sink.by_source_ = out;
    return sink;
  }

  bool recording() const { return record_ != nullptr; }
  bool outside_element() const { return outside_; }
  // What this sink (and the sub-paths' sinks it took in) dropped.
  const DropCounts& dropped() const { return dropped_; }
  // A shadow ray that stopped at kMaxCrossed elements (Shadow::truncated).
  void count_truncated() { ++dropped_.truncated_conditions; }

  // `source`: the light's source in an annual pass (AnnualSources), else 0.
  void light(const Rgb& c, const Crossing* crossed, int count, uint16_t source) {
    light(luminance(c), crossed, count, source);
  }
  void light(float v, const Crossing* crossed, int count, uint16_t source);
  // Outside: a sub-path that went on through element j (its light needs j open), if the
  // conditions leave room; the caller traces into it and absorb()s it.
  bool can_pass(bool through_face) const {
    return condition_count() < kMaxConditions && (!through_face || parts_[current_].passes < kMaxPassed);
  }
  RecordSink passing(const Crossing& j, bool through_face) const;
  void absorb(const RecordSink& child);
  // Outside: from now on, the light found needs element j closed. Returns false when the
  // conditions are full (the caller stops: what follows is not recorded).
  bool reflect_off(const Crossing& j);
  // Recording: what `outside` found beyond element k, reached by the path (an escape) ...
  void escape(const Crossing& k, const RecordSink& outside);
  // ... or reached by a portal sample (light that needs k open).
  void light_through(const Crossing& k, const RecordSink& outside);
  double total() const {
    double t = 0.0;
    for (const Part& part : parts_) t += part.value;
    return t;
  }

 private:
  struct Part {
    double value = 0.0;
    uint8_t open_count = 0, closed_count = 0;
    uint8_t passes = 0;  // element faces gone through
    uint16_t source = 0;  // of the light it holds (annual pass)
    std::array<Crossing, kMaxConditions> conditions{};  // open ones first
  };

  RecordSink(SensorRecord* record, bool outside) : record_(record), outside_(outside), parts_(1) {}
  int condition_count() const { return parts_[current_].open_count + parts_[current_].closed_count; }
  // v as a float, 0 (and counted) when it is not finite.
  float finite(double v);
  void push(float v, int element, const PanelPoint& at, uint8_t flags, const Crossing* open, size_t open_count,
            const Crossing* closed, size_t closed_count, uint16_t source);
  MetElement met(const Crossing& c) const { return {c.element, CellPoint::of((*cells_)[c.element], c.point)}; }

  SensorRecord* record_;
  const std::vector<Element>* cells_ = nullptr;
  bool outside_;
  std::vector<SourceLight>* by_source_ = nullptr;
  std::vector<Part> parts_;  // parts_[current_] takes the light now
  size_t current_ = 0;
  DropCounts dropped_;
};

}  // namespace fenestra
