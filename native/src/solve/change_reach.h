#pragma once
// Which sensors a change of openings can change: those whose path records met an element near
// it. Every path of a cut has random numbers of its own (seeded by its sensor and its index), so a
// sensor whose paths never come near the change bounces along the same paths whatever the
// openings, and finds the same light within the noise (its sky samples, aimed at every opening,
// are drawn anew): a cut need trace only the sensors a change can reach and keep the others' values.
// The records hold more paths per sensor than a cut and list every element a path met (from
// either face, through any tube, or named by a condition), so a sensor none of whose records came
// near a change seldom has a cut path that does.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "scene/opening_domain.h"
#include "trace/contributions.h"
#include "trace/open_region.h"

namespace fenestra {

class ChangeReach {
 public:
  // Every sensor reaches every element (the records are elsewhere, or not kept).
  ChangeReach() = default;
  // From the records of `c` (as the default when it holds none).
  ChangeReach(const Contributions& c, const OpeningDomain& domain);

  // The sensors (ascending, of `sensor_count`) whose records met any of `elements`; every sensor
  // when that is not known.
  std::vector<size_t> sensors(const std::vector<int32_t>& elements, size_t sensor_count) const;

  size_t memory_bytes() const;

 private:
  std::vector<std::vector<uint8_t>> met_;  // [sensor][element]; empty: not known
};

// The elements whose cells `before` and `after` cover differently, with their neighbours on the
// grid (a side's reveal in a thick wall lies on its cell's edge), ascending.
std::vector<int32_t> elements_near_change(const OpeningDomain& domain, const std::vector<PanelRectangle>& before,
                                          const std::vector<PanelRectangle>& after);

}  // namespace fenestra
