#include "solve/change_reach.h"

#include <algorithm>
#include <cmath>

#include "trace/parallel.h"
#include "trace/path_record.h"

namespace fenestra {
namespace {

// The area of element e's cell that `rects` cover (rectangles of one set do not overlap).
double covered(const Element& e, const std::vector<PanelRectangle>& rects) {
  double area = 0.0;
  for (const PanelRectangle& r : rects) {
    if (r.panel != e.panel) continue;
    const double w = std::min<double>(e.u1, r.u1) - std::max<double>(e.u0, r.u0);
    const double h = std::min<double>(e.v1, r.v1) - std::max<double>(e.v0, r.v0);
    if (w > 0.0 && h > 0.0) area += w * h;
  }
  return area;
}

}  // namespace

ChangeReach::ChangeReach(const Contributions& c, const OpeningDomain& domain) {
  const size_t sensors = c.records.size(), elements = domain.element_count();
  // A shard's worker keeps only the records (keep_records_only): E is then empty.
  if (sensors == 0 || (c.E.rows() != 0 && static_cast<Eigen::Index>(sensors) != c.E.rows())) return;
  met_.assign(sensors, std::vector<uint8_t>(elements, 0));
  for_each_sensor(sensors, nullptr, [&](size_t i) {
    const SensorRecord& r = c.records[i];
    std::vector<int32_t> met;
    for (size_t p = 0; p < r.path_count(); ++p) {
      path_elements(r, p, &met);
      for (int32_t k : met)
        if (k >= 0 && static_cast<size_t>(k) < elements) met_[i][static_cast<size_t>(k)] = 1;
    }
  });
}

std::vector<size_t> ChangeReach::sensors(const std::vector<int32_t>& elements, size_t sensor_count) const {
  std::vector<size_t> out;
  for (size_t i = 0; i < sensor_count; ++i) {
    bool reached = met_.size() != sensor_count;  // not known: every sensor
    for (size_t n = 0; n < elements.size() && !reached; ++n) {
      const int32_t k = elements[n];
      reached = k < 0 || static_cast<size_t>(k) >= met_[i].size() || met_[i][static_cast<size_t>(k)] != 0;
    }
    if (reached) out.push_back(i);
  }
  return out;
}

size_t ChangeReach::memory_bytes() const {
  size_t bytes = 0;
  for (const std::vector<uint8_t>& m : met_) bytes += m.capacity();
  return bytes;
}

std::vector<int32_t> elements_near_change(const OpeningDomain& domain, const std::vector<PanelRectangle>& before,
                                          const std::vector<PanelRectangle>& after) {
  std::vector<uint8_t> near(domain.element_count(), 0);
  for (size_t k = 0; k < domain.element_count(); ++k) {
    const Element& e = domain.elements()[k];
    const double cell = static_cast<double>(e.width()) * e.height();
    if (!(std::abs(covered(e, before) - covered(e, after)) > 1e-9 * cell)) continue;
    const Panel& panel = domain.panels()[static_cast<size_t>(e.panel)];
    for (int row = e.row - 1; row <= e.row + 1; ++row)
      for (int col = e.col - 1; col <= e.col + 1; ++col)
        if (row >= 0 && col >= 0 && row < panel.rows && col < panel.cols) {
          const int n = panel.grid[static_cast<size_t>(row) * panel.cols + col];
          if (n >= 0) near[static_cast<size_t>(n)] = 1;
        }
  }
  std::vector<int32_t> out;
  for (size_t k = 0; k < near.size(); ++k)
    if (near[k]) out.push_back(static_cast<int32_t>(k));
  return out;
}

}  // namespace fenestra
