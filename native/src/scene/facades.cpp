#include "scene/facades.h"

#include <cmath>

namespace fenestra {
namespace {

const double kWallCosine = std::sin(30.0 * M_PI / 180.0);  // |normal.z| at most: a wall
constexpr double kPlaneTolerance = 0.01;  // meters: panels this close to one plane are one facade

}  // namespace

bool is_wall(const Panel& panel) { return std::abs(panel.normal.z()) <= kWallCosine; }

std::vector<int> facades_of(const OpeningDomain& domain) {
  std::vector<int> facade(domain.panels().size(), -1);
  std::vector<size_t> first;  // a panel of each facade
  for (size_t p = 0; p < domain.panels().size(); ++p) {
    const Panel& panel = domain.panels()[p];
    if (panel.curved() || !is_wall(panel)) continue;
    for (size_t f = 0; f < first.size() && facade[p] < 0; ++f) {
      const Panel& q = domain.panels()[first[f]];
      const bool parallel = panel.normal.dot(q.normal) > 1.0f - 1e-4f;
      const bool same_plane = std::abs(panel.normal.dot(panel.origin - q.origin)) < kPlaneTolerance;
      if (parallel && same_plane) facade[p] = static_cast<int>(f);
    }
    if (facade[p] < 0) facade[p] = static_cast<int>(first.size()), first.push_back(p);
  }
  return facade;
}

}  // namespace fenestra
