// The climate sky matrix (daylight/sky_matrix.h) over the Chicago O'Hare TMY3 year: energy of the
// patch discretisation against the Perez sky's diffuse illuminance, a uniform sky, the sun of a
// known hour, night columns, the ground row, refusals, and how long a year takes.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

#include "daylight/perez_all_weather.h"
#include "daylight/sky_matrix.h"
#include "daylight/weather_site.h"
#include "scene/environment_map.h"
#include "study/cost_model.h"
#include "util/cost_context.h"

using namespace fenestra;

namespace {

const WeatherData& chicago() {
  static const WeatherData w =
      read_weather(std::string(FENESTRA_EXAMPLES) + "/weather/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw");
  return w;
}

// The Perez sky the matrix was built from for hour i (the same inputs).
PerezAllWeatherSky sky_of(const WeatherData& w, const SkyMatrix& m, size_t i) {
  const WeatherHour& h = w.hours[i];
  PerezSkyInput in;
  in.sun = m.sun_direction[i];
  in.day_of_year = day_of_year(h.month, h.day);
  in.direct_normal_w_m2 = h.direct_normal_w_m2;
  in.diffuse_horizontal_w_m2 = h.diffuse_horizontal_w_m2;
  in.dew_point_c = h.dew_point_c;
  return PerezAllWeatherSky::create(in);
}

// What the patch discretisation gives for one hour, next to the error bound derived in
// docs/sky.md ("The patch sum"). With n x n points per patch, s = sin(altitude) = cos(theta):
//  sum   = sum_k mean_k(L) P_k, P_k = Omega_k s_k (the projected solid angle; s_k the patch's
//          mid sine, exactly, since the points are uniform in s);
//  q     = sum_k Omega_k mean_k(L s), the midpoint rule for the horizontal illuminance itself;
//  sum - q = -sum_k Omega_k mean_k((L - c_k)(s - s_k)) for any constant c_k (the points are
//          symmetric about s_k), so |sum - q| <= sum_k Omega_k (range_k(L) / 2) mean|s - s_k|,
//          mean|s - s_k| = ds_k / 4 for even n: `bound`.
struct PatchSum {
  double sum = 0.0, q = 0.0, q_fine = 0.0, bound = 0.0;
};
PatchSum patch_sum(const SkyMatrix& m, size_t i, const PerezAllWeatherSky& sky, int n, int fine) {
  PatchSum r;
  const SkyPatches& p = m.patches;
  for (int k = 1; k < p.count(); ++k) {
    r.sum += double(m.radiance(k, static_cast<Eigen::Index>(i))) * p.projected_solid_angle(k);
    const SkyPatches::Bounds b = p.bounds(k);
    const double omega = p.solid_angle(k), ds = std::sin(b.alt1) - std::sin(b.alt0);
    double lo = HUGE_VAL, hi = -HUGE_VAL, ls = 0.0;
    for (int a = 0; a < n; ++a)
      for (int c = 0; c < n; ++c) {
        const Vec3d d = p.square_to_patch(k, (a + 0.5) / n, (c + 0.5) / n);
        const double l = sky.luminance(d.cast<float>());
        lo = std::min(lo, l), hi = std::max(hi, l), ls += l * d.z();
      }
    r.q += omega * ls / (n * n);
    r.bound += omega * 0.5 * (hi - lo) * ds / 4.0;
    if (fine > 0) {
      double lf = 0.0;
      for (int a = 0; a < fine; ++a)
        for (int c = 0; c < fine; ++c) {
          const Vec3d d = p.square_to_patch(k, (a + 0.5) / fine, (c + 0.5) / fine);
          lf += sky.luminance(d.cast<float>()) * d.z();
        }
      r.q_fine += omega * lf / (fine * fine);
    }
  }
  return r;
}

TEST(SkyMatrix, ShapeHoursAndWarningsOfTheChicagoYear) {
  const WeatherData& w = chicago();
  const SkyMatrix m = make_sky_matrix(w, ClimateSettings::for_weather(w));
  EXPECT_EQ(m.patches.count(), 146);
  EXPECT_EQ(m.radiance.rows(), 146);
  EXPECT_EQ(m.radiance.cols(), 8760);
  ASSERT_EQ(m.hours.size(), 8760u);
  EXPECT_EQ(m.sun_direction.size(), 8760u);
  EXPECT_EQ(m.sun_normal_illuminance.size(), 8760u);
  EXPECT_EQ(m.diffuse_horizontal_lux.size(), 8760u);
  EXPECT_EQ(m.global_horizontal_lux.size(), 8760u);
  EXPECT_EQ(m.hours.front().month, 1);
  EXPECT_EQ(m.hours.front().day, 1);
  EXPECT_DOUBLE_EQ(m.hours.front().clock_hour, 0.5);  // hour-ending row 1: the middle of 00:00-01:00
  EXPECT_EQ(m.hours.back().month, 12);
  EXPECT_EQ(m.hours.back().day, 31);
  EXPECT_DOUBLE_EQ(m.hours.back().clock_hour, 23.5);
  EXPECT_TRUE(m.warnings.empty());  // the file has none, and the place is the file's
  EXPECT_TRUE(m.radiance.allFinite());
  EXPECT_GE(m.radiance.minCoeff(), 0.0f);
  // The occupied hours of LM-83-12: 10 a day.
  EXPECT_EQ(occupied_hours(m.hours, ClimateSettings()).size(), 3650u);
}

TEST(SkyMatrix, PatchSumsKeepTheDiffuseIlluminanceWithinTheDerivedBound) {
  const WeatherData& w = chicago();
  for (int mf : {1, 2}) {
    ClimateSettings s = ClimateSettings::for_weather(w);
    s.subdivision = mf;
    const SkyMatrix m = make_sky_matrix(w, s);
    const size_t stride = getenv("FENESTRA_ALL_HOURS") ? 1 : mf == 1 ? 11 : 17;  // every hour: a minute
    double worst_total = 0.0, worst_bound = 0.0, worst_midpoint = 0.0, mean_total = 0.0;
    int hours = 0;
    for (size_t i = 0; i < w.hours.size(); i += stride) {
      const double e = m.diffuse_horizontal_lux[i];
      if (!(e > 0.0)) continue;
      ++hours;
      const PerezAllWeatherSky sky = sky_of(w, m, i);
      ASSERT_NEAR(sky.diffuse_horizontal_illuminance(), e, 1e-9 * e);
      const PatchSum r = patch_sum(m, i, sky, ClimateSettings::kPointsPerSide, mf == 1 ? 32 : 0);
      // The covariance term, within its bound (plus the float storage of the matrix).
      EXPECT_LE(std::abs(r.sum - r.q), r.bound + 1e-6 * e) << "hour " << i << " MF " << mf;
      worst_bound = std::max(worst_bound, r.bound / e);
      worst_total = std::max(worst_total, std::abs(r.sum - e) / e);
      mean_total += std::abs(r.sum - e) / e;
      if (mf == 1) {
        // The midpoint rule's own error falls as 1 / n^2 away from the sun's cusp: with 32 points a
        // side it is 1/64 of that with 4, so |q - e| is within 1.1 |q - q_fine| plus the error of the
        // normalisation integral (1e-4 where F changes sign).
        EXPECT_LE(std::abs(r.q - e), 1.1 * std::abs(r.q - r.q_fine) + 1e-4 * e) << "hour " << i;
        worst_midpoint = std::max(worst_midpoint, std::abs(r.q - e) / e);
      }
      // Altogether: the patch sum is the diffuse illuminance within the two.
      EXPECT_LE(std::abs(r.sum - e), r.bound + std::abs(r.q - e) + 1e-6 * e) << "hour " << i;
    }
    std::printf("MF %d, %d hours: |sum - E| / E at most %.2e, mean %.2e; bound at most %.2e; midpoint rule at most %.2e\n",
                mf, hours, worst_total, mean_total / hours, worst_bound, worst_midpoint);
    EXPECT_GT(hours, stride == 1 ? 4600 : mf == 1 ? 400 : 250);
    // Over the whole year (FENESTRA_ALL_HOURS=1; docs/sky.md, "The patch sum"): at most 5.1 % and
    // 0.51 % on average for MF 1, 1.3 % and 0.13 % for MF 2.
    EXPECT_LT(worst_total, mf == 1 ? 0.055 : 0.014);
    EXPECT_LT(mean_total / hours, mf == 1 ? 0.006 : 0.0015);
  }
}

TEST(SkyMatrix, AUniformSkyGivesEveryPatchItsLuminance) {
  // A clear-sky clearness with very little diffuse light and the sun near the zenith: F <= 0
  // everywhere and the Perez sky is uniform, L = E_dh / pi (docs/sky.md).
  WeatherData w;
  w.path = "uniform.wea";
  w.location.latitude_deg = 0.0;
  w.location.longitude_deg = 0.0;
  w.location.time_zone_hours = 0.0;
  WeatherHour h;
  h.month = 3;
  h.day = 21;
  h.hour_ending = std::numeric_limits<double>::quiet_NaN();
  h.clock_hours = 12.1;  // the sun within a few degrees of the zenith at the equator
  // Bin 6 (clearness 3.5) and brightness near 0.011: a = -1.0156 + 1.0078 x 0.011 < -1 near the
  // zenith, b > 0 held at 0, so 1 + a exp(b / cos theta) < 0 while c > 0: F < 0 everywhere.
  h.diffuse_horizontal_w_m2 = 15.0;
  h.direct_normal_w_m2 = 37.5;
  h.dew_point_c = std::numeric_limits<double>::quiet_NaN();
  h.line = 7;
  w.hours = {h};
  for (int mf : {1, 2, 4}) {
    ClimateSettings s = ClimateSettings::for_weather(w);
    s.subdivision = mf;
    s.north_offset_deg = 33.0;
    const SkyMatrix m = make_sky_matrix(w, s);
    const PerezAllWeatherSky sky = sky_of(w, m, 0);
    ASSERT_TRUE(sky.uniform()) << sky.to_string();
    const double l = sky.diffuse_horizontal_illuminance() / kPiD;
    double sum = 0.0;
    for (int k = 1; k < m.patches.count(); ++k) {
      EXPECT_NEAR(m.radiance(k, 0), l, 1e-6 * l) << "patch " << k;
      sum += m.radiance(k, 0) * m.patches.projected_solid_angle(k);
    }
    // The projected solid angles sum to pi: the patch sum is the diffuse illuminance exactly.
    EXPECT_NEAR(sum, sky.diffuse_horizontal_illuminance(), 1e-6 * sky.diffuse_horizontal_illuminance());
  }
}

TEST(SkyMatrix, TheSunOfAKnownHourIsTheSolarPositionAtItsMiddle) {
  const WeatherData& w = chicago();
  ClimateSettings s = ClimateSettings::for_weather(w);
  s.north_offset_deg = 30.0;
  const SkyMatrix m = make_sky_matrix(w, s);
  // 21 June, EPW hour 13: 12:00-13:00 of Chicago standard time (UTC-6), its middle 12:30 is
  // 18:30 UTC; the sun is placed in the reference year 2022 (no 29 February in the file).
  const size_t row = (31 + 28 + 31 + 30 + 31 + 20) * 24 + 12;
  ASSERT_EQ(w.hours[row].month, 6);
  ASSERT_EQ(w.hours[row].day, 21);
  ASSERT_EQ(w.hours[row].hour_ending, 13);
  EXPECT_EQ(m.hours[row].month, 6);
  EXPECT_EQ(m.hours[row].day, 21);
  EXPECT_DOUBLE_EQ(m.hours[row].clock_hour, 12.5);
  const double utc = TimeZone::fixed(0.0).utc_seconds(LocalDate{2022, 6, 21}, 18.5 * 60.0);
  const Place place{41.98, -87.92, 205.0};  // the file's LOCATION line
  SunPosition p = solar_position(utc, place, true);
  // Solar noon is near 11:53 standard time there (longitude 2.08 degrees east of the zone's
  // meridian, equation of time -1.8 min): 12:30 is an hour angle of 9.1 degrees, and with the
  // solstice declination cos Z = sin(41.98) sin(23.44) + cos(41.98) cos(23.44) cos(9.1), Z = 20.0.
  EXPECT_NEAR(p.zenith_deg, 20.0, 0.1);
  p.azimuth_deg += 30.0;                         // true north 30 degrees clockwise from +Y
  const Vec3 expected = sun_direction(p);
  EXPECT_LT((m.sun_direction[row] - expected).norm(), 1e-6f);
  // Direct illuminance of that hour: the Perez direct efficacy times DNI.
  const PerezAllWeatherSky sky = sky_of(w, m, row);
  EXPECT_FLOAT_EQ(m.sun_normal_illuminance[row], static_cast<float>(sky.direct_normal_illuminance()));
  EXPECT_NEAR(sky.direct_normal_illuminance(), w.hours[row].direct_normal_w_m2 * sky.direct_efficacy(), 1e-9);
}

TEST(SkyMatrix, NightHoursAreZeroColumnsAndTwilightHasSkyButNoSun) {
  const WeatherData& w = chicago();
  const SkyMatrix m = make_sky_matrix(w, ClimateSettings::for_weather(w));
  int night = 0, twilight = 0, day = 0;
  for (size_t i = 0; i < w.hours.size(); ++i) {
    const auto column = m.radiance.col(static_cast<Eigen::Index>(i));
    const bool up = m.sun_direction[i].z() > 0.0f;
    if (!up && w.hours[i].diffuse_horizontal_w_m2 == 0.0) {
      ++night;
      EXPECT_EQ(column.cwiseAbs().maxCoeff(), 0.0f) << "hour " << i;
      EXPECT_EQ(m.sun_normal_illuminance[i], 0.0f);
      EXPECT_EQ(m.diffuse_horizontal_lux[i], 0.0);
      EXPECT_EQ(m.global_horizontal_lux[i], 0.0);
    } else if (!up) {
      ++twilight;
      EXPECT_GT(column.tail(column.size() - 1).maxCoeff(), 0.0f) << "hour " << i;
      EXPECT_EQ(m.sun_normal_illuminance[i], 0.0f) << "hour " << i;
      EXPECT_DOUBLE_EQ(m.global_horizontal_lux[i], m.diffuse_horizontal_lux[i]);
    } else {
      ++day;
    }
  }
  EXPECT_GT(night, 3500);
  EXPECT_GT(twilight, 100);  // docs/sky.md: 291 hours with the sun down and some light
  EXPECT_GT(day, 4000);
  EXPECT_EQ(night + twilight + day, 8760);
}

TEST(SkyMatrix, TheGroundRowIsALambertianGroundLitByTheHour) {
  const WeatherData& w = chicago();
  ClimateSettings s = ClimateSettings::for_weather(w);
  s.ground_reflectance = 0.35;
  const SkyMatrix m = make_sky_matrix(w, s);
  int sunny = 0;
  for (size_t i = 0; i < w.hours.size(); ++i) {
    const double cos_zenith = std::max(0.0, double(m.sun_direction[i].z()));
    const double global = m.diffuse_horizontal_lux[i] + double(m.sun_normal_illuminance[i]) * cos_zenith;
    EXPECT_NEAR(m.global_horizontal_lux[i], global, 1e-5 * global + 1e-9) << "hour " << i;
    const double ground = 0.35 * global / kPiD;
    EXPECT_NEAR(m.radiance(SkyPatches::kGround, static_cast<Eigen::Index>(i)), ground, 1e-5 * ground + 1e-9)
        << "hour " << i;
    sunny += m.sun_normal_illuminance[i] > 0.0f;
  }
  EXPECT_GT(sunny, 3000);
}

TEST(SkyMatrix, ResultsDoNotDependOnTheMeansRoutine) {
  // The matrix's patch means are SkyPatches::patch_means of the hour's luminance.
  const WeatherData& w = chicago();
  ClimateSettings s = ClimateSettings::for_weather(w);
  s.subdivision = 2;
  s.north_offset_deg = -75.0;
  const SkyMatrix m = make_sky_matrix(w, s);
  for (size_t i : {4000u, 4013u, 100u, 8000u}) {
    const PerezAllWeatherSky sky = sky_of(w, m, i);
    const std::vector<double> means =
        m.patches.patch_means([&](const Vec3d& d) { return sky.luminance(d.cast<float>()); });
    for (int k = 1; k < m.patches.count(); ++k)
      EXPECT_NEAR(m.radiance(k, i), means[k], 1e-6 * means[k] + 1e-6) << "hour " << i << " patch " << k;
  }
}

TEST(SkyMatrix, AFarPlaceIsWarnedNamingBoth) {
  const WeatherData& w = chicago();
  ClimateSettings s = ClimateSettings::for_weather(w);
  s.place = {37.98, 23.73, 100.0};  // Athens
  const SkyMatrix m = make_sky_matrix(w, s);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("37.98"), std::string::npos) << m.warnings[0];
  EXPECT_NE(m.warnings[0].find("Chicago"), std::string::npos) << m.warnings[0];
  EXPECT_NE(m.warnings[0].find("km"), std::string::npos) << m.warnings[0];
  s.place = {42.3, -87.9, 0.0};  // 36 km north: no warning
  EXPECT_TRUE(make_sky_matrix(w, s).warnings.empty());
}

TEST(SkyMatrix, RefusesBadSettingsAndAMatrixBeyondTheMemoryLimit) {
  const WeatherData& w = chicago();
  auto refused = [&](const ClimateSettings& s, const std::string& needle) {
    try {
      make_sky_matrix(w, s);
      ADD_FAILURE() << "accepted; expected " << needle;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  ClimateSettings s = ClimateSettings::for_weather(w);
  s.subdivision = 0;
  refused(s, "subdivision");
  s = ClimateSettings::for_weather(w);
  s.ground_reflectance = 1.5;
  refused(s, "sky.ground_reflectance");
  s = ClimateSettings::for_weather(w);
  s.occupied_start_hour = 18.0, s.occupied_end_hour = 8.0;
  refused(s, "sky.occupied");
  s = ClimateSettings::for_weather(w);
  s.place.latitude_deg = 95.0;
  refused(s, "sky.latitude");
  // MF 4 needs 2306 x 8760 floats, 81 MB: refused under a 50 MB limit, naming the setting.
  s = ClimateSettings::for_weather(w);
  s.subdivision = 4;
  {
    CostScope scope({50'000'000, CostCommand::Any});
    try {
      make_sky_matrix(w, s);
      ADD_FAILURE() << "accepted under 50 MB";
    } catch (const CostError& e) {
      EXPECT_NE(std::string(e.what()).find("sky matrix"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("sky.patches"), std::string::npos) << e.what();
    }
  }
  // MF 64 (589 825 patches) would take hours: refused by time whatever the memory.
  s.subdivision = 64;
  {
    CostScope scope({uint64_t(1) << 50, CostCommand::Any});
    EXPECT_THROW(make_sky_matrix(w, s), CostError);
  }
}

TEST(SkyMatrix, TimingsForTheChicagoYear) {
  const WeatherData& w = chicago();
  for (int mf : {1, 2, 4}) {
    ClimateSettings s = ClimateSettings::for_weather(w);
    s.subdivision = mf;
    const auto start = std::chrono::steady_clock::now();
    const SkyMatrix m = make_sky_matrix(w, s);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("sky matrix MF %d: %d x %d in %.2f s\n", mf, int(m.radiance.rows()), int(m.radiance.cols()), seconds);
    RecordProperty("seconds_mf" + std::to_string(mf), std::to_string(seconds));
    EXPECT_LT(seconds, mf == 4 ? 120.0 : 30.0);  // generous: the machine may be shared
  }
}

}  // namespace
