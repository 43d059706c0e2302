#pragma once
// Analytic daylight models. Radiance is linear sRGB (Rec. 709 primaries, D65 white) in cd/m^2, so
// luminance(rgb) (math/vec.h) is the model's luminance Y and sensors read illuminance in lux.
// Directions: unit world vectors, +Z up; `sun` points toward the sun.
#include "math/vec.h"

namespace fenestra {

// Perez et al. all-weather luminance distribution, the shape used by Preetham:
// F(theta, gamma) = (1 + A exp(B / cos theta)) (1 + C exp(D gamma) + E cos^2 gamma).
struct PerezCoefficients {
  double A = 0, B = 0, C = 0, D = 0, E = 0;
  // 1 + A exp(B / cos theta), with cos theta held at kMinCosTheta or above: B < 0 for every
  // Preetham turbidity (and the all-weather sky holds B at 0 or below), so the factor tends to 1 at
  // the horizon and the floor only avoids 0 / 0.
  static constexpr double kMinCosTheta = 0.01;
  double theta_factor(double cos_theta) const;
  double gamma_factor(double gamma, double cos_gamma) const;  // 1 + C exp(D gamma) + E cos^2 gamma
  double operator()(double cos_theta, double gamma, double cos_gamma) const {
    return theta_factor(cos_theta) * gamma_factor(gamma, cos_gamma);
  }
};

// Preetham, Shirley, Smits (1999), "A practical analytic model for daylight": clear-sky radiance
// for a turbidity and a sun above the horizon (the sun disk itself excluded).
class PreethamSky {
 public:
  // Valid turbidity range of the model; the constructor throws std::invalid_argument outside it
  // and when the sun is not above the horizon (sun.z() <= 0). `sun` need not be unit length.
  static constexpr double kMinTurbidity = 1.7, kMaxTurbidity = 10.0;
  PreethamSky(double turbidity, const Vec3& sun);

  Rgb radiance(const Vec3& dir) const;  // cd/m^2; dir.z() < 0 (below horizon) gives 0
  // The same, for many directions sharing a polar angle (a map row): the factors that depend on
  // theta alone are computed once per row. `dir.z()` must equal the row's cos(theta).
  struct Row {
    double cos_theta = 0.0;
    double scaled_theta_factor[3] = {0.0, 0.0, 0.0};  // zenith value / F(0, theta_s) x (1 + A e^(B / cos))
  };
  Row row(double cos_theta) const;
  Rgb radiance(const Row& row, const Vec3& dir) const;
  double luminance(const Vec3& dir) const;  // Y, cd/m^2
  double zenith_luminance() const { return zenith_Y_; }  // Y_z, cd/m^2
  double zenith_x() const { return zenith_x_; }
  double zenith_y() const { return zenith_y_; }
  const PerezCoefficients& perez_Y() const { return perez_[0]; }
  const PerezCoefficients& perez_x() const { return perez_[1]; }
  const PerezCoefficients& perez_y() const { return perez_[2]; }
  double turbidity() const { return turbidity_; }
  const Vec3& sun() const { return sun_; }

 private:
  double turbidity_;
  Vec3 sun_;
  double sun_zenith_;
  double zenith_Y_, zenith_x_, zenith_y_;
  PerezCoefficients perez_[3];  // Y, x, y
  double norm_[3];              // 1 / F(0, theta_s) per channel
  Vec3 sun_f_;                  // single-precision copies for the per-pixel path
  float perez_f_[3][3];         // C, D, E per channel
  double scale_[3];             // zenith value x norm_ per channel: value = scale_ F(theta, gamma)
};

// The solar disk seen through the atmosphere.
struct SunDisk {
  static constexpr double kAngularDiameterDeg = 0.53;
  Rgb radiance = Rgb::Zero();  // mean disk radiance, cd/m^2 (linear sRGB)
  double solid_angle = 0.0;    // sr
  Rgb normal_illuminance() const { return radiance * static_cast<float>(solid_angle); }  // lux
};
// Sun radiance from Preetham's spectral attenuation (Rayleigh, Angstrom aerosol from turbidity,
// ozone, mixed gases, water vapour, relative air mass) applied to the extraterrestrial spectrum
// (daylight/sun_spectrum.h). At or below the horizon the disk keeps its solid angle and has zero
// radiance. Throws std::invalid_argument for a turbidity outside PreethamSky's range or a zenith
// angle that is negative or not finite.
SunDisk preetham_sun(double turbidity, double sun_zenith_rad);
// The same disk outside the atmosphere (no attenuation): the solar illuminance constant.
SunDisk extraterrestrial_sun();

// CIE standard overcast sky: L / L_z = (1 + 2 cos theta) / 3; horizontal illuminance 7 pi / 9 L_z.
// Zero below the horizon (cos theta < 0).
double cie_overcast_relative(double cos_theta);
// CIE standard clear sky (CIE S 011 type 12): L / L_z for direction dir and sun direction sun
// (both unit). Zero below the horizon (dir.z() < 0).
double cie_clear_relative(const Vec3& dir, const Vec3& sun);

}  // namespace fenestra
