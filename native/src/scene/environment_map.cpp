#include "scene/environment_map.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "format/image_library.h"
#include "scene/input_limits.h"
#include "util/byte_size.h"
#include "util/cost_error.h"
#include "util/memory_limit.h"
#include "util/out_of_memory.h"
#include "util/quoted_text.h"

namespace fenestra {

EnvironmentMap::EnvironmentMap(int width, int height, std::vector<Rgb> pixels, float scale, float rotation_deg,
                               std::string source)
    : width_(width), height_(height), pixels_(std::move(pixels)), scale_(scale), source_(std::move(source)) {
  if (width < 1 || height < 1 || pixels_.size() != static_cast<size_t>(width) * height)
    throw std::invalid_argument("environment map " + source_ + ": pixel count does not match its size");
  if (!(std::isfinite(scale) && scale >= 0.0f))
    throw std::invalid_argument("environment map " + source_ + ": the scale must be finite and not negative");
  if (!(std::abs(rotation_deg) <= limits::kMaxTurnDeg))
    throw std::invalid_argument("environment map " + source_ + ": the rotation must lie in [-360, 360] degrees");
  const float rot = rotation_deg * kPi / 180.0f;
  cos_rot_ = std::cos(rot);
  sin_rot_ = std::sin(rot);
  std::vector<double> weights(pixels_.size());
  float brightest = 0.0f;
  for (int y = 0; y < height; ++y) {
    const double sin_theta = std::sin(kPi * (y + 0.5) / height);
    for (int x = 0; x < width; ++x) {
      const Rgb& p = pixels_[static_cast<size_t>(y) * width + x];
      if (!p.isFinite().all() || (p < 0.0f).any())
        throw std::invalid_argument("environment map " + source_ + ": negative or non-finite pixel values");
      brightest = std::max(brightest, p.maxCoeff());
      weights[static_cast<size_t>(y) * width + x] = std::max(0.0, static_cast<double>(luminance(p))) * sin_theta;
    }
  }
  // Radiance is pixel times scale, in float: bounded so that it and the estimates built on it stay finite.
  if (static_cast<double>(brightest) * scale > limits::kMaxRadiance) {
    std::ostringstream s;
    s << "environment map " << source_ << ": its brightest pixel (" << brightest << ") times the scale (" << scale
      << ") exceeds " << limits::kMaxRadiance << " cd/m^2";
    throw std::invalid_argument(s.str());
  }
  distribution_ = Distribution2D(weights, width, height);
}

std::shared_ptr<EnvironmentMap> EnvironmentMap::load(const std::string& path, float scale, float rotation_deg) {
  FloatImage image;
  try {
    // The size is checked from the header, before the pixels are allocated.
    image = out_of_memory_while("reading environment map '" + quoted_path(path) + "'", [&] {
      return read_float_image(path, [&](int width, int height, int channels) {
        if (width < 2 || height < 1) throw std::invalid_argument("environment map '" + quoted_path(path) + "' is empty");
        check_image_cost(path, width, height, channels);
      });
    });
  } catch (const ImageError& e) {
    throw std::invalid_argument("cannot read environment map '" + quoted_path(path) + "': " + e.reason());
  }
  const int w = image.width, h = image.height, channels = image.channels;
  const std::vector<float>& data = image.pixels;
  std::vector<Rgb> pixels(static_cast<size_t>(w) * h);
  for (size_t i = 0; i < pixels.size(); ++i) {
    const float* p = &data[i * channels];
    pixels[i] = channels >= 3 ? Rgb(p[0], p[1], p[2]) : Rgb::Constant(p[0]);
  }
  return std::make_shared<EnvironmentMap>(w, h, std::move(pixels), scale, rotation_deg, "'" + quoted_path(path) + "'");
}

Vec2 EnvironmentMap::direction_to_uv(const Vec3& dir) const {
  // Undo the map's rotation about +Z, then Blender's equirectangular projection.
  const float x = cos_rot_ * dir.x() + sin_rot_ * dir.y();
  const float y = -sin_rot_ * dir.x() + cos_rot_ * dir.y();
  float u = 0.5f - std::atan2(y, x) / (2.0f * kPi);
  u -= std::floor(u);
  const float v = std::acos(std::clamp(dir.z(), -1.0f, 1.0f)) / kPi;
  return Vec2(std::min(u, std::nextafter(1.0f, 0.0f)), std::min(v, std::nextafter(1.0f, 0.0f)));
}

Vec3 EnvironmentMap::uv_to_direction(const Vec2& uv) const {
  const Vec3 d = equirect_direction(uv);
  return Vec3(cos_rot_ * d.x() - sin_rot_ * d.y(), sin_rot_ * d.x() + cos_rot_ * d.y(), d.z());
}

int EnvironmentMap::pixel_index(const Vec2& uv) const {
  const int x = std::clamp(static_cast<int>(uv.x() * width_), 0, width_ - 1);
  const int y = std::clamp(static_cast<int>(uv.y() * height_), 0, height_ - 1);
  return y * width_ + x;
}

Rgb EnvironmentMap::radiance(const Vec3& dir) const { return pixels_[pixel_index(direction_to_uv(dir))] * scale_; }

Vec3 EnvironmentMap::sample(const Vec2& u, float* pdf) const {
  float pdf_uv = 0.0f;
  const Vec2 uv = distribution_.sample(u, &pdf_uv);
  const float sin_theta = std::sin(uv.y() * kPi);
  *pdf = sin_theta > 0.0f ? pdf_uv / (2.0f * kPi * kPi * sin_theta) : 0.0f;
  return uv_to_direction(uv);
}

float EnvironmentMap::pdf(const Vec3& dir) const {
  const Vec2 uv = direction_to_uv(dir);
  // sin(theta) of the direction itself: in float, sin(v * pi) with v < 1 never drops below
  // ~1.5e-7, so every direction within 2.4e-4 rad of the nadir got a pdf up to ~1000x too large.
  const float sin_theta = std::sqrt(dir.x() * dir.x() + dir.y() * dir.y());
  if (sin_theta <= 0.0f) return 0.0f;
  return distribution_.pdf(uv) / (2.0f * kPi * kPi * sin_theta);
}

std::string EnvironmentMap::to_string() const {
  std::ostringstream s;
  s << "EnvironmentMap(" << source_ << ", " << width_ << "x" << height_ << ", scale=" << scale_ << ")";
  return s.str();
}

void check_image_cost(const std::string& path, int width, int height, int channels) {
  const double pixels = static_cast<double>(width) * static_cast<double>(height);
  const double need = pixels * (4.0 * std::max(channels, 1) + 52.0);
  std::ostringstream s;
  s << "environment map '" << path << "' is " << width << " x " << height << " pixels";
  if (pixels > kMaxImagePixels) {
    s << " (" << format_count(pixels) << "; reading it would need " << format_bytes(need) << "): at most "
      << format_count(kMaxImagePixels) << " pixels (16384 x 8192) are read: use a smaller map";
    throw CostError(s.str());
  }
  const MemoryLimit limit = memory_limit();
  if (need > static_cast<double>(limit.bytes)) {
    s << "; " << memory_refusal("reading it", need, need, limit, "a smaller map");
    throw CostError(s.str());
  }
}

}  // namespace fenestra
