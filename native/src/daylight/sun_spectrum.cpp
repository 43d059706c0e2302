#include "daylight/sun_spectrum.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "math/constants.h"

namespace fenestra {
namespace {

constexpr double kLuminousEfficacy = 683.0;  // lm/W, definition of the candela (555 nm)

// Piecewise-linear spectrum given at increasing wavelengths; zero outside its span.
template <size_t N>
double interpolate(const double (&lambda)[N], const double (&value)[N], double x) {
  if (!(x >= lambda[0] && x <= lambda[N - 1])) return 0.0;
  const size_t i = std::upper_bound(lambda, lambda + N, x) - lambda;
  if (i == N) return value[N - 1];
  const double t = (x - lambda[i - 1]) / (lambda[i] - lambda[i - 1]);
  return value[i - 1] + t * (value[i] - value[i - 1]);
}

// Extraterrestrial solar spectral radiance, W/(m^2 sr nm), from the reference implementation of
// Preetham et al. (1999) (also in Mitsuba 0.6, src/emitters/sunsky/sunmodel.h). The values are used
// as given: with the 0.53 degree disk they give 126.5 klx normal illuminance outside the
// atmosphere, within 1% of the IES solar illuminance constant (127.5 klx), so no unit factor applies.
constexpr double kSolarLambda[38] = {380, 390, 400, 410, 420, 430, 440, 450, 460, 470, 480, 490, 500,
                                     510, 520, 530, 540, 550, 560, 570, 580, 590, 600, 610, 620, 630,
                                     640, 650, 660, 670, 680, 690, 700, 710, 720, 730, 740, 750};
constexpr double kSolarRadiance[38] = {
    16559.0, 16233.7, 21127.5, 25888.2, 25829.1, 24232.3, 26760.5, 29658.3, 30545.4, 30057.5,
    30663.7, 28830.4, 28712.1, 27825.0, 27100.6, 27233.6, 26361.3, 25503.8, 25060.2, 25311.6,
    25355.9, 25134.2, 24631.5, 24173.2, 23685.3, 23212.1, 22827.7, 22339.8, 21970.2, 21526.7,
    21097.9, 20728.3, 20240.4, 19870.8, 19427.2, 19072.4, 18628.9, 18259.2};

// Ozone absorption coefficient k_o, 1/cm (Iqbal 1983, p. 127, via Preetham et al. 1999).
constexpr double kOzoneLambda[64] = {300, 305, 310, 315, 320, 325, 330, 335, 340, 345, 350, 355, 445,
                                     450, 455, 460, 465, 470, 475, 480, 485, 490, 495, 500, 505, 510,
                                     515, 520, 525, 530, 535, 540, 545, 550, 555, 560, 565, 570, 575,
                                     580, 585, 590, 595, 600, 605, 610, 620, 630, 640, 650, 660, 670,
                                     680, 690, 700, 710, 720, 730, 740, 750, 760, 770, 780, 790};
constexpr double kOzoneAbsorption[64] = {
    10.0,  4.8,   2.7,   1.35,  0.8,   0.380, 0.160, 0.075, 0.04,  0.019, 0.007, 0.0,   0.003,
    0.003, 0.004, 0.006, 0.008, 0.009, 0.012, 0.014, 0.017, 0.021, 0.025, 0.03,  0.035, 0.04,
    0.045, 0.048, 0.057, 0.063, 0.07,  0.075, 0.08,  0.085, 0.095, 0.103, 0.110, 0.12,  0.122,
    0.12,  0.118, 0.115, 0.12,  0.125, 0.130, 0.12,  0.105, 0.09,  0.079, 0.067, 0.057, 0.048,
    0.036, 0.028, 0.023, 0.018, 0.014, 0.011, 0.010, 0.009, 0.007, 0.004, 0.0,   0.0};

// Uniformly mixed gases (oxygen A band), coefficient k_g (Iqbal 1983, p. 130).
constexpr double kMixedGasLambda[4] = {759, 760, 770, 771};
constexpr double kMixedGasAbsorption[4] = {0.0, 3.0, 0.210, 0.0};

// Water vapour k_wa, 1/cm (Iqbal 1983, p. 130).
constexpr double kWaterLambda[13] = {689, 690, 700, 710, 720, 730, 740, 750, 760, 770, 780, 790, 800};
constexpr double kWaterAbsorption[13] = {0.0,   0.160e-1, 0.240e-1, 0.125e-1, 0.100e+1, 0.870,   0.610e-1,
                                         0.100e-2, 0.100e-4, 0.100e-4, 0.600e-3, 0.175e-1, 0.360e-1};

constexpr double kOzoneCm = 0.35;        // ozone column, cm at NTP
constexpr double kWaterCm = 2.0;         // precipitable water vapour, cm
constexpr double kAngstromAlpha = 1.3;   // ratio of small to large aerosol particles

// CIE 1931 2-degree colour matching functions, 380-780 nm every 5 nm (CIE 15:2004, Table T.4).
constexpr double kCmfStart = 380.0, kCmfStep = 5.0;
constexpr double kCmf[81][3] = {
    {0.001368, 0.000039, 0.006450}, {0.002236, 0.000064, 0.010550}, {0.004243, 0.000120, 0.020050},
    {0.007650, 0.000217, 0.036210}, {0.014310, 0.000396, 0.067850}, {0.023190, 0.000640, 0.110200},
    {0.043510, 0.001210, 0.207400}, {0.077630, 0.002180, 0.371300}, {0.134380, 0.004000, 0.645600},
    {0.214770, 0.007300, 1.039050}, {0.283900, 0.011600, 1.385600}, {0.328500, 0.016840, 1.622960},
    {0.348280, 0.023000, 1.747060}, {0.348060, 0.029800, 1.782600}, {0.336200, 0.038000, 1.772110},
    {0.318700, 0.048000, 1.744100}, {0.290800, 0.060000, 1.669200}, {0.251100, 0.073900, 1.528100},
    {0.195360, 0.090980, 1.287640}, {0.142100, 0.112600, 1.041900}, {0.095640, 0.139020, 0.812950},
    {0.057950, 0.169300, 0.616200}, {0.032010, 0.208020, 0.465180}, {0.014700, 0.258600, 0.353300},
    {0.004900, 0.323000, 0.272000}, {0.002400, 0.407300, 0.212300}, {0.009300, 0.503000, 0.158200},
    {0.029100, 0.608200, 0.111700}, {0.063270, 0.710000, 0.078250}, {0.109600, 0.793200, 0.057250},
    {0.165500, 0.862000, 0.042160}, {0.225750, 0.914850, 0.029840}, {0.290400, 0.954000, 0.020300},
    {0.359700, 0.980300, 0.013400}, {0.433450, 0.994950, 0.008750}, {0.512050, 1.000000, 0.005750},
    {0.594500, 0.995000, 0.003900}, {0.678400, 0.978600, 0.002750}, {0.762100, 0.952000, 0.002100},
    {0.842500, 0.915400, 0.001800}, {0.916300, 0.870000, 0.001650}, {0.978600, 0.816300, 0.001400},
    {1.026300, 0.757000, 0.001100}, {1.056700, 0.694900, 0.001000}, {1.062200, 0.631000, 0.000800},
    {1.045600, 0.566800, 0.000600}, {1.002600, 0.503000, 0.000340}, {0.938400, 0.441200, 0.000240},
    {0.854450, 0.381000, 0.000190}, {0.751400, 0.321000, 0.000100}, {0.642400, 0.265000, 0.000050},
    {0.541900, 0.217000, 0.000030}, {0.447900, 0.175000, 0.000020}, {0.360800, 0.138200, 0.000010},
    {0.283500, 0.107000, 0.000000}, {0.218700, 0.081600, 0.000000}, {0.164900, 0.061000, 0.000000},
    {0.121200, 0.044580, 0.000000}, {0.087400, 0.032000, 0.000000}, {0.063600, 0.023200, 0.000000},
    {0.046770, 0.017000, 0.000000}, {0.032900, 0.011920, 0.000000}, {0.022700, 0.008210, 0.000000},
    {0.015840, 0.005723, 0.000000}, {0.011359, 0.004102, 0.000000}, {0.008111, 0.002929, 0.000000},
    {0.005790, 0.002091, 0.000000}, {0.004109, 0.001484, 0.000000}, {0.002899, 0.001047, 0.000000},
    {0.002049, 0.000740, 0.000000}, {0.001440, 0.000520, 0.000000}, {0.001000, 0.000361, 0.000000},
    {0.000690, 0.000249, 0.000000}, {0.000476, 0.000172, 0.000000}, {0.000332, 0.000120, 0.000000},
    {0.000235, 0.000085, 0.000000}, {0.000166, 0.000060, 0.000000}, {0.000117, 0.000042, 0.000000},
    {0.000083, 0.000030, 0.000000}, {0.000059, 0.000021, 0.000000}, {0.000042, 0.000015, 0.000000}};

}  // namespace

double relative_air_mass(double sun_zenith_rad) {
  const double zenith_deg = sun_zenith_rad * 180.0 / kPiD;
  return 1.0 / (std::cos(sun_zenith_rad) + 0.15 * std::pow(93.885 - zenith_deg, -1.253));
}

double extraterrestrial_solar_radiance(double lambda_nm) {
  return interpolate(kSolarLambda, kSolarRadiance, lambda_nm);
}

double direct_beam_transmittance(double lambda_nm, double turbidity, double air_mass) {
  const double m = air_mass;
  const double lambda_um = lambda_nm / 1000.0;
  const double beta = 0.04608 * turbidity - 0.04586;  // Angstrom turbidity coefficient
  const double rayleigh = 0.008735 * std::pow(lambda_um, -4.08);
  const double aerosol = beta * std::pow(lambda_um, -kAngstromAlpha);
  const double ozone = interpolate(kOzoneLambda, kOzoneAbsorption, lambda_nm) * kOzoneCm;
  // The gas and water-vapour bands saturate, hence their non-linear dependence on the air mass.
  const double kg_m = interpolate(kMixedGasLambda, kMixedGasAbsorption, lambda_nm) * m;
  const double mixed_gases = 1.41 * kg_m / std::pow(1.0 + 118.93 * kg_m, 0.45);
  const double kwa_w_m = interpolate(kWaterLambda, kWaterAbsorption, lambda_nm) * kWaterCm * m;
  const double water = 0.2385 * kwa_w_m / std::pow(1.0 + 20.07 * kwa_w_m, 0.45);
  return std::exp(-m * (rayleigh + aerosol + ozone) - mixed_gases - water);
}

Eigen::Vector3d solar_disk_xyz(double turbidity, double air_mass) {
  // Trapezoidal rule on the colour-matching grid over the span of the solar table (380-750 nm);
  // y-bar beyond 750 nm holds about 1e-5 of the luminance.
  const int last = static_cast<int>((kSolarLambda[37] - kCmfStart) / kCmfStep);
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  for (int i = 0; i <= last; ++i) {
    const double lambda = kCmfStart + kCmfStep * i;
    const double weight = (i == 0 || i == last) ? 0.5 * kCmfStep : kCmfStep;
    const double radiance =
        extraterrestrial_solar_radiance(lambda) * direct_beam_transmittance(lambda, turbidity, air_mass);
    xyz += weight * radiance * Eigen::Vector3d(kCmf[i][0], kCmf[i][1], kCmf[i][2]);
  }
  return kLuminousEfficacy * xyz;
}

}  // namespace fenestra
