#include "daylight/sky.h"

#include <algorithm>
#include <sstream>

#include "sampling/warp.h"

namespace fenestra {

Vec3 UniformSky::sample(const Vec2& u, float* pdf) const {
  const Vec3 d = square_to_uniform_sphere(u);
  *pdf = square_to_uniform_sphere_pdf(d);
  return d;
}

float UniformSky::pdf(const Vec3& d) const { return square_to_uniform_sphere_pdf(d); }

Vec3 UniformSky::sample_toward(const Vec2& u, const Vec3& normal, float* pdf) const {
  const Vec3 local = square_to_cosine_hemisphere(u);
  *pdf = square_to_cosine_hemisphere_pdf(local);
  return Frame(normal).to_world(local);
}

float UniformSky::pdf_toward(const Vec3& dir, const Vec3& normal) const { return std::max(0.0f, dir.dot(normal)) * kInvPi; }

std::string UniformSky::to_string() const {
  std::ostringstream s;
  s << "UniformSky(radiance=[" << radiance_.transpose() << "]";
  if (!(ground_ == radiance_).all()) s << ", ground_radiance=[" << ground_.transpose() << "]";
  s << ")";
  return s.str();
}

}  // namespace fenestra
