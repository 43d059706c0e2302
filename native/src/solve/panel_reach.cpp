#include "solve/panel_reach.h"

#include "trace/parallel.h"
#include "trace/path_record.h"

namespace fenestra {

PanelReach::PanelReach(const Contributions& c, const OpeningDomain& domain) {
  const size_t sensors = c.records.size();
  if (sensors == 0 || static_cast<Eigen::Index>(sensors) != c.E.rows()) return;
  const size_t panels = domain.panels().size();
  reaches_.assign(sensors, std::vector<uint8_t>(panels, 0));
  for_each_sensor(sensors, nullptr, [&](size_t i) {
    const SensorRecord& r = c.records[i];
    std::vector<int32_t> met;
    for (size_t p = 0; p < r.path_count(); ++p) {
      path_elements(r, p, &met);
      for (int32_t k : met)
        if (k >= 0 && static_cast<size_t>(k) < domain.element_count())
          reaches_[i][static_cast<size_t>(domain.elements()[static_cast<size_t>(k)].panel)] = 1;
    }
  });
}

std::vector<size_t> PanelReach::sensors(const std::vector<int>& panels, size_t sensor_count) const {
  std::vector<size_t> out;
  for (size_t i = 0; i < sensor_count; ++i) {
    bool reached = reaches_.size() != sensor_count;  // not known: every sensor
    for (size_t k = 0; k < panels.size() && !reached; ++k)
      reached = panels[k] < 0 || static_cast<size_t>(panels[k]) >= reaches_[i].size() ||
                reaches_[i][static_cast<size_t>(panels[k])] != 0;
    if (reached) out.push_back(i);
  }
  return out;
}

}  // namespace fenestra
