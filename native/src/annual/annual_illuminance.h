#pragma once
// Every sensor's illuminance at every hour of the year for one set of open elements, from an
// annual pass's records: daylight coefficients per sensor and source (one walk over the records),
// then one matrix product with the sky matrix, the sun clusters' share of the light that reflected
// at least once, and the exact sun straight to the sensor. See docs/annual.md.
#include <tbb/parallel_for.h>

#include <Eigen/Core>

#include "annual/annual_records.h"
#include "util/progress.h"

namespace fenestra {

struct AnnualIlluminance {
  Eigen::MatrixXf total;   // sensors x hours of the weather file, lux
  Eigen::MatrixXf direct;  // sensors x hours, lux: the sun straight to the sensor, nothing reflected (ASE)
};

// Daylight coefficients of one set of open elements: per sensor, per source, the illuminance at
// unit source strength (lux per cd/m^2 for a patch, per lux of normal illuminance for a sun
// cluster) of the light that reflected at least once for suns; and per sensor, per sun hour, the
// fraction cos x attenuation of the sun's normal illuminance that arrives straight.
struct AnnualCoefficients {
  Eigen::MatrixXd sources;  // sensors x sources
  Eigen::MatrixXf direct;   // sensors x sun hours
};

// is_open(element, point): whether the domain is open where a path met it (OpenRegion::is_open,
// or a mask). Parallel over sensors.
template <typename IsOpen>
AnnualCoefficients annual_coefficients(const std::vector<SensorRecord>& records, const AnnualRecords& annual,
                                       IsOpen is_open, const Progress* progress = nullptr) {
  AnnualCoefficients c;
  const size_t sensors = records.size();
  c.sources.setZero(sensors, annual.sources.count());
  c.direct.setZero(sensors, annual.sun_hours.size());
  tbb::parallel_for(size_t(0), sensors, [&](size_t i) {
    if (progress && progress->cancelled()) return;
    const SensorRecord& r = records[i];
    Eigen::VectorXd row = Eigen::VectorXd::Zero(annual.sources.count());
    for (size_t p = 0; p < r.path_count(); ++p)
      for_each_counting_event_in_region(r, p, is_open, [&](uint32_t e) {
        const uint16_t source = r.event_sources[e];
        if (!(source & AnnualSources::kDirect)) row[source] += r.event_coefficients[e];
      });
    c.sources.row(i) = row.transpose() / static_cast<double>(std::max<size_t>(1, r.path_count()));
    const SensorRecord& d = annual.direct[i];
    for (size_t j = 0; j < d.path_count(); ++j)
      c.direct(i, j) = static_cast<float>(path_value_in_region(d, j, is_open)) * annual.direct_factor[i][j];
  });
  if (progress) progress->throw_if_cancelled();
  return c;
}

// The hourly illuminance from the coefficients (sensors x hours of the sky matrix).
AnnualIlluminance annual_illuminance(const AnnualCoefficients& coefficients, const AnnualRecords& annual);

}  // namespace fenestra
