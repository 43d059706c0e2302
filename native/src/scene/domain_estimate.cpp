#include "scene/domain_estimate.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "math/panel_axes.h"
#include "scene/element_size_hint.h"
#include "scene/mesh.h"
#include "scene/opening_domain.h"
#include "util/byte_size.h"
#include "util/cost_context.h"
#include "util/cost_error.h"
#include "util/memory_limit.h"

namespace fenestra {
namespace {

// Element (scene/opening_domain.h) with the vector's spare capacity, per element; int per grid cell.
constexpr double kDomainBytesPerElement = 2.0 * sizeof(Element), kDomainBytesPerCell = sizeof(int);
// A domain this large is probably not in meters.
constexpr double kSuspiciousSide = 1000.0;

}  // namespace

DomainEstimate estimate_domain(const Mesh& mesh, const std::vector<std::vector<uint32_t>>& panels, float element_size) {
  DomainEstimate out;
  const double s = element_size;
  for (const auto& tris : panels) {
    if (tris.empty()) continue;
    Vec3 n = Vec3::Zero();
    for (uint32_t t : tris) n += mesh.area_normal(t);
    const double area = 0.5 * n.norm();
    if (!(n.norm() > 0.0f)) continue;
    n.normalize();
    Vec3 u, v;
    panel_axes(n, &u, &v);
    const Vec3 o = mesh.vertex(tris.front(), 0);
    double amin = HUGE_VAL, amax = -HUGE_VAL, bmin = HUGE_VAL, bmax = -HUGE_VAL;
    for (uint32_t t : tris)
      for (int k = 0; k < 3; ++k) {
        const Vec3 d = mesh.vertex(t, k) - o;
        const double a = d.dot(u), b = d.dot(v);
        amin = std::min(amin, a), amax = std::max(amax, a), bmin = std::min(bmin, b), bmax = std::max(bmax, b);
      }
    const double cells = std::floor((amax - amin) / s + 1e-4) * std::floor((bmax - bmin) / s + 1e-4);
    out.grid_cells += cells;
    out.elements += std::min(cells, area / (s * s));
    out.largest_side = std::max({out.largest_side, amax - amin, bmax - bmin});
  }
  return out;
}

void check_domain_cost(const DomainEstimate& estimate, float element_size) {
  const MemoryLimit limit = memory_limit();
  const double N = estimate.elements;
  const double domain = kDomainBytesPerElement * N + kDomainBytesPerCell * estimate.grid_cells;
  const bool matrices = needs_element_matrices(cost_context().command);
  const double t = matrices ? 8.0 * N * N : 0.0;
  const double total = domain + 2.0 * t;  // T, and as much again as a margin (cost_model.cpp)
  const bool too_many = N > kMaxElements;
  if (!(total > static_cast<double>(limit.bytes)) && !too_many) return;
  const double cells_per_element = N > 0.0 ? estimate.grid_cells / N : 0.0;
  const double fits = element_size_that_fits(
      element_size, N,
      [&](double n) {
        return (kDomainBytesPerElement + kDomainBytesPerCell * cells_per_element) * n + (matrices ? 16.0 * n * n : 0.0);
      },
      static_cast<double>(limit.bytes), kMaxElements);
  std::ostringstream s;
  s << "element_size " << element_size << " m gives about " << format_count(N, 3) << " elements";
  if (estimate.largest_side > kSuspiciousSide)
    s << " (a panel of the opening domain is " << format_count(estimate.largest_side, 3)
      << " m long: is the geometry in millimetres? OBJ coordinates are read as meters)";
  s << "; ";
  const std::string setting = larger_element_size(fits);
  if (too_many && !(total > static_cast<double>(limit.bytes)))
    s << "at most " << format_count(kMaxElements) << " elements are diced (about 1 us each; their matrix T alone would need "
      << format_bytes(8.0 * kMaxElements * kMaxElements) << "): use " << setting;
  else if (t >= domain)
    s << memory_refusal("the error-compensation matrix T alone", t, total, limit, setting);
  else
    s << memory_refusal("the opening domain's grid", domain, total, limit, setting);
  throw CostError(s.str());
}

}  // namespace fenestra
