#pragma once
// The sun as explicit directional sources: one disk per time step of the sky's interval, each
// carrying its share of the interval's direct sunlight. Sampled by next-event estimation only
// (the environment map holds the sky without the sun, so no other strategy ever finds them).
#include <vector>

#include "daylight/sun_light.h"  // SunLight
#include "math/vec.h"
#include "sampling/distribution.h"

namespace fenestra {

class SunLights {
 public:
  static constexpr double kAngularDiameterDeg = 0.53;

  SunLights() = default;
  explicit SunLights(std::vector<SunLight> suns);

  bool empty() const { return suns_.empty(); }
  const std::vector<SunLight>& suns() const { return suns_; }

  struct Sample {
    Vec3 direction;                // a uniform direction within the chosen sun's disk
    Rgb illuminance = Rgb::Zero(); // its normal illuminance divided by the probability of the choice
    int index = -1;                // which sun
  };
  // Picks a sun in proportion to its normal illuminance, then a direction in its disk (soft shadows).
  Sample sample(float u_pick, const Vec2& u_disk) const;
  // Illuminance on an unobstructed horizontal surface (lux per channel).
  Rgb horizontal_illuminance() const;

 private:
  std::vector<SunLight> suns_;
  Distribution1D pick_;
  float cos_half_angle_ = 1.0f;
};

}  // namespace fenestra
