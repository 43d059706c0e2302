#include "daylight/sun_lights.h"

#include <algorithm>
#include <cmath>

namespace fenestra {

SunLights::SunLights(std::vector<SunLight> suns) : suns_(std::move(suns)) {
  std::vector<double> weights;
  for (const SunLight& s : suns_) weights.push_back(std::max(0.0f, luminance(s.normal_illuminance)));
  if (!weights.empty()) pick_ = Distribution1D(std::move(weights));
  cos_half_angle_ = static_cast<float>(std::cos(0.5 * kAngularDiameterDeg * kPi / 180.0));
}

SunLights::Sample SunLights::sample(float u_pick, const Vec2& u_disk) const {
  Sample out;
  if (suns_.empty()) return out;
  int index = 0;
  float density = 0.0f;
  pick_.sample(u_pick, &index, &density);
  const float probability = pick_.cell_pdf(index) / static_cast<float>(pick_.size());  // density on [0,1) -> mass
  const SunLight& sun = suns_[index];
  out.index = index;
  // Uniform in the cone: cos theta uniform in [cos_half_angle, 1].
  const float cos_t = 1.0f - u_disk.x() * (1.0f - cos_half_angle_);
  const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
  const float phi = 2.0f * kPi * u_disk.y();
  const Frame frame(sun.direction);
  out.direction = frame.to_world(Vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t)).normalized();
  if (probability > 0.0f) out.illuminance = sun.normal_illuminance / probability;
  return out;
}

Rgb SunLights::horizontal_illuminance() const { return fenestra::horizontal_illuminance(suns_); }

}  // namespace fenestra
