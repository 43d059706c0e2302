#pragma once
// The light sources of an annual pass, each traced with unit strength so that the records hold
// daylight coefficients: the sky patches (uniform unit luminance over each patch; the sky matrix
// gives their luminance per hour) and the sun at clustered positions (unit normal illuminance;
// each hour's sun takes its cluster's coefficients for the light it brings after a reflection, and
// its exact position for the light it brings straight to the sensor). See docs/annual.md.
#include <cstdint>
#include <vector>

#include "daylight/sky_matrix.h"
#include "math/vec.h"

namespace fenestra {

// The hours' sun positions grouped into the Reinhart patches (subdivision `subdivision`) that
// hold at least one of them; each cluster sits at the illuminance-weighted mean direction of its
// hours. Angles between an hour's sun and its cluster are reported (the clustering error).
struct SunClusters {
  int subdivision = 6;
  std::vector<Vec3> direction;       // unit, world (+Z up)
  std::vector<double> energy_lux_h;  // sum of its hours' direct normal illuminance (lux hours)
  std::vector<int> cluster_of_hour;  // per hour of the sky matrix, -1 when there is no sun
  double max_error_deg = 0.0;        // largest angle between an hour's sun and its cluster
  double mean_error_deg = 0.0;       // illuminance-weighted mean of those angles
  size_t size() const { return direction.size(); }
};
SunClusters cluster_suns(const SkyMatrix& sky, int subdivision = 6);

// Source indices: 0 .. patches - 1 the sky patches (0: the ground), then the sun clusters.
// A recorded event's source may carry kDirect: light that reached the sensor straight from a sun
// cluster, which annual evaluation replaces by the hour's exact sun.
struct AnnualSources {
  static constexpr uint16_t kDirect = 0x8000;
  static constexpr int kMaxSources = 0x7fff;
  int patch_count = 0;
  SunClusters suns;
  int count() const { return patch_count + static_cast<int>(suns.size()); }
  int sun_source(int cluster) const { return patch_count + cluster; }
};

}  // namespace fenestra
