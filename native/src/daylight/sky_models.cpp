#include "daylight/sky_models.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "daylight/sun_spectrum.h"
#include "math/constants.h"
#include "util/number_text.h"

namespace fenestra {
namespace {


void check_turbidity(const char* model, double turbidity) {
  if (!(turbidity >= PreethamSky::kMinTurbidity && turbidity <= PreethamSky::kMaxTurbidity))
    throw std::invalid_argument(std::string(model) + ": turbidity " + decimal_text(turbidity) +
                                " is outside [1.7, 10], the range the Preetham model was fitted for");
}

// CIE XYZ to linear sRGB (IEC 61966-2-1: Rec. 709 primaries, D65 white). Colours outside the sRGB
// gamut give negative channels: they are clamped to zero and the colour is then scaled so that
// luminance() (math/vec.h) returns Y exactly. The scale also absorbs the difference, in the fifth
// digit, between luminance()'s rounded weights and the luminance row of the inverse matrix.
Rgb linear_srgb_from_xyz(double X, double Y, double Z) {
  const Rgb rgb(static_cast<float>(std::max(0.0, 3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z)),
                static_cast<float>(std::max(0.0, -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z)),
                static_cast<float>(std::max(0.0, 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z)));
  const double weighted = luminance(rgb);
  if (!(weighted > 0.0) || !(Y > 0.0)) return Rgb::Zero();
  return rgb * static_cast<float>(Y / weighted);
}

Rgb linear_srgb_from_xyz(const Eigen::Vector3d& xyz) { return linear_srgb_from_xyz(xyz[0], xyz[1], xyz[2]); }

// Preetham et al. (1999), Appendix A.2: each Perez coefficient is linear in turbidity T.
struct LinearInTurbidity {
  double slope, intercept;
  double operator()(double T) const { return slope * T + intercept; }
};
constexpr LinearInTurbidity kPerezY[5] = {
    {0.1787, -1.4630}, {-0.3554, 0.4275}, {-0.0227, 5.3251}, {0.1206, -2.5771}, {-0.0670, 0.3703}};
constexpr LinearInTurbidity kPerezX[5] = {
    {-0.0193, -0.2592}, {-0.0665, 0.0008}, {-0.0004, 0.2125}, {-0.0641, -0.8989}, {-0.0033, 0.0452}};
constexpr LinearInTurbidity kPerezYChroma[5] = {
    {-0.0167, -0.2608}, {-0.0950, 0.0092}, {-0.0079, 0.2102}, {-0.0441, -1.6537}, {-0.0109, 0.0529}};

PerezCoefficients perez_at(const LinearInTurbidity (&c)[5], double T) {
  return PerezCoefficients{c[0](T), c[1](T), c[2](T), c[3](T), c[4](T)};
}

// Zenith chromaticity (Appendix A.2): [T^2 T 1] M [theta_s^3 theta_s^2 theta_s 1]^T.
using ChromaticityMatrix = double[3][4];
constexpr ChromaticityMatrix kZenithX = {{0.00166, -0.00375, 0.00209, 0.0},
                                         {-0.02903, 0.06377, -0.03202, 0.00394},
                                         {0.11693, -0.21196, 0.06052, 0.25886}};
constexpr ChromaticityMatrix kZenithY = {{0.00275, -0.00610, 0.00317, 0.0},
                                         {-0.04214, 0.08970, -0.04153, 0.00516},
                                         {0.15346, -0.26756, 0.06670, 0.26688}};

double zenith_chromaticity(const ChromaticityMatrix& m, double T, double theta_s) {
  const double t[4] = {theta_s * theta_s * theta_s, theta_s * theta_s, theta_s, 1.0};
  const double turbidity_powers[3] = {T * T, T, 1.0};
  double sum = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) sum += turbidity_powers[i] * m[i][j] * t[j];
  return sum;
}

// Zenith luminance (Appendix A.2), given in kcd/m^2 by the paper; returned in cd/m^2. Positive
// over the model's range: chi < pi/2 and -0.2155 T + 2.4192 > 0 for T < 11.2.
double zenith_luminance_cd(double T, double theta_s) {
  const double chi = (4.0 / 9.0 - T / 120.0) * (kPiD - 2.0 * theta_s);
  return 1000.0 * ((4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192);
}

double sun_disk_solid_angle() {
  const double half_angle = 0.5 * SunDisk::kAngularDiameterDeg * kPiD / 180.0;
  return 2.0 * kPiD * (1.0 - std::cos(half_angle));
}

SunDisk disk_from_xyz(const Eigen::Vector3d& xyz) {
  SunDisk disk;
  disk.radiance = linear_srgb_from_xyz(xyz);
  disk.solid_angle = sun_disk_solid_angle();
  return disk;
}

}  // namespace

double PerezCoefficients::theta_factor(double cos_theta) const {
  return 1.0 + A * std::exp(B / std::max(cos_theta, kMinCosTheta));
}

double PerezCoefficients::gamma_factor(double gamma, double cos_gamma) const {
  return 1.0 + C * std::exp(D * gamma) + E * cos_gamma * cos_gamma;
}

PreethamSky::PreethamSky(double turbidity, const Vec3& sun) : turbidity_(turbidity) {
  check_turbidity("Preetham sky", turbidity);
  if (!is_finite(sun) || !(sun.norm() > 0.0f))
    throw std::invalid_argument("Preetham sky: the sun direction must be a finite, non-zero vector");
  sun_ = sun.normalized();
  if (!(sun_.z() > 0.0f))
    throw std::invalid_argument("Preetham sky: the sun must be above the horizon (its elevation is " +
                                decimal_text(std::asin(std::clamp(static_cast<double>(sun_.z()), -1.0, 1.0)) * 180.0 / kPiD) +
                                " degrees)");
  sun_zenith_ = std::acos(std::min(1.0, static_cast<double>(sun_.z())));

  zenith_Y_ = zenith_luminance_cd(turbidity, sun_zenith_);
  zenith_x_ = zenith_chromaticity(kZenithX, turbidity, sun_zenith_);
  zenith_y_ = zenith_chromaticity(kZenithY, turbidity, sun_zenith_);
  perez_[0] = perez_at(kPerezY, turbidity);
  perez_[1] = perez_at(kPerezX, turbidity);
  perez_[2] = perez_at(kPerezYChroma, turbidity);
  // At the zenith theta = 0 and gamma = theta_s: F(0, theta_s) normalises each channel to its
  // zenith value.
  for (int c = 0; c < 3; ++c) norm_[c] = 1.0 / perez_[c](1.0, sun_zenith_, std::cos(sun_zenith_));
  scale_[0] = zenith_Y_ * norm_[0];
  scale_[1] = zenith_x_ * norm_[1];
  scale_[2] = zenith_y_ * norm_[2];
  sun_f_ = sun_.cast<float>();
  for (int c = 0; c < 3; ++c) {
    perez_f_[c][0] = static_cast<float>(perez_[c].C);
    perez_f_[c][1] = static_cast<float>(perez_[c].D);
    perez_f_[c][2] = static_cast<float>(perez_[c].E);
  }
}

double PreethamSky::luminance(const Vec3& dir) const {
  if (dir.z() < 0.0f) return 0.0;
  const double cos_gamma = std::clamp(static_cast<double>(dir.dot(sun_)), -1.0, 1.0);
  return scale_[0] * perez_[0](dir.z(), std::acos(cos_gamma), cos_gamma);
}

PreethamSky::Row PreethamSky::row(double cos_theta) const {
  Row r;
  r.cos_theta = cos_theta;
  for (int c = 0; c < 3; ++c) r.scaled_theta_factor[c] = scale_[c] * perez_[c].theta_factor(cos_theta);
  return r;
}

Rgb PreethamSky::radiance(const Row& row, const Vec3& dir) const {
  if (row.cos_theta < 0.0) return Rgb::Zero();
  // Single precision here: maps evaluate this tens of millions of times, and float keeps ~1e-6.
  const float cos_gamma = std::clamp(dir.dot(sun_f_), -1.0f, 1.0f);
  const float gamma = std::acos(cos_gamma), cos2 = cos_gamma * cos_gamma;
  float v[3];
  for (int c = 0; c < 3; ++c)
    v[c] = static_cast<float>(row.scaled_theta_factor[c]) *
           (1.0f + perez_f_[c][0] * std::exp(perez_f_[c][1] * gamma) + perez_f_[c][2] * cos2);
  const double Y = v[0], x = v[1], y = v[2];
  return linear_srgb_from_xyz(x / y * Y, Y, (1.0 - x - y) / y * Y);
}

Rgb PreethamSky::radiance(const Vec3& dir) const { return radiance(row(dir.z()), dir); }

SunDisk preetham_sun(double turbidity, double sun_zenith_rad) {
  check_turbidity("Preetham sun", turbidity);
  if (!std::isfinite(sun_zenith_rad) || sun_zenith_rad < 0.0)
    throw std::invalid_argument("Preetham sun: zenith angle " + decimal_text(sun_zenith_rad) +
                                " rad must be finite and not negative");
  if (sun_zenith_rad >= 0.5 * kPiD) {
    SunDisk dark;
    dark.solid_angle = sun_disk_solid_angle();
    return dark;
  }
  return disk_from_xyz(solar_disk_xyz(turbidity, relative_air_mass(sun_zenith_rad)));
}

// No air mass, no attenuation: the turbidity given is irrelevant.
SunDisk extraterrestrial_sun() { return disk_from_xyz(solar_disk_xyz(PreethamSky::kMinTurbidity, 0.0)); }

double cie_overcast_relative(double cos_theta) {
  if (cos_theta < 0.0) return 0.0;
  return (1.0 + 2.0 * cos_theta) / 3.0;
}

namespace {

// CIE S 011/E:2003 type 12 (CIE standard clear sky, low luminance turbidity).
constexpr double kClearA = -1.0, kClearB = -0.32;                    // gradation
constexpr double kClearC = 10.0, kClearD = -3.0, kClearE = 0.45;     // indicatrix

// Gradation phi(Z) = 1 + a exp(b / cos Z); phi(90 deg) = 1, the limit at the horizon.
double clear_gradation(double cos_z) { return cos_z > 0.0 ? 1.0 + kClearA * std::exp(kClearB / cos_z) : 1.0; }

// Scattering indicatrix f(chi) = 1 + c (exp(d chi) - exp(d pi / 2)) + e cos^2 chi.
double clear_indicatrix(double chi, double cos_chi) {
  return 1.0 + kClearC * (std::exp(kClearD * chi) - std::exp(kClearD * 0.5 * kPiD)) + kClearE * cos_chi * cos_chi;
}

}  // namespace

double cie_clear_relative(const Vec3& dir, const Vec3& sun) {
  if (dir.z() < 0.0f) return 0.0;
  const double cos_sun_zenith = std::clamp(static_cast<double>(sun.z()), -1.0, 1.0);
  const double cos_gamma = std::clamp(static_cast<double>(dir.dot(sun)), -1.0, 1.0);
  const double at_dir = clear_indicatrix(std::acos(cos_gamma), cos_gamma) * clear_gradation(dir.z());
  const double at_zenith = clear_indicatrix(std::acos(cos_sun_zenith), cos_sun_zenith) * clear_gradation(1.0);
  return at_dir / at_zenith;
}

}  // namespace fenestra
