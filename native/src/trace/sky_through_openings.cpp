#include "trace/sky_through_openings.h"

#include <limits>

namespace fenestra {

float SkyThroughOpenings::mixture(const OpeningPortals::From& from, float sky_pdf, float through_pdf) {
  return from.any() ? kSkyShare * sky_pdf + (1.0f - kSkyShare) * through_pdf : sky_pdf;
}

float SkyThroughOpenings::pdf(const Vec3& x, const Vec3& n, const Vec3& dir) const {
  const OpeningPortals::From from(openings_, x, n);
  return mixture(from, sky_->pdf_toward(dir, n), from.pdf(dir, std::numeric_limits<float>::infinity()));
}

bool SkyThroughOpenings::sample(const Vec3& x, const Vec3& n, const Vec2& u, float u_pick, Vec3* dir,
                                float* pdf_out) const {
  const OpeningPortals::From from(openings_, x, n);
  if (!from.any()) {
    *dir = sky_->sample_toward(u, n, pdf_out);
    return *pdf_out > 0.0f;
  }
  // u.x chooses the strategy and, rescaled, stays uniform for the one chosen.
  if (u.x() < kSkyShare) {
    float sky_pdf = 0.0f;
    *dir = sky_->sample_toward(Vec2(u.x() / kSkyShare, u.y()), n, &sky_pdf);
    if (!(sky_pdf > 0.0f)) return false;
    *pdf_out = mixture(from, sky_pdf, from.pdf(*dir, std::numeric_limits<float>::infinity()));
  } else {
    OpeningPortals::Sample drawn;
    if (!from.sample(u_pick, Vec2((u.x() - kSkyShare) / (1.0f - kSkyShare), u.y()), &drawn)) return false;
    *dir = drawn.direction;
    *pdf_out = mixture(from, sky_->pdf_toward(*dir, n), drawn.pdf);
  }
  return *pdf_out > 0.0f;
}

}  // namespace fenestra
