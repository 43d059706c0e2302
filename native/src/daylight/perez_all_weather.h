#pragma once
// The Perez all-weather sky for one instant of a weather record: the sky luminance distribution of
// Perez, Seals & Michalsky (1993), "All-weather model for sky luminance distribution - preliminary
// configuration and validation", Solar Energy 50(3) 235-245 (erratum 51(5) 423), scaled by the
// luminous efficacy model of Perez, Ineichen, Seals, Michalsky & Stewart (1990), "Modeling daylight
// availability and irradiance components from direct and global irradiance", Solar Energy 44(5)
// 271-289, as Radiance's gendaylit -W and gendaymtx use them. The sky only: the sun's direct part is
// returned as a direct normal illuminance, for an explicit sun source. See docs/sky.md.
// Units: irradiance W/m^2, illuminance lux, luminance cd/m^2, angles radians unless named _deg.
#include <limits>
#include <string>

#include "daylight/sky_models.h"
#include "math/vec.h"

namespace fenestra {

// ---- The model's ingredients, each a published formula ----

// Solar constant (W/m^2) of gendaylit and gendaymtx.
constexpr double kPerezSolarConstant = 1367.0;
// Extraterrestrial normal irradiance on a day of the year (1..366), W/m^2: the solar constant times
// Spencer's (1971) eccentricity correction (the series gendaylit uses).
double extraterrestrial_normal_irradiance(int day_of_year);
// Atmospheric precipitable water (cm) from the surface dew point (deg C), Perez et al. 1990:
// W = exp(0.07 Td - 0.075).
double precipitable_water_cm(double dew_point_c);
// When the dew point is missing: 2 cm, gendaylit's default (its dew point 10.97 deg C).
constexpr double kDefaultPrecipitableWaterCm = 2.0;

// Sky clearness epsilon = ((DHI + DNI) / DHI + 1.041 Z^3) / (1 + 1.041 Z^3), Z the solar zenith in
// radians (Perez et al. 1990 eq. 1). DHI = 0 gives +infinity (the clear limit).
double perez_clearness(double direct_normal_w_m2, double diffuse_horizontal_w_m2, double zenith_rad);
// Sky brightness Delta = DHI m / E0n with m Kasten's (1966) relative air mass (relative_air_mass in
// daylight/sun_spectrum.h, the one gendaylit uses) and E0n the extraterrestrial normal irradiance.
double perez_brightness(double diffuse_horizontal_w_m2, double zenith_rad, int day_of_year);
// The eight clearness bins of both papers, 1..8, with lower bounds 1, 1.065, 1.23, 1.5, 1.95, 2.8,
// 4.5, 6.2: a bound belongs to the bin above it. Bin 1 takes epsilon < 1 too and bin 8 has no top
// (gendaylit clamps epsilon to 12.01 and gendaymtx to 11.9, which only keeps it in bin 8).
int perez_clearness_bin(double clearness);
constexpr int kPerezBins = 8;

// The five coefficients a..e of Table 1 of the 1993 paper for a bin, solar zenith Z (radians) and
// sky brightness, as given: x1 + x2 Z + Delta (x3 + x4 Z), except in bin 1 where
// c = exp((Delta (c1 + c2 Z))^c3) - c4 and d = -exp(Delta (d1 + d2 Z)) + d3 + Delta d4. No clamp.
PerezCoefficients perez_all_weather_coefficients(int bin, double zenith_rad, double brightness);

// Luminous efficacies of the 1990 paper, lm/W, for a bin, precipitable water W (cm), zenith Z
// (radians) and brightness Delta. Diffuse (Table 4, eq. 7): a + b W + c cos Z + d ln Delta.
// Direct (eq. 8): a + b W + c exp(5.73 Z - 5) + d Delta, held at 0 or above (as in gendaylit).
double perez_diffuse_efficacy(int bin, double water_cm, double zenith_rad, double brightness);
double perez_direct_efficacy(int bin, double water_cm, double zenith_rad, double brightness);

// ---- The sky ----

struct PerezSkyInput {
  Vec3 sun = Vec3(0.0f, 0.0f, 1.0f);  // toward the sun, +Z up; any non-zero length
  int day_of_year = 1;                // 1..366, for the Earth-Sun distance
  double direct_normal_w_m2 = 0.0;    // DNI
  double diffuse_horizontal_w_m2 = 0.0;  // DHI
  double dew_point_c = std::numeric_limits<double>::quiet_NaN();  // NaN: missing (W = 2 cm)
  std::string where;                  // names the record in error messages, e.g. "x.epw line 12"
};

// One instant's sky. With the sun below the horizon the model takes Z = 90 deg and the sun on the
// horizon at its azimuth, so twilight DHI still lights the sky, and there is no direct light (as
// gendaymtx); DHI = 0 gives a black sky. The luminance is 0 below the horizon.
class PerezAllWeatherSky {
 public:
  // Validates (throws std::invalid_argument naming the record, the field and the value): sun finite
  // and non-zero, day of year in 1..366, irradiances finite, >= 0 and not above the extraterrestrial
  // normal irradiance of the day, dew point NaN (missing) or within kMinDewPointC..kMaxDewPointC.
  static PerezAllWeatherSky create(const PerezSkyInput& input);
  static constexpr double kMinDewPointC = -90.0, kMaxDewPointC = 60.0;

  // The model's limits, those of gendaylit and gendaymtx: Delta is held within [0.01, 0.6] for the
  // coefficients and the efficacies, and at 0.2 or more for the coefficients of bins 2 to 5.
  static constexpr double kMinBrightness = 0.01, kMaxBrightness = 0.6, kIntermediateMinBrightness = 0.2;

  // cd/m^2 toward a unit direction (+Z up), 0 below the horizon: scale() max(0, F(theta, gamma)),
  // or scale() alone for a uniform() sky.
  double luminance(const Vec3& dir) const;
  double zenith_luminance() const;  // cd/m^2
  // The same for many directions sharing a zenith angle (a map row, a ring of patch points): the
  // gradation factor is computed once per row. luminance(dir) is luminance(row(dir.z()), dir).
  struct Row {
    double cos_theta = 0.0;
    double scaled_gradation = 0.0;  // scale() (1 + a exp(b / cos theta)), or scale() for a uniform sky
  };
  Row row(double cos_theta) const;
  double luminance(const Row& row, const Eigen::Vector3d& dir) const;  // dir unit, dir.z() == row.cos_theta

  double diffuse_horizontal_illuminance() const { return diffuse_lux_; }  // lux: the integral of L cos
  double direct_normal_illuminance() const { return direct_lux_; }        // lux, for an explicit sun
  double diffuse_efficacy() const { return diffuse_efficacy_; }           // lm/W
  double direct_efficacy() const { return direct_efficacy_; }             // lm/W

  double clearness() const { return clearness_; }    // epsilon, unclamped (+inf when DHI = 0)
  double brightness() const { return brightness_; }  // Delta from the data, unclamped
  double efficacy_brightness() const;                // Delta as the efficacies use it
  double coefficient_brightness() const;             // Delta as the coefficients use it
  int clearness_bin() const { return bin_; }         // 1..8
  double precipitable_water_cm() const { return water_cm_; }
  // The solar zenith the model uses (radians): the sun's, or pi/2 when the sun is below the horizon.
  double model_zenith() const { return zenith_; }
  bool sun_below_horizon() const { return sun_below_horizon_; }
  const Eigen::Vector3d& model_sun() const { return model_sun_; }  // unit; on the horizon when below
  // a..e, with b held at 0 or below (gradation_held() says when it was positive).
  const PerezCoefficients& coefficients() const { return coefficients_; }
  double scale() const { return scale_; }  // cd/m^2 per unit of F

  // Where the model leaves its domain (docs/sky.md): b > 0 makes the gradation diverge toward the
  // horizon and is held at 0; F < 0 somewhere gives zero luminance there; F <= 0 everywhere gives a
  // uniform sky of the same diffuse horizontal illuminance.
  bool gradation_held() const { return gradation_held_; }
  bool clipped() const { return clipped_; }
  bool uniform() const { return uniform_; }

  std::string to_string() const;

  // The normalisation: the integral over the upper hemisphere of max(0, F) cos(theta) d(omega), sr.
  // Gauss-Legendre (24 nodes a piece) in cos(theta) and in the azimuth from the sun's vertical,
  // in pieces that end where the integrand has a kink or a cusp. Relative error below 1e-6 where
  // F > 0 and 1e-4 where F changes sign, over the states the data can reach (docs/sky.md).
  struct HorizontalIntegral {
    double value = 0.0;
    bool clipped = false;  // F < 0 at some node
  };
  static HorizontalIntegral horizontal_integral(const PerezCoefficients& coefficients, double sun_zenith_rad);

 private:
  PerezAllWeatherSky() = default;
  double direct_normal_w_m2_ = 0.0, diffuse_horizontal_w_m2_ = 0.0;
  double clearness_ = 1.0, brightness_ = 0.0, water_cm_ = 0.0;
  int bin_ = 1;
  double zenith_ = 0.0;
  bool sun_below_horizon_ = false;
  Eigen::Vector3d model_sun_ = Eigen::Vector3d::UnitZ();
  PerezCoefficients coefficients_;
  double diffuse_efficacy_ = 0.0, direct_efficacy_ = 0.0;
  double diffuse_lux_ = 0.0, direct_lux_ = 0.0;
  double scale_ = 0.0;
  bool gradation_held_ = false, clipped_ = false, uniform_ = false;
};

}  // namespace fenestra
