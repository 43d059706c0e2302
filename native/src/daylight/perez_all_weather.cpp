#include "daylight/perez_all_weather.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "daylight/sun_spectrum.h"
#include "math/constants.h"
#include "math/gauss_legendre.h"
#include "util/number_text.h"

namespace fenestra {
namespace {

constexpr double kDegree = kPiD / 180.0;

// Lower clearness bounds of bins 2..8 (both papers, Table 1).
constexpr double kBinLowerBounds[kPerezBins - 1] = {1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200};

// Perez, Seals & Michalsky 1993, Table 1: for each clearness bin, coefficients a, b, c, d, e, each
// as x1, x2, x3, x4 (see perez_all_weather_coefficients).
constexpr double kLuminanceTable[kPerezBins][5][4] = {
    {{1.3525, -0.2576, -0.2690, -1.4366},
     {-0.7670, 0.0007, 1.2734, -0.1233},
     {2.8000, 0.6004, 1.2375, 1.0000},
     {1.8734, 0.6297, 0.9738, 0.2809},
     {0.0356, -0.1246, -0.5718, 0.9938}},
    {{-1.2219, -0.7730, 1.4148, 1.1016},
     {-0.2054, 0.0367, -3.9128, 0.9156},
     {6.9750, 0.1774, 6.4477, -0.1239},
     {-1.5798, -0.5081, -1.7812, 0.1080},
     {0.2624, 0.0672, -0.2190, -0.4285}},
    {{-1.1000, -0.2515, 0.8952, 0.0156},
     {0.2782, -0.1812, -4.5000, 1.1766},
     {24.7219, -13.0812, -37.7000, 34.8438},
     {-5.0000, 1.5218, 3.9229, -2.6204},
     {-0.0156, 0.1597, 0.4199, -0.5562}},
    {{-0.5484, -0.6654, -0.2672, 0.7117},
     {0.7234, -0.6219, -5.6812, 2.6297},
     {33.3389, -18.3000, -62.2500, 52.0781},
     {-3.5000, 0.0016, 1.1477, 0.1062},
     {0.4659, -0.3296, -0.0876, -0.0329}},
    {{-0.6000, -0.3566, -2.5000, 2.3250},
     {0.2937, 0.0496, -5.6812, 1.8415},
     {21.0000, -4.7656, -21.5906, 7.2492},
     {-3.5000, -0.1554, 1.4062, 0.3988},
     {0.0032, 0.0766, -0.0656, -0.1294}},
    {{-1.0156, -0.3670, 1.0078, 1.4051},
     {0.2875, -0.5328, -3.8500, 3.3750},
     {14.0000, -0.9999, -7.1406, 7.5469},
     {-3.4000, -0.1078, -1.0750, 1.5702},
     {-0.0672, 0.4016, 0.3017, -0.4844}},
    {{-1.0000, 0.0211, 0.5025, -0.5119},
     {-0.3000, 0.1922, 0.7023, -1.6317},
     {19.0000, -5.0000, 1.2438, -1.9094},
     {-4.0000, 0.0250, 0.3844, 0.2656},
     {1.0468, -0.3788, -2.4517, 1.4656}},
    {{-1.0500, 0.0289, 0.4260, 0.3590},
     {-0.3250, 0.1156, 0.7781, 0.0025},
     {31.0625, -14.5000, -46.1148, 55.3750},
     {-7.2312, 0.4050, 13.3500, 0.6234},
     {1.5000, -0.6426, 1.8564, 0.5636}},
};

// Perez et al. 1990, Table 4: a, b, c, d per clearness bin.
struct EfficacyRow {
  double a, b, c, d;
};
constexpr EfficacyRow kDiffuseEfficacy[kPerezBins] = {
    {97.24, -0.46, 12.00, -8.91},    {107.22, 1.15, 0.59, -3.95},    {104.97, 2.96, -5.53, -8.77},
    {102.39, 5.59, -13.95, -13.90},  {100.71, 5.94, -22.75, -23.74}, {106.42, 3.83, -36.15, -28.83},
    {141.88, 1.90, -53.24, -14.03},  {152.23, 0.35, -45.27, -7.98}};
constexpr EfficacyRow kDirectEfficacy[kPerezBins] = {
    {57.20, -4.55, -2.98, 117.12}, {98.99, -3.46, -1.21, 12.38},  {109.83, -4.90, -1.71, -8.81},
    {110.34, -5.84, -1.99, -4.56}, {106.36, -3.97, -1.75, -6.16}, {107.19, -1.25, -1.51, -26.73},
    {105.75, 0.77, -1.26, -34.44}, {101.18, 1.58, -1.10, -8.29}};

void check_bin(int bin) {
  if (bin < 1 || bin > kPerezBins)
    throw std::invalid_argument("Perez all-weather sky: clearness bin " + std::to_string(bin) + " is not in 1..8");
}

// x1 + x2 Z + Delta (x3 + x4 Z)
double linear_form(const double (&x)[4], double zenith, double brightness) {
  return x[0] + x[1] * zenith + brightness * (x[2] + x[3] * zenith);
}

// ---- Quadrature ----

constexpr int kNodesPerPiece = 24;  // Gauss-Legendre nodes per piece, in cos(theta) and in azimuth

const QuadratureRule& rule() {
  static const QuadratureRule r = gauss_legendre(kNodesPerPiece);
  return r;
}

// Integral of f over [a, b]; with `graded_at_a` the nodes are pulled toward a (x = a + (b - a) t^2),
// which keeps the accuracy of a rule whose integrand has a cusp at a.
template <typename F>
double integrate(const F& f, double a, double b, bool graded_at_a) {
  const QuadratureRule& r = rule();
  double sum = 0.0;
  for (int i = 0; i < kNodesPerPiece; ++i) {
    const double t = r.nodes[i];
    if (graded_at_a)
      sum += r.weights[i] * 2.0 * t * f(a + (b - a) * t * t);
    else
      sum += r.weights[i] * f(a + (b - a) * t);
  }
  return sum * (b - a);
}

// Sorted, unique breakpoints within [lo, hi], ends included.
std::vector<double> breakpoints(std::vector<double> points, double lo, double hi) {
  std::vector<double> out = {lo, hi};
  for (double p : points)
    if (p > lo && p < hi) out.push_back(p);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Scattering angles in (0, pi) where the gamma factor changes sign: a sample every pi/64, then bisection.
std::vector<double> gamma_factor_roots(const PerezCoefficients& c) {
  const auto g = [&](double gamma) { return c.gamma_factor(gamma, std::cos(gamma)); };
  std::vector<double> roots;
  constexpr int kSamples = 64;
  double lo = 0.0, g_lo = g(lo);
  for (int i = 1; i <= kSamples; ++i) {
    double hi = kPiD * i / kSamples, g_hi = g(hi);
    if ((g_lo < 0.0) != (g_hi < 0.0)) {
      double a = lo, b = hi;
      for (int k = 0; k < 60; ++k) {
        const double m = 0.5 * (a + b);
        ((g(m) < 0.0) == (g_lo < 0.0) ? a : b) = m;
      }
      roots.push_back(0.5 * (a + b));
    }
    lo = hi;
    g_lo = g_hi;
  }
  return roots;
}

// ---- Input checks ----

std::string record(const PerezSkyInput& input) {
  return (input.where.empty() ? std::string() : input.where + ": ") + "Perez all-weather sky: ";
}

void check_irradiance(const PerezSkyInput& input, const char* field, double value, double bound) {
  if (!std::isfinite(value) || value < 0.0)
    throw std::invalid_argument(record(input) + field + " " + decimal_text(value) + " W/m^2 must be finite and not negative");
  if (value > bound)
    throw std::invalid_argument(record(input) + field + " " + decimal_text(value) +
                                " W/m^2 exceeds the extraterrestrial normal irradiance of day " +
                                std::to_string(input.day_of_year) + ", " + decimal_text(bound) + " W/m^2");
}

void check(const PerezSkyInput& input) {
  const Vec3& s = input.sun;
  if (!is_finite(s) || !(s.norm() > 0.0f))
    throw std::invalid_argument(record(input) + "sun direction (" + decimal_text(s.x()) + ", " + decimal_text(s.y()) + ", " +
                                decimal_text(s.z()) + ") must be finite and non-zero");
  if (input.day_of_year < 1 || input.day_of_year > 366)
    throw std::invalid_argument(record(input) + "day of year " + std::to_string(input.day_of_year) +
                                " is not in 1..366");
  const double bound = extraterrestrial_normal_irradiance(input.day_of_year);
  check_irradiance(input, "direct normal irradiance", input.direct_normal_w_m2, bound);
  check_irradiance(input, "diffuse horizontal irradiance", input.diffuse_horizontal_w_m2, bound);
  const double td = input.dew_point_c;
  if (!std::isnan(td) && !(td >= PerezAllWeatherSky::kMinDewPointC && td <= PerezAllWeatherSky::kMaxDewPointC))
    throw std::invalid_argument(record(input) + "dew point " + decimal_text(td) + " deg C is outside [" +
                                decimal_text(PerezAllWeatherSky::kMinDewPointC) + ", " +
                                decimal_text(PerezAllWeatherSky::kMaxDewPointC) + "] (NaN: missing)");
}

}  // namespace

double extraterrestrial_normal_irradiance(int day_of_year) {
  const double day_angle = 2.0 * kPiD * (day_of_year - 1) / 365.0;
  const double eccentricity = 1.00011 + 0.034221 * std::cos(day_angle) + 0.00128 * std::sin(day_angle) +
                              0.000719 * std::cos(2.0 * day_angle) + 0.000077 * std::sin(2.0 * day_angle);
  return kPerezSolarConstant * eccentricity;
}

double precipitable_water_cm(double dew_point_c) { return std::exp(0.07 * dew_point_c - 0.075); }

double perez_clearness(double direct_normal_w_m2, double diffuse_horizontal_w_m2, double zenith_rad) {
  if (!(diffuse_horizontal_w_m2 > 0.0)) return std::numeric_limits<double>::infinity();
  const double k = 1.041 * zenith_rad * zenith_rad * zenith_rad;
  return ((diffuse_horizontal_w_m2 + direct_normal_w_m2) / diffuse_horizontal_w_m2 + k) / (1.0 + k);
}

double perez_brightness(double diffuse_horizontal_w_m2, double zenith_rad, int day_of_year) {
  return diffuse_horizontal_w_m2 * relative_air_mass(zenith_rad) / extraterrestrial_normal_irradiance(day_of_year);
}

int perez_clearness_bin(double clearness) {
  int bin = 1;
  for (double bound : kBinLowerBounds)
    if (clearness >= bound) ++bin;
  return bin;
}

PerezCoefficients perez_all_weather_coefficients(int bin, double zenith_rad, double brightness) {
  check_bin(bin);
  const auto& x = kLuminanceTable[bin - 1];
  const double Z = zenith_rad, D = brightness;
  PerezCoefficients p;
  p.A = linear_form(x[0], Z, D);
  p.B = linear_form(x[1], Z, D);
  p.E = linear_form(x[4], Z, D);
  if (bin == 1) {  // the 1993 paper's eqs. for c and d in the overcast bin
    p.C = std::exp(std::pow(D * (x[2][0] + x[2][1] * Z), x[2][2])) - x[2][3];
    p.D = -std::exp(D * (x[3][0] + x[3][1] * Z)) + x[3][2] + D * x[3][3];
  } else {
    p.C = linear_form(x[2], Z, D);
    p.D = linear_form(x[3], Z, D);
  }
  return p;
}

double perez_diffuse_efficacy(int bin, double water_cm, double zenith_rad, double brightness) {
  check_bin(bin);
  const EfficacyRow& k = kDiffuseEfficacy[bin - 1];
  return k.a + k.b * water_cm + k.c * std::cos(zenith_rad) + k.d * std::log(brightness);
}

double perez_direct_efficacy(int bin, double water_cm, double zenith_rad, double brightness) {
  check_bin(bin);
  const EfficacyRow& k = kDirectEfficacy[bin - 1];
  return std::max(0.0, k.a + k.b * water_cm + k.c * std::exp(5.73 * zenith_rad - 5.0) + k.d * brightness);
}

// ---- The normalisation integral ----

// In u = cos(theta) and the azimuth phi measured from the sun's vertical (the sky is symmetric about
// it, so phi in [0, pi], doubled). Pieces in u end at the theta factor's floor (u = 0.01), at the
// sun's height (graded toward it from both sides: the gamma factor has a cusp at the sun), where the
// theta factor changes sign, and where a circle on which the gamma factor changes sign is tangent to
// a row; pieces in phi end where a row crosses such a circle. Grading in phi as well, toward the
// sun's vertical, changes the worst error by less than 5 %.
PerezAllWeatherSky::HorizontalIntegral PerezAllWeatherSky::horizontal_integral(const PerezCoefficients& c,
                                                                              double sun_zenith_rad) {
  const double us = std::cos(sun_zenith_rad), ss = std::sin(sun_zenith_rad);
  std::vector<double> u_points = {PerezCoefficients::kMinCosTheta, us};
  if (c.A < -1.0 && c.B < 0.0) u_points.push_back(c.B / std::log(-1.0 / c.A));  // 1 + A e^(B/u) = 0
  const std::vector<double> gamma_roots = gamma_factor_roots(c);
  for (double root : gamma_roots) {
    u_points.push_back(std::cos(sun_zenith_rad + root));
    u_points.push_back(std::cos(sun_zenith_rad - root));
  }
  const std::vector<double> u_breaks = breakpoints(u_points, 0.0, 1.0);

  bool clipped = false;
  const auto row = [&](double u) {
    const double s = std::sqrt(std::max(0.0, 1.0 - u * u));
    const double theta_factor = c.theta_factor(u);
    const auto f = [&](double phi) {
      const double cos_gamma = std::clamp(u * us + s * ss * std::cos(phi), -1.0, 1.0);
      const double value = theta_factor * c.gamma_factor(std::acos(cos_gamma), cos_gamma);
      if (value < 0.0) clipped = true;
      return std::max(0.0, value);
    };
    std::vector<double> phi_points;
    for (double root : gamma_roots)
      if (s * ss > 0.0) phi_points.push_back(std::acos(std::clamp((std::cos(root) - u * us) / (s * ss), -1.0, 1.0)));
    const std::vector<double> phi_breaks = breakpoints(phi_points, 0.0, kPiD);
    double sum = 0.0;
    for (size_t k = 0; k + 1 < phi_breaks.size(); ++k) sum += integrate(f, phi_breaks[k], phi_breaks[k + 1], false);
    return u * sum;
  };

  double sum = 0.0;
  for (size_t k = 0; k + 1 < u_breaks.size(); ++k) {
    const double a = u_breaks[k], b = u_breaks[k + 1];
    if (b == us)  // graded toward the sun's row from below: integrate in the mirrored variable
      sum += integrate([&](double v) { return row(b - v); }, 0.0, b - a, true);
    else
      sum += integrate(row, a, b, a == us);
  }
  return HorizontalIntegral{2.0 * sum, clipped};
}

// ---- The sky ----

PerezAllWeatherSky PerezAllWeatherSky::create(const PerezSkyInput& input) {
  check(input);
  PerezAllWeatherSky sky;
  sky.direct_normal_w_m2_ = input.direct_normal_w_m2;
  sky.diffuse_horizontal_w_m2_ = input.diffuse_horizontal_w_m2;

  // Below the horizon the model sees the sun on the horizon, at its azimuth (as gendaymtx does).
  const Eigen::Vector3d sun = input.sun.cast<double>().normalized();
  const double horizontal = std::hypot(sun.x(), sun.y());
  sky.sun_below_horizon_ = sun.z() < 0.0;
  if (sky.sun_below_horizon_) {
    sky.zenith_ = 0.5 * kPiD;
    sky.model_sun_ = horizontal > 0.0 ? Eigen::Vector3d(sun.x() / horizontal, sun.y() / horizontal, 0.0)
                                      : Eigen::Vector3d::UnitY();  // at the nadir: any azimuth
  } else {
    sky.zenith_ = std::atan2(horizontal, sun.z());
    sky.model_sun_ = sun;
  }

  sky.water_cm_ = std::isnan(input.dew_point_c) ? kDefaultPrecipitableWaterCm
                                                : fenestra::precipitable_water_cm(input.dew_point_c);
  sky.clearness_ = perez_clearness(input.direct_normal_w_m2, input.diffuse_horizontal_w_m2, sky.zenith_);
  sky.brightness_ = perez_brightness(input.diffuse_horizontal_w_m2, sky.zenith_, input.day_of_year);
  sky.bin_ = perez_clearness_bin(sky.clearness_);

  sky.coefficients_ = perez_all_weather_coefficients(sky.bin_, sky.zenith_, sky.coefficient_brightness());
  if (sky.coefficients_.B > 0.0) {
    sky.coefficients_.B = 0.0;
    sky.gradation_held_ = true;
  }

  sky.diffuse_efficacy_ = perez_diffuse_efficacy(sky.bin_, sky.water_cm_, sky.zenith_, sky.efficacy_brightness());
  sky.direct_efficacy_ = perez_direct_efficacy(sky.bin_, sky.water_cm_, sky.zenith_, sky.efficacy_brightness());
  sky.diffuse_lux_ = input.diffuse_horizontal_w_m2 * sky.diffuse_efficacy_;
  sky.direct_lux_ = sky.sun_below_horizon_ ? 0.0 : input.direct_normal_w_m2 * sky.direct_efficacy_;

  if (sky.diffuse_lux_ > 0.0) {
    const HorizontalIntegral integral = horizontal_integral(sky.coefficients_, sky.zenith_);
    sky.clipped_ = integral.clipped;
    sky.uniform_ = !(integral.value > 0.0);
    sky.scale_ = sky.diffuse_lux_ / (sky.uniform_ ? kPiD : integral.value);
  }
  return sky;
}

double PerezAllWeatherSky::efficacy_brightness() const {
  return std::clamp(brightness_, kMinBrightness, kMaxBrightness);
}

double PerezAllWeatherSky::coefficient_brightness() const {
  const bool intermediate = bin_ >= 2 && bin_ <= 5;
  return intermediate ? std::max(efficacy_brightness(), kIntermediateMinBrightness) : efficacy_brightness();
}

double PerezAllWeatherSky::luminance(const Vec3& dir) const {
  const Eigen::Vector3d d = dir.cast<double>();
  return luminance(row(d.z()), d);
}

PerezAllWeatherSky::Row PerezAllWeatherSky::row(double cos_theta) const {
  Row r;
  r.cos_theta = cos_theta;
  if (cos_theta < 0.0) return r;  // below the horizon: 0
  r.scaled_gradation = uniform_ ? scale_ : scale_ * coefficients_.theta_factor(cos_theta);
  return r;
}

double PerezAllWeatherSky::luminance(const Row& row, const Eigen::Vector3d& dir) const {
  if (row.cos_theta < 0.0 || uniform_) return row.scaled_gradation;
  const double cos_gamma = std::clamp(dir.dot(model_sun_), -1.0, 1.0);
  // max(0, F): F < 0 where the model leaves its domain (clipped()); scale_ >= 0.
  return std::max(0.0, row.scaled_gradation * coefficients_.gamma_factor(std::acos(cos_gamma), cos_gamma));
}

double PerezAllWeatherSky::zenith_luminance() const {
  if (uniform_) return scale_;
  return scale_ * std::max(0.0, coefficients_(1.0, zenith_, std::cos(zenith_)));
}

std::string PerezAllWeatherSky::to_string() const {
  std::ostringstream s;
  s.precision(4);
  s << "PerezAllWeatherSky(sun zenith " << zenith_ / kDegree << " deg"
    << (sun_below_horizon_ ? " (below the horizon)" : "") << ", DNI " << direct_normal_w_m2_ << " W/m2, DHI "
    << diffuse_horizontal_w_m2_ << " W/m2, water " << water_cm_ << " cm; clearness " << clearness_ << " (bin "
    << bin_ << "), brightness " << brightness_ << "; a " << coefficients_.A << " b " << coefficients_.B << " c "
    << coefficients_.C << " d " << coefficients_.D << " e " << coefficients_.E << "; diffuse " << diffuse_lux_
    << " lx (" << diffuse_efficacy_ << " lm/W), direct " << direct_lux_ << " lx (" << direct_efficacy_
    << " lm/W), zenith " << zenith_luminance() << " cd/m2";
  if (gradation_held_) s << "; b > 0 held at 0";
  if (clipped_) s << "; negative luminance set to 0";
  if (uniform_) s << "; uniform (F <= 0 everywhere)";
  s << ")";
  return s.str();
}

}  // namespace fenestra
