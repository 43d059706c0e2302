#pragma once
// Which element a sensor's portal sample aims at. Each element gets samples in proportion to how
// much of the sensor's view it fills (its solid angle times the sensor's cosine, with no
// occlusion), mixed with an even share of the elements it can see at all: the few elements near a
// sensor carry most of its light and of the error of E, while those far or at grazing angles get
// enough samples to keep their own entries of E honest. Elements wholly behind the sensor's plane
// get none (no light of theirs reaches it directly). Probabilities are kept as 32-bit fixed-point
// intervals, so a uniform 32-bit number picks element k with probability exactly width_k / 2^32.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "math/vec.h"

namespace fenestra {

// The corner, edges and normal of a flat element, or a probe of a curved one.
struct PortalShape {
  Vec3 corner, u, v, normal;
  bool curved = false;
  Vec3 center;  // curved: the surface point at the middle of the cell, `normal` there
  float area = 0.0f;
};

// Share of samples spread evenly over the elements a sensor sees (the rest follows the view).
constexpr double kEvenPortalShare = 0.2;

// How much of the view from (point, normal) the element fills: solid angle x mean cosine (flat),
// or area x cosines / d^2 at the centre (curved, floored so that it is never 0). Steradians.
double portal_view_weight(const Vec3& point, const Vec3& normal, const PortalShape& portal);

class PortalSelection {
 public:
  PortalSelection() = default;
  explicit PortalSelection(const std::vector<double>& weights);

  struct Choice {
    int element = -1;
    double probability = 0.0;  // of choosing it
    float remainder = 0.0f;    // where u fell within its interval, uniform in [0, 1)
  };
  Choice choose(uint32_t u) const;
  double probability(int element) const;
  size_t memory_bytes() const { return starts_.capacity() * sizeof(uint32_t); }

 private:
  uint64_t width(size_t k) const { return (k + 1 < starts_.size() ? uint64_t(starts_[k + 1]) : uint64_t(1) << 32) - starts_[k]; }
  std::vector<uint32_t> starts_;  // element k takes [starts_[k], starts_[k + 1]) of [0, 2^32)
};

}  // namespace fenestra
