#include "trace/portal_selection.h"

#include <algorithm>
#include <cmath>

#include "sampling/spherical_rectangle.h"

namespace fenestra {

double portal_view_weight(const Vec3& point, const Vec3& normal, const PortalShape& portal) {
  if (portal.curved) {
    const Vec3 d = portal.center - point;
    const double r2 = std::max(1e-8, static_cast<double>(d.squaredNorm()));
    const double cos_x = std::max(0.0, static_cast<double>(d.normalized().dot(normal)));
    const double cos_y = std::abs(static_cast<double>(d.normalized().dot(portal.normal)));
    // A curved patch may face the sensor in part only: never 0, so every part stays reachable.
    return std::max(portal.area * cos_x * cos_y / r2, 1e-9 * portal.area / r2);
  }
  const SphericalRectangle seen(point, portal.corner, portal.u, portal.v);
  if (!(seen.solid_angle() > 0.0)) return 0.0;
  const Vec3 corners[4] = {portal.corner, portal.corner + portal.u, portal.corner + portal.v,
                           portal.corner + portal.u + portal.v};
  double cosine = 0.0;
  bool in_front = false;
  for (const Vec3& c : corners) {
    const double cos = (c - point).normalized().dot(normal);
    in_front = in_front || cos > 0.0;
    cosine += std::max(0.0, cos) / 4.0;
  }
  // The cosine is linear over a flat rectangle: with no corner in front, no point is.
  if (!in_front) return 0.0;
  return seen.solid_angle() * std::max(cosine, 1e-3);
}

PortalSelection::PortalSelection(const std::vector<double>& weights) {
  const size_t n = weights.size();
  double total = 0.0;
  size_t seen = 0;
  for (const double w : weights)
    if (w > 0.0) total += w, ++seen;
  std::vector<double> p(n, 0.0);
  for (size_t k = 0; k < n; ++k) {
    if (seen == 0) p[k] = 1.0 / static_cast<double>(n);  // sees none: any choice carries no light
    else if (weights[k] > 0.0) p[k] = (1.0 - kEvenPortalShare) * weights[k] / total + kEvenPortalShare / seen;
  }
  // Fixed-point starts; every element with p > 0 keeps at least one unit.
  starts_.resize(n);
  const double scale = 4294967296.0;
  double cumulative = 0.0;
  uint64_t previous_end = 0;
  for (size_t k = 0; k < n; ++k) {
    starts_[k] = static_cast<uint32_t>(previous_end);
    cumulative += p[k];
    uint64_t end = k + 1 == n ? uint64_t(1) << 32 : static_cast<uint64_t>(std::llround(cumulative * scale));
    if (p[k] > 0.0) end = std::max(end, previous_end + 1);
    end = std::min(end, uint64_t(1) << 32);
    previous_end = end;
  }
}

PortalSelection::Choice PortalSelection::choose(uint32_t u) const {
  Choice c;
  if (starts_.empty()) return c;
  const size_t k = static_cast<size_t>(std::upper_bound(starts_.begin(), starts_.end(), u) - starts_.begin()) - 1;
  const uint64_t w = width(k);
  c.element = static_cast<int>(k);
  c.probability = static_cast<double>(w) / 4294967296.0;
  c.remainder = std::min(static_cast<float>(static_cast<double>(u - starts_[k]) / static_cast<double>(w)), 0.99999994f);
  return c;
}

double PortalSelection::probability(int element) const {
  return static_cast<double>(width(static_cast<size_t>(element))) / 4294967296.0;
}

}  // namespace fenestra
