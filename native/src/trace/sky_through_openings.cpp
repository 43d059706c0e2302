#include "trace/sky_through_openings.h"

#include <limits>

namespace fenestra {

float SkyThroughOpenings::pdf(const Vec3& x, const Vec3& n, const Vec3& dir) const {
  bool candidates = false;
  const float through = openings_.pdf(x, n, dir, std::numeric_limits<float>::infinity(), &candidates);
  const float sky = sky_->pdf_toward(dir, n);
  return candidates ? kSkyShare * sky + (1.0f - kSkyShare) * through : sky;
}

bool SkyThroughOpenings::sample(const Vec3& x, const Vec3& n, const Vec2& u, float u_pick, Vec3* dir,
                                float* pdf_out) const {
  if (!openings_.candidates(x, n)) {
    *dir = sky_->sample_toward(u, n, pdf_out);
    return *pdf_out > 0.0f;
  }
  // u.x chooses the strategy and, rescaled, stays uniform for the one chosen.
  if (u.x() < kSkyShare) {
    float sky_pdf = 0.0f;
    *dir = sky_->sample_toward(Vec2(u.x() / kSkyShare, u.y()), n, &sky_pdf);
    if (!(sky_pdf > 0.0f)) return false;
  } else {
    OpeningPortals::Sample drawn;
    if (!openings_.sample(x, n, u_pick, Vec2((u.x() - kSkyShare) / (1.0f - kSkyShare), u.y()), &drawn)) return false;
    *dir = drawn.direction;
  }
  *pdf_out = pdf(x, n, *dir);
  return *pdf_out > 0.0f;
}

}  // namespace fenestra
