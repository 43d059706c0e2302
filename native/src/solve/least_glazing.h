#pragma once
// Least glazing (goals.least_glazing): of the designs a solve evaluated, the answer is the one with
// the least glass among those that meet every climate goal, so that no design shown beside it (the
// trade-off list) meets them with less.
#include <cstddef>
#include <vector>

namespace fenestra {

struct GlazingCandidate {
  double area_m2 = 0.0;  // glazing area
  bool meets = false;    // every climate goal met
};

// The candidates that meet the goals, least glass first (equal areas keep their order).
std::vector<size_t> passing_by_glazing(const std::vector<GlazingCandidate>& candidates);

}  // namespace fenestra
