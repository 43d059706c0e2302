#include "trace/flip_effects.h"


#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "trace/parallel.h"
#include "util/progress.h"

namespace fenestra {
namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// What flipping element k does to one event's conditions: the event's value gained or lost, where
// it sits (its own index for light, its escape's for an escape part).
struct FlipChange {
  int32_t element;
  uint32_t at;
  bool part;
  double delta;
};

// Whether condition i names an element no earlier condition does.
bool first_occurrence(const EventConditions& c, int i) {
  for (int j = 0; j < i; ++j)
    if (c[j] == c[i]) return false;
  return true;
}

// Changes of event e (value v) under single flips, appended to out: when its conditions hold,
// flipping any of their elements breaks them; when they fail only on one element, every
// occurrence of it failing, flipping that element makes them hold.
void event_changes(const PathEvent& e, const EventConditions& c, const std::vector<uint8_t>& open, uint32_t at,
                   bool part, std::vector<FlipChange>* out) {
  const int n = c.count();
  auto satisfied = [&](int i) { return (open[c[i]] != 0) == (i < c.open); };
  int32_t failing = -1;
  bool other_failing = false;
  for (int i = 0; i < n && !other_failing; ++i)
    if (!satisfied(i)) {
      if (failing < 0) failing = c[i];
      else other_failing = c[i] != failing;
    }
  if (failing < 0) {  // holds: lost when any of its elements flips
    for (int i = 0; i < n; ++i)
      if (first_occurrence(c, i)) out->push_back({c[i], at, part, -static_cast<double>(e.value())});
    return;
  }
  if (other_failing) return;
  for (int i = 0; i < n; ++i)
    if (c[i] == failing && satisfied(i)) return;  // flipping it would break this occurrence
  out->push_back({failing, at, part, static_cast<double>(e.value())});
}

// One path's flip effects, added to `row` (indexed by element): value with k flipped minus value.
class PathFlips {
 public:
  void add(const SensorRecord& r, size_t p, const std::vector<uint8_t>& open, double* row) {
    read(r, p, open);
    const double base = value_with_cutoff(first_open_);
    std::sort(changes_.begin(), changes_.end(), [](const FlipChange& a, const FlipChange& b) { return a.element < b.element; });
    std::sort(escapes_.begin(), escapes_.end(), [](const Escape& a, const Escape& b) {
      return a.element != b.element ? a.element < b.element : a.at < b.at;
    });
    // Every element the path depends on: in the changes, or an escape's.
    size_t ci = 0, ei = 0;
    while (ci < changes_.size() || ei < escapes_.size()) {
      const int32_t k = std::min(ci < changes_.size() ? changes_[ci].element : std::numeric_limits<int32_t>::max(),
                                 ei < escapes_.size() ? escapes_[ei].element : std::numeric_limits<int32_t>::max());
      const size_t c_end = std::find_if(changes_.begin() + ci, changes_.end(), [&](const FlipChange& f) { return f.element != k; }) - changes_.begin();
      uint32_t first_of_k = kNone;  // the first escape through k (escapes_ sorted by element, then order)
      for (; ei < escapes_.size() && escapes_[ei].element == k; ++ei) first_of_k = std::min(first_of_k, escapes_[ei].at);
      const uint32_t cutoff = cutoff_with_flip(k, first_of_k, open);
      double v = value_with_cutoff(cutoff);
      for (size_t i = ci; i < c_end; ++i) {
        const FlipChange& f = changes_[i];
        if (f.part ? f.at == cutoff : f.at < cutoff) v += f.delta;
      }
      row[k] += v - base;
      ci = c_end;
    }
  }

 private:
  struct Escape {
    int32_t element;
    uint32_t at;  // event index within the path
  };

  void read(const SensorRecord& r, size_t p, const std::vector<uint8_t>& open) {
    changes_.clear();
    escapes_.clear();
    order_.clear();
    light_before_.clear();
    escape_value_.clear();
    first_open_ = kNone, first_open_element_ = -1;
    const uint32_t b = r.path_begin[p];
    double light = 0.0;
    uint32_t escape = kNone;  // the escape the parts that follow belong to
    r.walk(p, [&](uint32_t i, const PathEvent& e, const EventConditions& c) {
      const uint32_t at = i - b;
      if (e.is_light()) {
        escape = kNone;
        if (SensorRecord::holds(c, open)) light += e.value();
        event_changes(e, c, open, at, false, &changes_);
      } else if (e.is_escape()) {
        escape = at;
        escapes_.push_back({e.element(), at});
        order_.push_back({e.element(), at});
        light_before_.push_back(light);
        escape_value_.push_back(e.value());
        if (first_open_ == kNone && open[e.element()]) first_open_ = at, first_open_element_ = e.element();
      } else if (escape != kNone) {  // a part of the escape before it
        if (SensorRecord::holds(c, open)) escape_value_.back() += e.value();
        event_changes(e, c, open, escape, true, &changes_);
      }
      return true;
    });
    total_light_ = light;
  }

  // The escape a path leaves through when element k flips (kNone: none): first_of_k is k's first
  // escape in path order, if any.
  uint32_t cutoff_with_flip(int32_t k, uint32_t first_of_k, const std::vector<uint8_t>& open) const {
    if (first_of_k == kNone) return first_open_;
    if (!open[k]) return std::min(first_open_, first_of_k);  // k opens
    if (first_open_ == kNone || first_open_element_ != k) return first_open_;
    for (const Escape& e : order_)  // k closes, and the path left through it: the next open escape
      if (e.at > first_open_ && e.element != k && open[e.element]) return e.at;
    return kNone;
  }
  // Light before the cutoff plus the cutoff escape's value and its parts' (with the base state's
  // conditions); the changes are added by the caller.
  double value_with_cutoff(uint32_t cutoff) const {
    if (cutoff == kNone) return total_light_;
    for (size_t j = 0; j < order_.size(); ++j)
      if (order_[j].at == cutoff) return light_before_[j] + escape_value_[j];
    return total_light_;
  }

  std::vector<FlipChange> changes_;
  std::vector<Escape> escapes_, order_;   // escapes sorted by element, and in path order
  std::vector<double> light_before_, escape_value_;  // per escape in path order
  double total_light_ = 0.0;
  uint32_t first_open_ = kNone;  // the escape the path leaves through, and its element
  int32_t first_open_element_ = -1;
};

}  // namespace

Eigen::MatrixXd flip_effects(const Contributions& c, const std::vector<uint8_t>& open, const Progress* progress) {
  if (open.size() != c.element_count())
    throw std::invalid_argument("open-element mask has " + std::to_string(open.size()) + " entries, expected " +
                                std::to_string(c.element_count()));
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(c.records.size(), c.element_count());
  for_each_sensor(c.records.size(), progress, [&](size_t i) {
    const SensorRecord& r = c.records[i];
    std::vector<double> row(c.element_count(), 0.0);
    PathFlips flips;
    for (size_t p = 0; p < r.path_count(); ++p) {
      if (cancelled_at(progress, p)) return;
      flips.add(r, p, open, row.data());
    }
    for (size_t k = 0; k < row.size(); ++k)
      D(i, k) = r.path_count() > 0 ? row[k] / static_cast<double>(r.path_count()) : 0.0;
  });
  return D;
}

}  // namespace fenestra
