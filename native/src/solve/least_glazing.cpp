#include "solve/least_glazing.h"

#include <algorithm>

namespace fenestra {

std::vector<size_t> passing_by_glazing(const std::vector<GlazingCandidate>& candidates) {
  std::vector<size_t> order;
  for (size_t i = 0; i < candidates.size(); ++i)
    if (candidates[i].meets) order.push_back(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return candidates[a].area_m2 < candidates[b].area_m2; });
  return order;
}

}  // namespace fenestra
