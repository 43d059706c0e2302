#pragma once
// Distant light: radiance arriving from each direction (cd/m^2 per colour channel when the
// sensor values are to be lux). Blender's world convention: +Z up. The environment map (an image,
// a daylight sky's averaged map): scene/environment_map.h.
#include <string>

#include "math/vec.h"

namespace fenestra {

class Sky {
 public:
  virtual ~Sky() = default;
  // Radiance arriving from direction `dir` (unit, pointing away from the scene).
  virtual Rgb radiance(const Vec3& dir) const = 0;
  // Importance-samples a direction; pdf in solid angle.
  virtual Vec3 sample(const Vec2& u, float* pdf) const = 0;
  virtual float pdf(const Vec3& dir) const = 0;
  // The same for light arriving at a surface with unit normal `normal`: skies that can, put the
  // samples where the cosine is (only directions with dir . normal > 0 matter there).
  virtual Vec3 sample_toward(const Vec2& u, const Vec3& /*normal*/, float* pdf) const { return sample(u, pdf); }
  virtual float pdf_toward(const Vec3& dir, const Vec3& /*normal*/) const { return pdf(dir); }
  virtual std::string to_string() const = 0;
};

class UniformSky final : public Sky {
 public:
  explicit UniformSky(const Rgb& radiance) : radiance_(radiance), ground_(radiance) {}
  // Another radiance below the horizon (z < 0): an open sky over a uniform ground, as the
  // reference room of ../shared/reference describes it, without an image.
  UniformSky(const Rgb& radiance, const Rgb& ground) : radiance_(radiance), ground_(ground) {}
  Rgb radiance(const Vec3& dir) const override { return dir.z() < 0.0f ? ground_ : radiance_; }
  Vec3 sample(const Vec2& u, float* pdf) const override;
  float pdf(const Vec3&) const override;
  // Constant radiance: cosine-weighted about the normal is the ideal light sampling.
  Vec3 sample_toward(const Vec2& u, const Vec3& normal, float* pdf) const override;
  float pdf_toward(const Vec3& dir, const Vec3& normal) const override;
  std::string to_string() const override;

 private:
  Rgb radiance_, ground_;
};

}  // namespace fenestra
