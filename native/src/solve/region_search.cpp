#include "solve/region_search.h"

#include <algorithm>
#include <atomic>

#include "trace/parallel.h"
#include "util/progress.h"

namespace fenestra {
namespace {

// Meters added around a strip: met points are stored as floats, and a path found in excess is only
// evaluated once more, unchanged.
constexpr double kStripSlack = 1e-5;

double value_of_flags(const SensorRecord& r, size_t p, const std::vector<uint8_t>& event, const std::vector<uint8_t>& condition) {
  return path_value_by_point(r, p, [&](uint32_t i) { return event[i] != 0; }, [&](uint32_t i) { return condition[i] != 0; });
}

bool same(const PanelRectangle& a, const PanelRectangle& b) {
  return a.panel == b.panel && a.u0 == b.u0 && a.u1 == b.u1 && a.v0 == b.v0 && a.v1 == b.v1;
}

}  // namespace

std::vector<PanelRectangle> changed_strips(const PanelRectangle& a, const PanelRectangle& b) {
  if (same(a, b)) return {};
  if (a.panel != b.panel) return {a, b};
  // A point of a outside b lies beyond one of b's edges and within a's extent, so between the two
  // positions of that edge and within the union's extent across it (and the same for b).
  const double u0 = std::min(a.u0, b.u0), u1 = std::max(a.u1, b.u1);
  const double v0 = std::min(a.v0, b.v0), v1 = std::max(a.v1, b.v1);
  std::vector<PanelRectangle> out;
  auto across_u = [&](double x, double y) {
    if (x != y) out.push_back({a.panel, std::min(x, y), std::max(x, y), v0, v1});
  };
  auto across_v = [&](double x, double y) {
    if (x != y) out.push_back({a.panel, u0, u1, std::min(x, y), std::max(x, y)});
  };
  across_u(a.u0, b.u0);
  across_u(a.u1, b.u1);
  across_v(a.v0, b.v0);
  across_v(a.v1, b.v1);
  return out;
}

namespace {

// The strips between two rectangle lists: per index when they pair up, else both lists whole.
std::vector<PanelRectangle> strips_between(const std::vector<PanelRectangle>& from, const std::vector<PanelRectangle>& to) {
  std::vector<PanelRectangle> out;
  if (from.size() != to.size()) {
    out = from;
    out.insert(out.end(), to.begin(), to.end());
    return out;
  }
  for (size_t i = 0; i < from.size(); ++i) {
    const std::vector<PanelRectangle> strips = changed_strips(from[i], to[i]);
    out.insert(out.end(), strips.begin(), strips.end());
  }
  return out;
}

}  // namespace

RegionSearch::RegionSearch(const Contributions& c, const OpeningDomain& domain, const std::vector<PanelRectangle>& start,
                           const Progress* progress)
    : c_(c), domain_(domain), rectangles_(start), candidate_region_(domain, start) {
  const size_t sensors = c.records.size(), elements = c.element_count();
  path_values_.resize(sensors);
  element_begin_.resize(sensors);
  met_.resize(sensors);
  open_.resize(sensors);
  tries_.resize(sensors);
  values_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(sensors));
  const OpenRegion region(domain, start);
  for_each_sensor(sensors, progress, [&](size_t i) {
    const SensorRecord& r = c.records[i];
    std::vector<uint32_t>& begin = element_begin_[i];
    std::vector<Met>& met = met_[i];
    PointFlags& open = open_[i];
    // Every point where a path met an element: its escapes' and its conditions'.
    auto for_each_point = [&](auto visit) {
      for (size_t p = 0; p < r.path_count(); ++p) {
        if (cancelled_at(progress, p)) return;
        r.walk(p, [&](uint32_t e, const PathEvent& ev, const EventConditions& c) {
          if (ev.is_escape() || ev.own_condition()) visit(ev.element(), r.event_points[e], p, e, true);
          if (c.stored)
            for (uint32_t k = c.first; k < c.first + c.count(); ++k)
              visit(r.conditions[k], r.condition_points[k], p, k, false);
          return true;
        });
      }
    };
    if (progress && progress->cancelled()) return;
    begin.assign(elements + 1, 0);
    for_each_point([&](int32_t k, const CellPoint&, size_t, uint32_t, bool) { ++begin[k + 1]; });
    for (size_t k = 0; k < elements; ++k) begin[k + 1] += begin[k];
    met.resize(begin[elements]);
    open.event.assign(r.events.size(), 0);
    open.condition.assign(r.conditions.size(), 0);
    std::vector<uint32_t> next(begin.begin(), begin.end() - 1);
    for_each_point([&](int32_t k, const CellPoint& q, size_t p, uint32_t index, bool is_event) {
      const PanelPoint in_cell = region.point_in_cell(k, q);
      Met& m = met[next[k]++];
      m = {in_cell.u, in_cell.v, static_cast<uint32_t>(p), index, is_event};
      open.of(m) = region.is_open(k, in_cell);
    });
    for (size_t k = 0; k < elements; ++k)
      std::sort(met.begin() + begin[k], met.begin() + begin[k + 1], [](const Met& a, const Met& b) { return a.u < b.u; });
    path_values_[i].resize(r.path_count());
    double sum = 0.0;
    for (size_t p = 0; p < r.path_count(); ++p) sum += path_values_[i][p] = value_of_flags(r, p, open.event, open.condition);
    values_[static_cast<Eigen::Index>(i)] = r.path_count() ? sum / static_cast<double>(r.path_count()) : 0.0;
  });
}

template <typename Visit>
void RegionSearch::points_in(size_t sensor, const std::vector<PanelRectangle>& strips, Visit visit) const {
  const std::vector<uint32_t>& begin = element_begin_[sensor];
  const std::vector<Met>& met = met_[sensor];
  for (const PanelRectangle& s : strips) {
    const double u0 = s.u0 - kStripSlack, u1 = s.u1 + kStripSlack, v0 = s.v0 - kStripSlack, v1 = s.v1 + kStripSlack;
    const auto [c0, c1] = domain_.columns_overlapping(s.panel, u0, u1);
    const auto [r0, r1] = domain_.rows_overlapping(s.panel, v0, v1);
    for (int row = std::max(r0, 0); row <= r1; ++row)
      for (int col = std::max(c0, 0); col <= c1; ++col) {
        const int k = domain_.cell(s.panel, row, col);
        if (k < 0) continue;
        const auto first = met.begin() + begin[k], last = met.begin() + begin[k + 1];
        const auto lo = std::lower_bound(first, last, u0, [](const Met& m, double x) { return m.u < x; });
        for (auto it = lo; it != last && it->u <= u1; ++it)
          if (it->v >= v0 && it->v <= v1) visit(k, *it);
      }
  }
}

const Eigen::VectorXd& RegionSearch::try_region(const std::vector<PanelRectangle>& candidate) {
  const std::vector<PanelRectangle> strips = strips_between(rectangles_, candidate);
  candidate_ = candidate;
  candidate_values_ = values_;
  candidate_region_.set_rectangles(candidate);
  const OpenRegion& region = candidate_region_;
  std::atomic<size_t> evaluated{0};
  for_each_sensor(c_.records.size(), nullptr, [&](size_t i) {
    const SensorRecord& r = c_.records[i];
    PointFlags& open = open_[i];
    Try& t = tries_[i];
    t.flipped.clear();
    t.values.clear();
    // The points in the strips whose flag changes, flipped while the paths they belong to are
    // evaluated (and flipped back: accept() flips them again).
    std::vector<uint32_t>& paths = t.paths;
    paths.clear();
    points_in(i, strips, [&](int k, const Met& m) {
      const uint8_t now = region.is_open(k, PanelPoint{m.u, m.v});
      if (now == open.of(m)) return;
      open.of(m) = now;
      t.flipped.push_back(&m);
      paths.push_back(m.path);
    });
    std::sort(paths.begin(), paths.end());
    paths.erase(std::unique(paths.begin(), paths.end()), paths.end());
    evaluated += paths.size();
    double delta = 0.0;
    for (uint32_t p : paths) {
      const double v = value_of_flags(r, p, open.event, open.condition);
      delta += v - path_values_[i][p];
      t.values.push_back({p, v});
    }
    for (const Met* m : t.flipped) open.of(*m) ^= 1;
    if (r.path_count()) candidate_values_[static_cast<Eigen::Index>(i)] += delta / static_cast<double>(r.path_count());
  });
  paths_evaluated_ += evaluated.load();
  return candidate_values_;
}

size_t RegionSearch::memory_bytes() const {
  size_t bytes = 0;
  for (size_t i = 0; i < met_.size(); ++i)
    bytes += met_[i].capacity() * sizeof(Met) + element_begin_[i].capacity() * sizeof(uint32_t) +
             open_[i].event.capacity() + open_[i].condition.capacity() + path_values_[i].capacity() * sizeof(double);
  return bytes;
}

void RegionSearch::accept() {
  rectangles_ = candidate_;
  values_ = candidate_values_;
  for (size_t i = 0; i < tries_.size(); ++i) {
    Try& t = tries_[i];
    for (const Met* m : t.flipped) open_[i].of(*m) ^= 1;
    for (const auto& [p, v] : t.values) path_values_[i][p] = v;
    t.flipped.clear();
    t.values.clear();
  }
}

}  // namespace fenestra
