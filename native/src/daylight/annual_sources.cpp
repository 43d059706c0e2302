#include "daylight/annual_sources.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fenestra {

SunClusters cluster_suns(const SkyMatrix& sky, int subdivision) {
  const SkyPatches patches(subdivision, sky.patches.north_offset_deg());
  SunClusters out;
  out.subdivision = subdivision;
  const size_t hours = sky.sun_direction.size();
  out.cluster_of_hour.assign(hours, -1);
  std::vector<int> cluster_of_patch(patches.count(), -1);
  std::vector<Eigen::Vector3d> sum;
  for (size_t h = 0; h < hours; ++h) {
    const float e = sky.sun_normal_illuminance[h];
    const Vec3& d = sky.sun_direction[h];
    if (!(e > 0.0f) || !(d.z() > 0.0f)) continue;
    const int patch = patches.patch_of(d);
    int& c = cluster_of_patch[patch];
    if (c < 0) {
      c = static_cast<int>(sum.size());
      sum.push_back(Eigen::Vector3d::Zero());
      out.energy_lux_h.push_back(0.0);
    }
    sum[c] += static_cast<double>(e) * d.cast<double>();
    out.energy_lux_h[c] += e;
    out.cluster_of_hour[h] = c;
  }
  for (const auto& s : sum) out.direction.push_back(s.normalized().cast<float>());
  double weighted = 0.0, total = 0.0;
  for (size_t h = 0; h < hours; ++h) {
    const int c = out.cluster_of_hour[h];
    if (c < 0) continue;
    const double cos = std::clamp<double>(sky.sun_direction[h].normalized().dot(out.direction[c]), -1.0, 1.0);
    const double angle = std::acos(cos) * 180.0 / 3.14159265358979323846;
    out.max_error_deg = std::max(out.max_error_deg, angle);
    weighted += sky.sun_normal_illuminance[h] * angle;
    total += sky.sun_normal_illuminance[h];
  }
  out.mean_error_deg = total > 0.0 ? weighted / total : 0.0;
  return out;
}

}  // namespace fenestra
