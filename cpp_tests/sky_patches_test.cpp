#include "daylight/sky_patches.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "chi2.h"
#include "daylight/sky_models.h"
#include "util/rng.h"

using namespace fenestra;

namespace {

constexpr double kDeg = kPiD / 180.0;
const int kTregenza[7] = {30, 30, 24, 24, 18, 12, 6};  // Tregenza's ring sizes, horizon up

// Uniform double in [0, 1) with 53 random bits.
double uniform53(Rng& rng) {
  const uint64_t a = rng.next_u32() >> 5, b = rng.next_u32() >> 6;
  return (a * 67108864.0 + b) * 0x1p-53;
}

// Uniform direction over the sphere (hemisphere when z_min = 0), z drawn first.
Vec3d uniform_direction(Rng& rng, double z_min = -1.0) {
  const double z = z_min + (1.0 - z_min) * uniform53(rng);
  const double phi = 2.0 * kPiD * uniform53(rng);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vec3d(r * std::cos(phi), r * std::sin(phi), z);
}

// World direction at an altitude and an azimuth clockwise from +Y seen from above (degrees).
Vec3d world_direction(double alt_deg, double world_az_deg) {
  const double a = alt_deg * kDeg, w = world_az_deg * kDeg;
  return Vec3d(std::cos(a) * std::sin(w), std::cos(a) * std::cos(w), std::sin(a));
}

double wrap(double a) {
  a = std::fmod(a, 2.0 * kPiD);
  return a < 0.0 ? a + 2.0 * kPiD : a;
}

// The bin reinhart.cal assigns to a unit direction (Dx, Dy, Dz), its expressions evaluated as the
// calcomp file states them: alt and azi in degrees (azi = atan2(Dx, Dy), east of north), rows of
// alpha = 90 / (7 MF + 0.5) degrees, rnaz(r) patches in row r, raccum(r) patches below row r.
// *fuzzy is set where the file's 359.9999 guard sends a direction to azimuth bin 0 that the exact
// rule puts in the last bin of its row.
int reinhart_cal_bin(const Vec3d& d, int mf, bool* fuzzy) {
  const double alt = std::asin(std::clamp(d.z(), -1.0, 1.0)) / kDeg;
  double azi = std::atan2(d.x(), d.y());
  if (azi < 0.0) azi += 2.0 * kPiD;
  azi /= kDeg;
  *fuzzy = false;
  if (alt < 0.0) return 0;
  const double alpha = 90.0 / (mf * 7 + 0.5);
  auto rnaz = [&](int r) { return r > 7 * mf - 0.5 ? 1 : mf * kTregenza[static_cast<int>(std::floor((r + 0.5) / mf))]; };
  auto raccum = [&](int r) {
    int sum = 0;
    for (int i = 0; i < r; ++i) sum += rnaz(i);
    return sum;
  };
  const int r_row = static_cast<int>(std::floor(alt / alpha));
  const double r_inc = 360.0 / rnaz(r_row);
  int r_azn = 0;
  if (359.9999 - 0.5 * r_inc - azi > 0.0)
    r_azn = static_cast<int>(std::floor((azi + 0.5 * r_inc) / r_inc));
  else
    *fuzzy = azi < 360.0 - 0.5 * r_inc;
  return raccum(r_row) + r_azn + 1;
}

// gendaymtx's rh_init, restated: patch altitude and azimuth (radians) and solid angle (sr), the
// ground first and the zenith last.
struct GendaymtxPatch {
  double alt, azi, dom;
};
std::vector<GendaymtxPatch> gendaymtx_patches(int mf) {
  const double alpha = 0.5 * kPiD / (7 * mf + 0.5);
  std::vector<GendaymtxPatch> out{{-0.5 * kPiD, 0.0, 2.0 * kPiD}};
  for (int i = 0; i < 7 * mf; ++i) {
    const int ninrow = kTregenza[i / mf] * mf;
    const double dom = 2.0 * kPiD * (std::sin(alpha * (i + 1)) - std::sin(alpha * i)) / ninrow;
    for (int j = 0; j < ninrow; ++j) out.push_back({alpha * (i + 0.5), 2.0 * kPiD * j / ninrow, dom});
  }
  out.push_back({0.5 * kPiD, 0.0, 2.0 * kPiD * (1.0 - std::cos(0.5 * alpha))});
  return out;
}

}  // namespace

TEST(SkyPatches, CountsAndRingSizesAreRadiances) {
  const int expected_sky[5] = {0, 145, 577, 1297, 2305};
  for (int mf : {1, 2, 3, 4}) {
    const SkyPatches p(mf);
    EXPECT_EQ(p.sky_count(), expected_sky[mf]) << "MF " << mf;
    EXPECT_EQ(p.count(), expected_sky[mf] + 1) << "MF " << mf;
    EXPECT_EQ(p.ring_count(), 7 * mf + 1);
    EXPECT_NEAR(p.ring_height(), 90.0 / (7 * mf + 0.5) * kDeg, 1e-15);
    int total = 0;
    for (int r = 0; r < p.ring_count(); ++r) {
      EXPECT_EQ(p.first_patch(r), 1 + total) << "MF " << mf << " ring " << r;
      total += p.ring_size(r);
    }
    EXPECT_EQ(total, p.sky_count());
  }
  const std::vector<int> mf1 = {30, 30, 24, 24, 18, 12, 6, 1};
  const std::vector<int> mf2 = {60, 60, 60, 60, 48, 48, 48, 48, 36, 36, 24, 24, 12, 12, 1};
  const SkyPatches t(1), r2(2);
  for (int r = 0; r < t.ring_count(); ++r) EXPECT_EQ(t.ring_size(r), mf1[r]);
  for (int r = 0; r < r2.ring_count(); ++r) EXPECT_EQ(r2.ring_size(r), mf2[r]);
  EXPECT_EQ(t.ring_of(0), -1);
  EXPECT_EQ(t.ring_of(145), 7);
  EXPECT_EQ(t.ring_of(30), 0);
  EXPECT_EQ(t.ring_of(31), 1);
}

TEST(SkyPatches, RefusesBadInput) {
  EXPECT_THROW(SkyPatches(0), std::invalid_argument);
  EXPECT_THROW(SkyPatches(-2), std::invalid_argument);
  EXPECT_THROW(SkyPatches(SkyPatches::kMaxSubdivision + 1), std::invalid_argument);
  EXPECT_THROW(SkyPatches(1, std::nan("")), std::invalid_argument);
  EXPECT_THROW(SkyPatches(1, INFINITY), std::invalid_argument);
  try {
    SkyPatches(3000);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("subdivision 3000"), std::string::npos) << e.what();
  }
  const SkyPatches p(1);
  EXPECT_THROW(p.patch_of(Vec3d(0, 0, 0)), std::invalid_argument);
  EXPECT_THROW(p.patch_of(Vec3d(std::nan(""), 0, 1)), std::invalid_argument);
  EXPECT_THROW(p.bounds(146), std::invalid_argument);
  EXPECT_THROW(p.solid_angle(-1), std::invalid_argument);
  EXPECT_THROW(p.centre(146), std::invalid_argument);
  EXPECT_THROW(p.ring_size(8), std::invalid_argument);
  EXPECT_THROW(p.square_to_patch(3, 1.5, 0.5), std::invalid_argument);
  EXPECT_THROW(p.square_to_patch(3, 0.5, std::nan("")), std::invalid_argument);
  EXPECT_THROW(p.patch_means([](const Vec3d&) { return 1.0; }, 0), std::invalid_argument);
  try {
    p.bounds(146);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("patch 146"), std::string::npos) << e.what();
  }
}

// tregenza.cal's table: rows of 12 degrees starting at bins 1, 31, 61, 85, 109, 127, 139 with
// azimuth steps of 12, 12, 15, 15, 20, 30, 60 degrees, bin 145 above 84 degrees; bin 1 due north
// at the horizon, continuing to the east.
TEST(SkyPatches, TregenzaOrderIsTregenzaCal) {
  const SkyPatches p(1);
  EXPECT_NEAR(p.ring_height(), 12.0 * kDeg, 1e-15);
  const int first[8] = {1, 31, 61, 85, 109, 127, 139, 145};
  const double step[7] = {12, 12, 15, 15, 20, 30, 60};
  for (int r = 0; r < 7; ++r) {
    EXPECT_EQ(p.first_patch(r), first[r]);
    for (int k = 0; k * step[r] < 360.0; ++k) {
      // Inside the bin, a quarter step clockwise (east) of its centre, and a quarter step back.
      EXPECT_EQ(p.patch_of(world_direction(12.0 * r + 3.0, k * step[r] + 0.25 * step[r])), first[r] + k);
      EXPECT_EQ(p.patch_of(world_direction(12.0 * r + 9.0, k * step[r] - 0.25 * step[r])), first[r] + k);
    }
  }
  EXPECT_EQ(p.patch_of(world_direction(84.5, 200.0)), 145);
  EXPECT_EQ(p.patch_of(Vec3d(0, 0, 1)), 145);
  EXPECT_EQ(p.patch_of(world_direction(-0.01, 0.0)), 0);
}

TEST(SkyPatches, BinningIsReinhartCals) {
  Rng rng(11, 3);
  for (int mf : {1, 2, 3, 4}) {
    const SkyPatches p(mf);
    int compared = 0, mismatches = 0;
    for (int i = 0; i < 200000; ++i) {
      const Vec3d d = uniform_direction(rng);
      bool fuzzy = false;
      const int expected = reinhart_cal_bin(d, mf, &fuzzy);
      if (fuzzy) continue;
      ++compared;
      if (p.patch_of(d) != expected && ++mismatches <= 5)
        ADD_FAILURE() << "MF " << mf << " direction (" << d.transpose() << "): " << p.patch_of(d) << " vs reinhart.cal "
                      << expected;
    }
    EXPECT_EQ(mismatches, 0) << "MF " << mf;
    EXPECT_GT(compared, 199000);
  }
}

TEST(SkyPatches, CentresAndSolidAnglesAreGendaymtxs) {
  for (int mf : {1, 2, 4}) {
    const SkyPatches p(mf);
    const std::vector<GendaymtxPatch> g = gendaymtx_patches(mf);
    ASSERT_EQ(static_cast<int>(g.size()), p.count());
    for (int k = 0; k < p.count(); ++k) {
      const Vec3d expected(std::cos(g[k].alt) * std::sin(g[k].azi), std::cos(g[k].alt) * std::cos(g[k].azi),
                           std::sin(g[k].alt));
      EXPECT_LT((p.centre(k) - expected).norm(), 1e-14) << "MF " << mf << " patch " << k;
      EXPECT_NEAR(p.solid_angle(k), g[k].dom, 1e-15) << "MF " << mf << " patch " << k;
    }
  }
}

TEST(SkyPatches, SolidAnglesAreTheirClosedFormsAndFillTheHemisphere) {
  for (int mf : {1, 2, 3, 4, 8}) {
    const SkyPatches p(mf);
    const double alpha = 0.5 * kPiD / (7 * mf + 0.5);
    EXPECT_DOUBLE_EQ(p.solid_angle(0), 2.0 * kPiD);
    double sum = 0.0;
    for (int k = 1; k < p.count(); ++k) {
      const int r = p.ring_of(k);
      const double top = r == 7 * mf ? 0.5 * kPiD : (r + 1) * alpha;
      const double closed = 2.0 * (std::sin(top) - std::sin(r * alpha)) * kPiD / p.ring_size(r);
      EXPECT_NEAR(p.solid_angle(k), closed, 1e-15) << "MF " << mf << " patch " << k;
      sum += p.solid_angle(k);
    }
    EXPECT_NEAR(sum, 2.0 * kPiD, 1e-12) << "MF " << mf;
  }
}

TEST(SkyPatches, EveryCentreLandsInItsPatch) {
  for (int mf : {1, 2, 3, 4, 8})
    for (double offset : {0.0, 20.0, -137.5, 400.0}) {
      const SkyPatches p(mf, offset);
      for (int k = 0; k < p.count(); ++k) {
        ASSERT_EQ(p.patch_of(p.centre(k)), k) << "MF " << mf << " offset " << offset;
        ASSERT_EQ(p.patch_of(Vec3(p.centre(k).cast<float>())), k) << "float, MF " << mf << " offset " << offset;
        ASSERT_NEAR(p.centre(k).norm(), 1.0, 1e-15);
      }
    }
}

TEST(SkyPatches, PatchOfAgreesWithBounds) {
  Rng rng(5, 1);
  for (int mf : {1, 2, 4})
    for (double offset : {0.0, 33.3}) {
      const SkyPatches p(mf, offset);
      for (int i = 0; i < 100000; ++i) {
        const Vec3d d = uniform_direction(rng) * (0.1 + 10.0 * uniform53(rng));  // any length
        const int k = p.patch_of(d);
        const SkyPatches::Bounds b = p.bounds(k);
        const double alt = std::asin(d.z() / d.norm());
        const double az = std::atan2(d.x(), d.y()) - offset * kDeg;  // clockwise from true north
        ASSERT_GE(alt, b.alt0) << "patch " << k;
        ASSERT_LT(alt, b.alt1) << "patch " << k;
        ASSERT_LT(wrap(az - b.az0), b.az1 - b.az0) << "patch " << k;
      }
    }
  // The horizon belongs to the first ring (reinhart.cal: ground only for alt < 0).
  const SkyPatches p(1);
  EXPECT_EQ(p.patch_of(Vec3d(0, 1, 0)), 1);
  EXPECT_EQ(p.patch_of(Vec3d(0, 1, -1e-300)), 0);
  EXPECT_EQ(p.patch_of(Vec3d(0, 0, -1)), 0);
}

// Uniform directions over the upper hemisphere binned by patch_of: counts proportional to the
// solid angles (Pearson's test, cells below 5 expected pooled; none here).
TEST(SkyPatches, UniformDirectionsFillPatchesInProportionToSolidAngle) {
  const std::vector<int> mfs = {1, 2, 4};
  const double significance = fenestra_test::sidak_correction(fenestra_test::kSignificance, 2 * mfs.size());
  for (int mf : mfs)
    for (double offset : {0.0, 71.0}) {
      const SkyPatches p(mf, offset);
      const int n = 1000000;
      Rng rng(2024 + mf, 9);
      std::vector<double> observed(p.count(), 0.0), expected(p.count(), 0.0);
      for (int i = 0; i < n; ++i) observed[p.patch_of(uniform_direction(rng, 0.0))] += 1.0;
      for (int k = 1; k < p.count(); ++k) expected[k] = n * p.solid_angle(k) / (2.0 * kPiD);
      const fenestra_test::Chi2Result r = fenestra_test::pearson_chi2(observed, expected, significance);
      EXPECT_TRUE(r.passed) << "MF " << mf << " offset " << offset << ": " << r.message;
      EXPECT_EQ(r.pooled_cells, 0) << "every sky patch expects 380 or more";
    }
}

TEST(SkyPatches, SquareToPatchRoundTripsAndStaysInThePatch) {
  Rng rng(77, 2);
  for (int mf : {1, 2, 4})
    for (double offset : {0.0, -20.0}) {
      const SkyPatches p(mf, offset);
      for (int k = 0; k < p.count(); ++k) {
        EXPECT_NEAR(p.square_to_patch_pdf(k) * p.solid_angle(k), 1.0, 1e-15);
        for (int i = 0; i < 20; ++i) {
          const double u = uniform53(rng), v = uniform53(rng);
          const Vec3d d = p.square_to_patch(k, u, v);
          ASSERT_NEAR(d.norm(), 1.0, 1e-15);
          ASSERT_EQ(p.patch_of(d), k) << "MF " << mf << " patch " << k << " (u, v) = (" << u << ", " << v << ")";
          const Eigen::Vector2d back = p.patch_to_square(k, d);
          ASSERT_NEAR(back.x(), u, 1e-9) << "patch " << k;
          ASSERT_NEAR(back.y(), v, 1e-12) << "patch " << k;
        }
      }
    }
}

// Directions from square_to_patch binned on an altitude x azimuth grid over the patch: the
// expected counts use each cell's exact solid angle (sin alt difference x azimuth width), so a
// sampler uniform in altitude rather than in solid angle fails.
TEST(SkyPatches, SquareToPatchIsUniformInSolidAngle) {
  struct Case {
    int mf, patch;
    double offset;
  };
  const std::vector<Case> cases = {{1, 1, 0.0}, {1, 145, 0.0}, {1, 0, 0.0}, {2, 300, 20.0}, {4, 2305, 20.0}};
  const double significance = fenestra_test::sidak_correction(fenestra_test::kSignificance, cases.size());
  const int grid = 9, n = 200000;
  for (const Case& c : cases) {
    const SkyPatches p(c.mf, c.offset);
    const SkyPatches::Bounds b = p.bounds(c.patch);
    Rng rng(31 + c.patch, 4);
    std::vector<double> observed(grid * grid, 0.0), expected(grid * grid, 0.0);
    const double dalt = (b.alt1 - b.alt0) / grid, daz = (b.az1 - b.az0) / grid;
    for (int i = 0; i < n; ++i) {
      const Vec3d d = p.square_to_patch(c.patch, uniform53(rng), uniform53(rng));
      const double alt = std::asin(std::clamp(d.z(), -1.0, 1.0));
      const double az = wrap(std::atan2(d.x(), d.y()) - c.offset * kDeg - b.az0);
      const int ia = std::min(grid - 1, static_cast<int>((alt - b.alt0) / dalt));
      const int iz = std::min(grid - 1, static_cast<int>(az / daz));
      observed[ia * grid + iz] += 1.0;
    }
    for (int ia = 0; ia < grid; ++ia)
      for (int iz = 0; iz < grid; ++iz)
        expected[ia * grid + iz] =
            n * (std::sin(b.alt0 + (ia + 1) * dalt) - std::sin(b.alt0 + ia * dalt)) * daz / p.solid_angle(c.patch);
    const fenestra_test::Chi2Result r = fenestra_test::pearson_chi2(observed, expected, significance);
    EXPECT_TRUE(r.passed) << "MF " << c.mf << " patch " << c.patch << ": " << r.message;
  }
}

TEST(SkyPatches, NorthOffsetTurnsThePatchesWithTrueNorth) {
  // Due true north, low: the first patch of the first ring, whatever the offset.
  for (double offset : {0.0, 20.0, 90.0, -45.0, 217.0, 359.0})
    for (int mf : {1, 2, 4}) {
      const SkyPatches p(mf, offset);
      EXPECT_EQ(p.patch_of(world_direction(1.0, offset)), 1) << "offset " << offset;
      // Due true east, in the first ring of Tregenza's third (24 MF patches, centres every
      // 15 / MF degrees): a quarter of the way round, the centre of patch 6 MF of the ring.
      const int ring = 2 * mf;
      const double alt = (ring + 0.5) * p.ring_height() / kDeg;
      EXPECT_EQ(p.patch_of(world_direction(alt, offset + 90.0)), p.first_patch(ring) + 6 * mf)
          << "true east, offset " << offset << ", MF " << mf;
    }
  // Offset 0: +Y is north; the order goes clockwise seen from above, towards +X (east).
  const SkyPatches p0(1);
  EXPECT_EQ(p0.patch_of(world_direction(5.0, 84.0)), 8);    // 7 steps of 12 degrees east of north
  EXPECT_EQ(p0.patch_of(world_direction(5.0, 276.0)), 24);  // 23 steps: west
  EXPECT_NEAR(p0.azimuth(Vec3d(1.0, 0.0, 0.3)), 0.5 * kPiD, 1e-15);  // +X is east
  EXPECT_NEAR(p0.azimuth(Vec3d(0.0, -1.0, 0.3)), kPiD, 1e-15);      // -Y is south
  // Offset 20: true north is 20 degrees clockwise of +Y, so +Y is 340 degrees east of true north.
  const SkyPatches p20(1, 20.0);
  EXPECT_EQ(p20.patch_of(Vec3d(0.0, 1.0, 0.05)), 29);
  EXPECT_NEAR(p20.azimuth(Vec3d(0.0, 1.0, 0.05)), 340.0 * kDeg, 1e-14);
  // Turning a direction clockwise by the offset gives the patch it had with no offset.
  Rng rng(8, 8);
  for (double offset : {13.0, -100.0, 250.0}) {
    const SkyPatches turned(2, offset), plain(2, 0.0);
    const double o = offset * kDeg;
    for (int i = 0; i < 20000; ++i) {
      const Vec3d d = uniform_direction(rng);
      // Clockwise seen from above by o: (x, y) -> (x cos o + y sin o, -x sin o + y cos o).
      const Vec3d t(d.x() * std::cos(o) + d.y() * std::sin(o), -d.x() * std::sin(o) + d.y() * std::cos(o), d.z());
      ASSERT_EQ(turned.patch_of(t), plain.patch_of(d)) << "offset " << offset;
    }
  }
}

TEST(SkyPatches, PatchMeansOfConstantsAndOfLinearTermsAreExact) {
  for (int mf : {1, 2, 4})
    for (int n : {1, 2, 4}) {
      const SkyPatches p(mf, 15.0);
      const std::vector<double> ones = p.patch_means([](const Vec3d&) { return 2.5; }, n);
      ASSERT_EQ(static_cast<int>(ones.size()), p.count());
      EXPECT_EQ(ones[0], 0.0);
      for (int k = 1; k < p.count(); ++k) ASSERT_NEAR(ones[k], 2.5, 1e-14);
      // Horizontal illuminance of a unit-radiance sky, sum of mean(cos theta) x solid angle: pi.
      // The rule is the midpoint rule in sin altitude = cos theta, exact for a linear integrand.
      const std::vector<double> cosines = p.patch_means([](const Vec3d& d) { return d.z(); }, n);
      double e = 0.0;
      for (int k = 1; k < p.count(); ++k) e += cosines[k] * p.solid_angle(k);
      EXPECT_NEAR(e, kPiD, 1e-12) << "MF " << mf << " n " << n;
    }
}

// For smooth integrands the midpoint rule errs by a known amount: over [s0, s1] in n steps of h,
// the mean of s^2 comes out h^2 / 12 low; the n-point mean of cos(2 w) over an azimuth span D
// centred on c is cos(2c) sin(D) / (n sin(D / n)) rather than cos(2c) sin(D) / D. Each patch's
// mean must match these predictions to round-off.
TEST(SkyPatches, PatchMeansErrIsTheMidpointRulesPredictedError) {
  for (int mf : {1, 2, 4})
    for (int n : {3, 4, 8}) {
      const double offset = 25.0;
      const SkyPatches p(mf, offset);
      const std::vector<double> z2 = p.patch_means([](const Vec3d& d) { return d.z() * d.z(); }, n);
      const std::vector<double> x2 = p.patch_means([](const Vec3d& d) { return d.x() * d.x(); }, n);
      const std::vector<double> overcast =
          p.patch_means([](const Vec3d& d) { return cie_overcast_relative(d.z()) * d.z(); }, n);
      double sum_z2 = 0.0, sum_x2 = 0.0, sum_overcast = 0.0, predicted_error = 0.0;
      for (int k = 1; k < p.count(); ++k) {
        const SkyPatches::Bounds b = p.bounds(k);
        const double s0 = std::sin(b.alt0), s1 = std::sin(b.alt1), h = (s1 - s0) / n;
        const double exact_s2 = (s0 * s0 + s0 * s1 + s1 * s1) / 3.0;
        const double mid_s2 = exact_s2 - h * h / 12.0;
        ASSERT_NEAR(z2[k], mid_s2, 1e-14) << "MF " << mf << " n " << n << " patch " << k;
        // x = cos(alt) sin(w), w the azimuth clockwise from +Y: x^2 = (1 - s^2)(1 - cos 2w) / 2.
        const double span = b.az1 - b.az0, c = 0.5 * (b.az0 + b.az1) + offset * kDeg;
        const double mid_cos2w = std::cos(2.0 * c) * std::sin(span) / (n * std::sin(span / n));
        ASSERT_NEAR(x2[k], (1.0 - mid_s2) * 0.5 * (1.0 - mid_cos2w), 1e-14) << "patch " << k;
        // CIE overcast (1 + 2 s) / 3 times s: 1/3 of s plus 2/3 of s^2.
        ASSERT_NEAR(overcast[k], (0.5 * (s0 + s1) + 2.0 * mid_s2) / 3.0, 1e-14) << "patch " << k;
        predicted_error += p.solid_angle(k) * 2.0 / 3.0 * h * h / 12.0;
        sum_z2 += z2[k] * p.solid_angle(k);
        sum_x2 += x2[k] * p.solid_angle(k);
        sum_overcast += overcast[k] * p.solid_angle(k);
      }
      // Over the hemisphere: integral of z^2 and of x^2 is 2 pi / 3; horizontal illuminance of the
      // CIE overcast sky 7 pi / 9 L_z. The quadrature errs low by the predicted amount only.
      EXPECT_NEAR(7.0 * kPiD / 9.0 - sum_overcast, predicted_error, 1e-12) << "MF " << mf << " n " << n;
      EXPECT_NEAR(2.0 * kPiD / 3.0 - sum_z2, 1.5 * predicted_error, 1e-12);
      EXPECT_GT(predicted_error, 0.0);
      // x^2: the azimuth part sums to its exact value over each full ring (the cos 2w terms cancel
      // when a ring holds more than two patches), leaving the altitude error.
      EXPECT_NEAR(sum_x2 - 2.0 * kPiD / 3.0, 0.5 * 1.5 * predicted_error, 1e-12);
      // docs/sky.md quotes 2.6e-4 for Tregenza's sky with the default 4 x 4 points.
      if (mf == 1 && n == 4) EXPECT_NEAR(predicted_error / (7.0 * kPiD / 9.0), 2.6e-4, 0.05e-4);
    }
}

TEST(SkyPatches, ToStringNamesTheDiscretisation) {
  EXPECT_EQ(SkyPatches(1).to_string(), "SkyPatches(Tregenza: 145 sky patches + ground, 8 rings of 12 deg, north offset 0 deg)");
  EXPECT_NE(SkyPatches(4, 12.5).to_string().find("Reinhart MF 4: 2305 sky patches"), std::string::npos);
}
