#include "daylight/sky_models.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

#include "daylight/sun_spectrum.h"

using namespace fenestra;

namespace {

constexpr double kDeg = kPiD / 180.0;

Vec3 direction(double zenith_deg, double azimuth_deg) {
  const double z = zenith_deg * kDeg, a = azimuth_deg * kDeg;
  return Vec3(static_cast<float>(std::sin(z) * std::sin(a)), static_cast<float>(std::sin(z) * std::cos(a)),
              static_cast<float>(std::cos(z)));
}

// Zenith angle the sky sees for a sun given in float.
double zenith_of(const Vec3& sun) { return std::acos(static_cast<double>(sun.normalized().z())); }

// Illuminance on a horizontal plane from a radiance field over the upper hemisphere: midpoint rule
// in zenith angle and azimuth, integrand L cos(theta) sin(theta).
double horizontal_illuminance(const std::function<double(const Vec3&)>& radiance, int n_theta = 360) {
  const int n_phi = 2 * n_theta;
  const double d_theta = 0.5 * kPiD / n_theta, d_phi = 2.0 * kPiD / n_phi;
  double sum = 0.0;
  for (int i = 0; i < n_theta; ++i) {
    const double theta = (i + 0.5) * d_theta;
    double ring = 0.0;
    for (int j = 0; j < n_phi; ++j) ring += radiance(direction(theta / kDeg, (j + 0.5) * d_phi / kDeg));
    sum += ring * std::cos(theta) * std::sin(theta);
  }
  return sum * d_theta * d_phi;
}

// Linear sRGB back to CIE XYZ (inverse of the IEC 61966-2-1 matrix).
Eigen::Vector3d xyz_from_rgb(const Rgb& c) {
  return Eigen::Vector3d(0.4124564 * c[0] + 0.3575761 * c[1] + 0.1804375 * c[2],
                         0.2126729 * c[0] + 0.7151522 * c[1] + 0.0721750 * c[2],
                         0.0193339 * c[0] + 0.1191920 * c[1] + 0.9503041 * c[2]);
}

// Clear-sky daylight availability of the IESNA Lighting Handbook (9th ed., 2000, ch. 8, after
// IES RP-21-1984 "Calculation of daylight availability"): direct normal illuminance
// E_dn = E_sc exp(-c m) with E_sc = 127.5 klx, c = 0.21 (clear), m = 1 / sin(altitude); sky
// illuminance on the horizontal E_kh = A + B sin^C(altitude), A = 0.8 klx, B = 15.5 klx, C = 0.5.
double ies_clear_direct_normal_lux(double altitude_deg) {
  return 127.5e3 * std::exp(-0.21 / std::sin(altitude_deg * kDeg));
}
double ies_clear_sky_horizontal_lux(double altitude_deg) {
  return 0.8e3 + 15.5e3 * std::sqrt(std::sin(altitude_deg * kDeg));
}

const std::vector<double> kTurbidities = {1.7, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 7.5, 9.0, 10.0};
const std::vector<double> kSunZeniths = {0.0, 10.0, 20.0, 30.0, 45.0, 60.0, 70.0, 80.0, 85.0, 89.0, 89.9};

}  // namespace

// ---- Preetham sky ----

TEST(SkyModelPreetham, ZenithLuminanceAndChromaticityFollowThePaper) {
  for (double T : kTurbidities)
    for (double zenith_deg : kSunZeniths) {
      const Vec3 sun = direction(zenith_deg, 135.0);
      const PreethamSky sky(T, sun);
      const double ts = zenith_of(sun);
      // Preetham et al. 1999, Appendix A.2, written out independently of the implementation.
      const double chi = (4.0 / 9.0 - T / 120.0) * (kPiD - 2.0 * ts);
      const double Yz = 1000.0 * ((4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192);
      const double t3 = ts * ts * ts, t2 = ts * ts;
      const double xz = T * T * (0.00166 * t3 - 0.00375 * t2 + 0.00209 * ts) +
                        T * (-0.02903 * t3 + 0.06377 * t2 - 0.03202 * ts + 0.00394) +
                        (0.11693 * t3 - 0.21196 * t2 + 0.06052 * ts + 0.25886);
      const double yz = T * T * (0.00275 * t3 - 0.00610 * t2 + 0.00317 * ts) +
                        T * (-0.04214 * t3 + 0.08970 * t2 - 0.04153 * ts + 0.00516) +
                        (0.15346 * t3 - 0.26756 * t2 + 0.06670 * ts + 0.26688);
      SCOPED_TRACE(testing::Message() << "T " << T << ", sun zenith " << zenith_deg << " deg");
      EXPECT_NEAR(sky.zenith_luminance(), Yz, 1e-9 * Yz);
      EXPECT_GT(sky.zenith_luminance(), 0.0);
      EXPECT_NEAR(sky.zenith_x(), xz, 1e-12);
      EXPECT_NEAR(sky.zenith_y(), yz, 1e-12);
      EXPECT_NEAR(sky.perez_Y().A, 0.1787 * T - 1.4630, 1e-12);
      EXPECT_NEAR(sky.perez_Y().D, 0.1206 * T - 2.5771, 1e-12);
      EXPECT_NEAR(sky.perez_x().B, -0.0665 * T + 0.0008, 1e-12);
      EXPECT_NEAR(sky.perez_y().E, -0.0109 * T + 0.0529, 1e-12);
    }
  // A value to read off by hand: T = 2.5, sun 30 degrees from the zenith.
  EXPECT_NEAR(PreethamSky(2.5, direction(30.0, 0.0)).zenith_luminance(), 8193.0, 2.0);
}

TEST(SkyModelPreetham, ZenithReproducesZenithValues) {
  for (double T : kTurbidities)
    for (double zenith_deg : kSunZeniths) {
      const PreethamSky sky(T, direction(zenith_deg, 40.0));
      const Vec3 up(0.0f, 0.0f, 1.0f);
      SCOPED_TRACE(testing::Message() << "T " << T << ", sun zenith " << zenith_deg << " deg");
      EXPECT_NEAR(sky.luminance(up), sky.zenith_luminance(), 1e-9 * sky.zenith_luminance());
      const Rgb rgb = sky.radiance(up);
      EXPECT_NEAR(luminance(rgb), sky.zenith_luminance(), 1e-5 * sky.zenith_luminance());
      // Back to XYZ through the exact inverse: chromaticity is kept; Y differs from luminance()
      // only by the rounding of its weights (a few 1e-5).
      const Eigen::Vector3d xyz = xyz_from_rgb(rgb);
      EXPECT_NEAR(xyz[1], sky.zenith_luminance(), 2e-4 * sky.zenith_luminance());
      EXPECT_NEAR(xyz[0] / xyz.sum(), sky.zenith_x(), 1e-5);
      EXPECT_NEAR(xyz[1] / xyz.sum(), sky.zenith_y(), 1e-5);
    }
}

TEST(SkyModelPreetham, RgbIsLuminanceTrue) {
  for (double T : {1.7, 3.0, 6.0, 10.0})
    for (double zenith_deg : {0.0, 30.0, 60.0, 85.0, 89.9}) {
      const PreethamSky sky(T, direction(zenith_deg, 200.0));
      for (double z = 0.0; z <= 90.0; z += 5.0)
        for (double a = 0.0; a < 360.0; a += 15.0) {
          const Vec3 d = direction(z, a);
          const double Y = sky.luminance(d);
          ASSERT_NEAR(luminance(sky.radiance(d)), Y, 1e-5 * Y)
              << "T " << T << " sun " << zenith_deg << " dir " << z << "/" << a;
        }
    }
}

TEST(SkyModelPreetham, FiniteAndNonNegativeEverywhere) {
  std::vector<Vec3> dirs;
  for (double z = 0.0; z <= 90.0; z += 2.0)
    for (double a = 0.0; a < 360.0; a += 10.0) dirs.push_back(direction(z, a));
  dirs.push_back(Vec3(1.0f, 0.0f, 0.0f));   // exactly on the horizon
  dirs.push_back(Vec3(0.0f, -1.0f, 0.0f));
  dirs.push_back(Vec3(0.0f, 0.0f, 1.0f));
  for (double T = 1.7; T <= 10.0 + 1e-9; T += 0.5)
    for (double zenith_deg : kSunZeniths) {
      const Vec3 sun = direction(zenith_deg, 290.0);
      const PreethamSky sky(T, sun);
      std::vector<Vec3> all = dirs;
      all.push_back(sun.normalized());                                // the sun itself
      all.push_back(Vec3(-sun.x(), -sun.y(), sun.z()).normalized());  // opposite azimuth
      all.push_back(Vec3(sun.x(), sun.y(), 0.0f).normalized());       // horizon below the sun
      for (const Vec3& d : all) {
        const Rgb c = sky.radiance(d);
        ASSERT_TRUE(c.isFinite().all() && (c >= 0.0f).all() && luminance(c) > 0.0f)
            << "T " << T << " sun " << zenith_deg << " dir " << d.transpose() << " rgb " << c.transpose();
      }
      EXPECT_EQ(luminance(sky.radiance(Vec3(0.0f, 0.6f, -0.8f))), 0.0f);  // below the horizon
      EXPECT_EQ(sky.luminance(Vec3(0.0f, 0.0f, -1.0f)), 0.0);
    }
}

TEST(SkyModelPreetham, RejectsWhatTheModelDoesNotCover) {
  const Vec3 sun = direction(40.0, 180.0);
  for (double T : {1.69, 10.01, 0.0, -3.0, std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity()})
    EXPECT_THROW(PreethamSky(T, sun), std::invalid_argument) << T;
  EXPECT_NO_THROW(PreethamSky(1.7, sun));
  EXPECT_NO_THROW(PreethamSky(10.0, sun));
  EXPECT_THROW(PreethamSky(3.0, Vec3(1.0f, 0.0f, 0.0f)), std::invalid_argument);    // on the horizon
  EXPECT_THROW(PreethamSky(3.0, Vec3(0.0f, 0.5f, -0.1f)), std::invalid_argument);   // below
  EXPECT_THROW(PreethamSky(3.0, Vec3::Zero()), std::invalid_argument);
  EXPECT_THROW(PreethamSky(3.0, Vec3(0.0f, std::nanf(""), 1.0f)), std::invalid_argument);
  try {
    PreethamSky(12.0, sun);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("turbidity 12"), std::string::npos) << e.what();
  }
  // A sun direction that is not unit length is the same sky.
  EXPECT_NEAR(PreethamSky(3.0, 5.0f * sun).zenith_luminance(), PreethamSky(3.0, sun).zenith_luminance(), 1e-6);
}

TEST(SkyModelPreetham, BrightestTowardTheSunAndSymmetricAboutItsMeridian) {
  const PreethamSky sky(3.0, direction(50.0, 90.0));
  EXPECT_GT(sky.luminance(direction(45.0, 90.0)), sky.luminance(direction(45.0, 270.0)));
  for (double z = 5.0; z < 90.0; z += 10.0)
    for (double da = 10.0; da < 180.0; da += 20.0)
      EXPECT_NEAR(sky.luminance(direction(z, 90.0 + da)), sky.luminance(direction(z, 90.0 - da)),
                  1e-4 * sky.luminance(direction(z, 90.0 - da)));
}

// ---- The sun ----

TEST(SkyModelSun, ExtraterrestrialIlluminanceIsTheSolarConstant) {
  const SunDisk sun = extraterrestrial_sun();
  const double half = 0.5 * 0.53 * kDeg;
  EXPECT_NEAR(sun.solid_angle, 2.0 * kPiD * (1.0 - std::cos(half)), 1e-12);
  EXPECT_NEAR(sun.solid_angle, 6.72e-5, 0.01e-5);
  // Solar illuminance constant: 127.5 klx (IES RP-21) to 133.3 klx (Darula, Kittler, Gueymard 2005,
  // "Reference luminous solar constant and solar luminance for illuminance calculations").
  const double E = luminance(sun.normal_illuminance());
  EXPECT_GT(E, 122e3);
  EXPECT_LT(E, 136e3);
  // Mean disk luminance about 1.9e9 cd/m^2, white to the eye (x, y near the equal-energy point).
  EXPECT_NEAR(luminance(sun.radiance), E / sun.solid_angle, 1e-5 * E / sun.solid_angle);
  const Eigen::Vector3d xyz = xyz_from_rgb(sun.radiance);
  EXPECT_NEAR(xyz[0] / xyz.sum(), 0.32, 0.02);
  EXPECT_NEAR(xyz[1] / xyz.sum(), 0.33, 0.02);
  // The same number straight from the spectrum: 683 lm/W x integral of L y-bar, times the disk.
  EXPECT_NEAR(solar_disk_xyz(3.0, 0.0)[1] * sun.solid_angle, E, 1e-5 * E);
}

TEST(SkyModelSun, AirMassAndTransmittance) {
  EXPECT_NEAR(relative_air_mass(0.0), 1.0, 1e-3);
  EXPECT_NEAR(relative_air_mass(60.0 * kDeg), 2.0, 0.01);
  EXPECT_NEAR(relative_air_mass(90.0 * kDeg), 36.5, 0.5);  // Kasten: finite at the horizon
  EXPECT_DOUBLE_EQ(direct_beam_transmittance(550.0, 4.0, 0.0), 1.0);
  // Blue is scattered more than red; more turbidity, more air: less light.
  EXPECT_LT(direct_beam_transmittance(450.0, 3.0, 1.0), direct_beam_transmittance(650.0, 3.0, 1.0));
  EXPECT_LT(direct_beam_transmittance(550.0, 6.0, 1.0), direct_beam_transmittance(550.0, 3.0, 1.0));
  EXPECT_LT(direct_beam_transmittance(550.0, 3.0, 2.0), direct_beam_transmittance(550.0, 3.0, 1.0));
  // The water-vapour band at 720 nm dims the beam below its 700 nm neighbour, against the trend.
  EXPECT_LT(direct_beam_transmittance(720.0, 3.0, 1.0), direct_beam_transmittance(700.0, 3.0, 1.0));
}

TEST(SkyModelSun, DirectNormalIlluminanceAgainstIesClearSky) {
  // Clear sky, T = 2.5: within 20% of the IES clear-sky direct normal illuminance at 30 and 60
  // degrees of altitude. The model gives about 13% and 8% less than IES (its atmosphere carries
  // more aerosol than IES' c = 0.21); a unit or air-mass mistake lands far outside.
  for (double altitude : {30.0, 60.0}) {
    const double E = luminance(preetham_sun(2.5, (90.0 - altitude) * kDeg).normal_illuminance());
    const double ies = ies_clear_direct_normal_lux(altitude);
    EXPECT_NEAR(E, ies, 0.2 * ies) << "altitude " << altitude;
  }
  // More turbidity, lower sun: less direct light, and a redder sun low in the sky.
  EXPECT_LT(luminance(preetham_sun(5.0, 30.0 * kDeg).normal_illuminance()),
            luminance(preetham_sun(2.5, 30.0 * kDeg).normal_illuminance()));
  double previous = std::numeric_limits<double>::infinity();
  for (double zenith = 0.0; zenith < 90.0; zenith += 5.0) {
    const SunDisk sun = preetham_sun(3.0, zenith * kDeg);
    const double E = luminance(sun.normal_illuminance());
    EXPECT_LT(E, previous) << zenith;
    EXPECT_TRUE(sun.radiance.isFinite().all() && (sun.radiance >= 0.0f).all()) << zenith;
    previous = E;
  }
  const Rgb high = preetham_sun(3.0, 30.0 * kDeg).radiance, low = preetham_sun(3.0, 80.0 * kDeg).radiance;
  EXPECT_GT(low[0] / low[2], high[0] / high[2]);
}

TEST(SkyModelSun, HorizonAndInvalidInput) {
  for (double T : {1.7, 10.0}) {
    const SunDisk grazing = preetham_sun(T, 89.99 * kDeg);
    EXPECT_TRUE(grazing.radiance.isFinite().all() && (grazing.radiance >= 0.0f).all());
  }
  const SunDisk set = preetham_sun(3.0, 90.0 * kDeg);
  EXPECT_EQ(luminance(set.radiance), 0.0f);
  EXPECT_GT(set.solid_angle, 0.0);
  EXPECT_EQ(luminance(preetham_sun(3.0, 120.0 * kDeg).normal_illuminance()), 0.0f);
  EXPECT_THROW(preetham_sun(1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(preetham_sun(11.0, 0.5), std::invalid_argument);
  EXPECT_THROW(preetham_sun(3.0, -0.1), std::invalid_argument);
  EXPECT_THROW(preetham_sun(3.0, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

// ---- Sky and sun together ----

TEST(SkyModelDaylight, HorizontalIlluminanceAgainstIesClearSky) {
  // Global horizontal (sky + sun) illuminance of a T = 2.5 Preetham day lies within 20% of the IES
  // clear-sky value (the model gives +10% at 30 degrees, +5% at 60 degrees). Its split leans to the
  // sky: Preetham's sky is known to be brighter than measured clear skies (Zotti, Wilkie,
  // Purgathofer 2007, "A critical review of the Preetham skylight model"), here 1.8x to 1.9x the
  // IES sky illuminance, so the sky alone is held to [1, 2.5] x IES, and its share of the global
  // illuminance to 15-45%.
  for (double altitude : {30.0, 60.0}) {
    const double zenith = 90.0 - altitude;
    const PreethamSky sky(2.5, direction(zenith, 180.0));
    const double E_sky = horizontal_illuminance([&](const Vec3& d) { return sky.luminance(d); });
    const double E_sun =
        luminance(preetham_sun(2.5, zenith * kDeg).normal_illuminance()) * std::cos(zenith * kDeg);
    const double ies_sky = ies_clear_sky_horizontal_lux(altitude);
    const double ies_global = ies_sky + ies_clear_direct_normal_lux(altitude) * std::sin(altitude * kDeg);
    SCOPED_TRACE(testing::Message() << "altitude " << altitude << ": sky " << E_sky << " lx, sun " << E_sun << " lx");
    EXPECT_NEAR(E_sky + E_sun, ies_global, 0.2 * ies_global);
    EXPECT_GT(E_sky, 1.0 * ies_sky);
    EXPECT_LT(E_sky, 2.5 * ies_sky);
    EXPECT_GT(E_sky / (E_sky + E_sun), 0.15);
    EXPECT_LT(E_sky / (E_sky + E_sun), 0.45);
  }
  // A hazier sky is brighter, its sun dimmer.
  const Vec3 sun = direction(30.0, 180.0);
  const PreethamSky clear(2.5, sun), hazy(5.0, sun);
  EXPECT_GT(horizontal_illuminance([&](const Vec3& d) { return hazy.luminance(d); }, 90),
            horizontal_illuminance([&](const Vec3& d) { return clear.luminance(d); }, 90));
}

TEST(SkyModelDaylight, SkyIlluminanceFromRgbMatchesLuminance) {
  const PreethamSky sky(3.0, direction(40.0, 30.0));
  const double from_Y = horizontal_illuminance([&](const Vec3& d) { return sky.luminance(d); }, 90);
  const double from_rgb =
      horizontal_illuminance([&](const Vec3& d) { return static_cast<double>(luminance(sky.radiance(d))); }, 90);
  EXPECT_NEAR(from_rgb, from_Y, 1e-5 * from_Y);
}

// ---- CIE standard skies ----

TEST(SkyModelCie, OvercastHorizontalIlluminanceIsSevenPiOverNine) {
  const double E = horizontal_illuminance([](const Vec3& d) { return cie_overcast_relative(d.z()); }, 200);
  EXPECT_NEAR(E, 7.0 * kPiD / 9.0, 1e-4);
  EXPECT_DOUBLE_EQ(cie_overcast_relative(1.0), 1.0);
  EXPECT_NEAR(cie_overcast_relative(0.0), 1.0 / 3.0, 1e-15);
  EXPECT_EQ(cie_overcast_relative(-0.2), 0.0);
}

TEST(SkyModelCie, ClearSkyShape) {
  for (double sun_zenith : {10.0, 30.0, 50.0, 70.0, 85.0}) {
    const Vec3 sun = direction(sun_zenith, 120.0);
    SCOPED_TRACE(testing::Message() << "sun zenith " << sun_zenith);
    EXPECT_NEAR(cie_clear_relative(Vec3(0.0f, 0.0f, 1.0f), sun), 1.0, 1e-6);
    // Symmetric about the solar meridian.
    for (double z = 0.0; z <= 90.0; z += 7.5)
      for (double da = 5.0; da < 180.0; da += 25.0) {
        const double left = cie_clear_relative(direction(z, 120.0 - da), sun);
        const double right = cie_clear_relative(direction(z, 120.0 + da), sun);
        EXPECT_NEAR(left, right, 1e-5 * left);
        EXPECT_TRUE(std::isfinite(left) && left > 0.0);
      }
    // Brightest around the sun: the maximum of a 1-degree grid lies within 5 degrees of it, and
    // the sky toward the sun outshines the sky away from it.
    double best = -1.0;
    Vec3 best_dir;
    for (double z = 0.5; z < 90.0; z += 1.0)
      for (double a = 0.5; a < 360.0; a += 1.0) {
        const Vec3 d = direction(z, a);
        const double v = cie_clear_relative(d, sun);
        if (v > best) best = v, best_dir = d;
      }
    EXPECT_LT(std::acos(std::min(1.0f, best_dir.dot(sun))) / kDeg, 5.0);
    EXPECT_GT(cie_clear_relative(direction(60.0, 120.0), sun), cie_clear_relative(direction(60.0, 300.0), sun));
  }
  // Reference value: CIE S 011 type 12 at the horizon opposite a sun at 45 degrees, written out.
  const auto f = [](double chi) {
    return 1.0 + 10.0 * (std::exp(-3.0 * chi) - std::exp(-1.5 * kPiD)) + 0.45 * std::cos(chi) * std::cos(chi);
  };
  const double phi0 = 1.0 - std::exp(-0.32);
  const double expected = f(135.0 * kDeg) * 1.0 / (f(45.0 * kDeg) * phi0);
  EXPECT_NEAR(cie_clear_relative(direction(90.0, 300.0), direction(45.0, 120.0)), expected, 1e-5 * expected);
  EXPECT_EQ(cie_clear_relative(Vec3(0.0f, 0.6f, -0.8f), direction(45.0, 0.0)), 0.0);
}
