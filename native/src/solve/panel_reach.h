#pragma once
// Which sensors a change of openings on a panel can change: those whose path records met one of
// the panel's elements (an event there, or a condition naming one). A sensor in another room,
// whose paths never reach the panel, traces the same paths bit for bit whatever its openings (every
// path has random numbers of its own), so a cut that changes only that panel's openings need not
// trace it again. The cuts that rank and choose openings in thick walls trace only these sensors
// and keep the others' values; the cuts that judge and check the answer trace every sensor.
#include <cstddef>
#include <vector>

#include "scene/opening_domain.h"
#include "trace/contributions.h"

namespace fenestra {

class PanelReach {
 public:
  // Every sensor for every panel (the records are elsewhere, or not kept).
  PanelReach() = default;
  // From the records of `c` (every sensor for every panel when it holds none).
  PanelReach(const Contributions& c, const OpeningDomain& domain);

  // The sensors (ascending) that a change on any of `panels` can change; every sensor when that
  // is not known.
  std::vector<size_t> sensors(const std::vector<int>& panels, size_t sensor_count) const;

 private:
  std::vector<std::vector<uint8_t>> reaches_;  // [sensor][panel]; empty: not known
};

}  // namespace fenestra
