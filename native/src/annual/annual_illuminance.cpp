#include "annual/annual_illuminance.h"

namespace fenestra {

AnnualIlluminance annual_illuminance(const AnnualCoefficients& coefficients, const AnnualRecords& annual) {
  const SkyMatrix& sky = *annual.climate->sky;
  const int patches = annual.sources.patch_count;
  const Eigen::Index sensors = coefficients.sources.rows(), hours = static_cast<Eigen::Index>(sky.hours.size());
  AnnualIlluminance out;
  out.total.setZero(sensors, hours);
  out.direct.setZero(sensors, hours);
  // The sky: one product over the day hours (night columns stay zero).
  const Eigen::MatrixXf sky_part = coefficients.sources.leftCols(patches).cast<float>() * annual.day_sky;
  for (size_t j = 0; j < annual.day_hours.size(); ++j) out.total.col(annual.day_hours[j]) = sky_part.col(j);
  // The sun: its cluster's coefficients for the light that reflected, its exact position for the rest.
  const Eigen::MatrixXf sun_coefficients = coefficients.sources.rightCols(annual.sources.suns.size()).cast<float>();
  for (size_t j = 0; j < annual.sun_hours.size(); ++j) {
    const int h = annual.sun_hours[j];
    const float e = sky.sun_normal_illuminance[h];
    out.direct.col(h) = coefficients.direct.col(j) * e;
    out.total.col(h) += sun_coefficients.col(annual.sources.suns.cluster_of_hour[h]) * e + out.direct.col(h);
  }
  return out;
}

}  // namespace fenestra
