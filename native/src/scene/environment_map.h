#pragma once
// A sky given as an equirectangular image: an environment map read from a file (with the cost of
// reading it), or a daylight sky's averaged map.
#include <memory>
#include <string>
#include <vector>

#include "daylight/sky.h"
#include "math/equirect.h"  // equirect_direction
#include "math/vec.h"
#include "sampling/distribution.h"

namespace fenestra {

// Equirectangular map as Blender's Environment Texture reads it: the top row is the zenith,
// u = 0.5 - atan2(y, x) / (2 pi) (the image centre looks along +X), rows uniform in polar angle.
// Pixels are piecewise constant; sampling follows luminance x sin(theta).
class EnvironmentMap final : public Sky {
 public:
  EnvironmentMap(int width, int height, std::vector<Rgb> pixels, float scale, float rotation_deg,
                 std::string source = "");
  static std::shared_ptr<EnvironmentMap> load(const std::string& path, float scale, float rotation_deg);

  Rgb radiance(const Vec3& dir) const override;
  Vec3 sample(const Vec2& u, float* pdf) const override;
  float pdf(const Vec3& dir) const override;
  std::string to_string() const override;

  int width() const { return width_; }
  int height() const { return height_; }
  // Map coordinates in [0,1)^2 (u across, v down from the zenith) of a world direction, and back.
  Vec2 direction_to_uv(const Vec3& dir) const;
  Vec3 uv_to_direction(const Vec2& uv) const;

 private:
  int pixel_index(const Vec2& uv) const;
  int width_, height_;
  std::vector<Rgb> pixels_;
  float scale_;
  float cos_rot_, sin_rot_;
  std::string source_;
  Distribution2D distribution_;
};

// Environment maps: at most kMaxImagePixels pixels, and their reading must fit in memory
// (the file's floats, the map, its sampling distribution: 4 x channels + 52 bytes per pixel);
// else CostError naming the figure.
inline constexpr double kMaxImagePixels = 16384.0 * 8192.0;
void check_image_cost(const std::string& path, int width, int height, int channels);

}  // namespace fenestra
