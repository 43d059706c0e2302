// Tests of the sampling routines: square-to-direction warps, piecewise-constant distributions,
// GGX visible-normal sampling and the sky models. Densities are checked three ways: the pdf
// integrates to its expected mass, the inverse warp undoes the warp, and samples follow the pdf
// (chi-square goodness of fit, see chi2.h). All random numbers come from fixed seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "chi2.h"
#include "sampling/distribution.h"
#include "sampling/ggx.h"
#include "sampling/warp.h"
#include "scene/environment_map.h"
#include "util/rng.h"

namespace fenestra {
namespace {

using fenestra_test::Chi2Result;
using fenestra_test::kPiD;
using fenestra_test::SphereGrid;

using fenestra_test::kSignificance;
using fenestra_test::next2;
constexpr int kChi2Samples = 1000000;


SphereGrid hemisphere_grid() {
  SphereGrid g;
  g.theta_res = 15;
  g.phi_res = 41;
  g.theta_max = kPiD / 2;
  return g;
}

SphereGrid sphere_grid() {
  SphereGrid g;
  g.theta_res = 21;
  g.phi_res = 41;
  g.theta_max = kPiD;
  g.theta_breaks = {kPiD / 2};  // the odd grid puts the horizon inside a cell
  return g;
}

Vec3 spherical(double theta_deg, double phi_rad) {
  return SphereGrid::direction(theta_deg * kPiD / 180.0, phi_rad);
}

// Difference of two coordinates on the unit circle [0, 1).
double periodic_difference(double a, double b) {
  double d = a - b;
  return d - std::round(d);
}

// ============================================================================================
// The chi-square machinery itself.

TEST(ChiSquare, IncompleteGammaMatchesClosedForms) {
  // Integer a: Q(n, x) = exp(-x) sum_{k<n} x^k / k!  (covers both the series and the continued fraction).
  for (int n : {1, 2, 5, 20, 50, 200}) {
    for (double x : {0.01, 0.5, 1.0, 3.0, 10.0, 30.0, 60.0, 150.0, 250.0}) {
      double q = 0.0;
      for (int k = 0; k < n; ++k) q += std::exp(k * std::log(x) - std::lgamma(k + 1.0) - x);
      EXPECT_NEAR(fenestra_test::regularized_gamma_q(n, x), q, 1e-10 * q + 1e-300) << "a=" << n << " x=" << x;
    }
  }
  // Half-integer a: Q(1/2, x) = erfc(sqrt(x)), Q(a + 1, x) = Q(a, x) + x^a exp(-x) / Gamma(a + 1).
  for (double x : {0.01, 0.4, 1.0, 2.5, 7.0, 20.0, 45.0}) {
    double q = std::erfc(std::sqrt(x));
    for (double a = 0.5; a < 40.0; a += 1.0) {
      EXPECT_NEAR(fenestra_test::regularized_gamma_q(a, x), q, 1e-10 * q + 1e-300) << "a=" << a << " x=" << x;
      q += std::exp(a * std::log(x) - x - std::lgamma(a + 1.0));
    }
  }
  // Tabulated 1% critical values of the chi-square distribution.
  EXPECT_NEAR(fenestra_test::chi2_p_value(6.634897, 1), 0.01, 1e-6);
  EXPECT_NEAR(fenestra_test::chi2_p_value(23.209251, 10), 0.01, 1e-6);
  EXPECT_NEAR(fenestra_test::chi2_p_value(135.806723, 100), 0.01, 1e-6);
}

TEST(ChiSquare, PValueAgreesWithWilsonHilfertyForManyDegreesOfFreedom) {
  // The Wilson-Hilferty cube-root normal approximation is accurate to well under 1e-3 for
  // hundreds of degrees of freedom, the regime of the grid tests.
  for (int dof : {300, 600, 1000, 3000}) {
    for (double z : {-2.0, -1.0, 0.0, 1.0, 2.0, 2.5, 3.0}) {
      const double stat = dof + z * std::sqrt(2.0 * dof);
      EXPECT_NEAR(fenestra_test::chi2_p_value(stat, dof), fenestra_test::chi2_p_value_wilson_hilferty(stat, dof),
                  1e-3)
          << "dof=" << dof << " stat=" << stat;
    }
  }
}

TEST(ChiSquare, PearsonStatisticAndPooling) {
  // Three cells: chi2 = (100 + 0 + 100) / 20 = 10 with 2 dof, p = exp(-5).
  Chi2Result r = fenestra_test::pearson_chi2({10, 20, 30}, {20, 20, 20}, 0.01);
  EXPECT_DOUBLE_EQ(r.statistic, 10.0);
  EXPECT_EQ(r.dof, 2);
  EXPECT_NEAR(r.p_value, std::exp(-5.0), 1e-12);
  EXPECT_FALSE(r.passed);
  // Cells expecting 1, 2 and 3 are pooled into one expecting 6 (observed 7): two cells, 1 dof.
  r = fenestra_test::pearson_chi2({2, 1, 4, 53}, {1, 2, 3, 54}, 0.01);
  EXPECT_EQ(r.pooled_cells, 3);
  EXPECT_EQ(r.dof, 1);
  EXPECT_NEAR(r.statistic, 1.0 / 6.0 + 1.0 / 54.0, 1e-12);
  EXPECT_TRUE(r.passed);
  // An observation where nothing is expected rejects outright.
  r = fenestra_test::pearson_chi2({1, 10, 10}, {0, 10.5, 10.5}, 0.01);
  EXPECT_FALSE(r.passed);
}

TEST(ChiSquare, DetectsAFivePercentTiltOfTheDensity) {
  // Cosine-hemisphere samples against a density that differs by a 5% azimuthal tilt (still normalised).
  const SphereGrid g = hemisphere_grid();
  const Chi2Result r = fenestra_test::sphere_chi2(
      g, kChi2Samples, 11,
      [](Rng& rng, Vec3* d) {
        *d = square_to_cosine_hemisphere(next2(rng));
        return true;
      },
      [](const Vec3& d) { return square_to_cosine_hemisphere_pdf(d) * (1.0f + 0.05f * d.x()); }, kSignificance);
  EXPECT_FALSE(r.passed) << r.message;
  EXPECT_LT(r.p_value, 1e-6) << r.message;
}

TEST(ChiSquare, DetectsSamplesWhereThePdfIsZero) {
  const SphereGrid g = sphere_grid();
  const Chi2Result r = fenestra_test::sphere_chi2(
      g, 100000, 12,
      [](Rng& rng, Vec3* d) {
        *d = square_to_uniform_sphere(next2(rng));
        return true;
      },
      [](const Vec3& d) { return square_to_cosine_hemisphere_pdf(d); }, kSignificance);
  EXPECT_FALSE(r.passed) << r.message;
}

// ============================================================================================
// Warps.

TEST(SamplingWarp, CosineHemispherePdfIntegratesToOne) {
  const double integral = fenestra_test::integrate_sphere([](const Vec3& d) { return square_to_cosine_hemisphere_pdf(d); });
  // Quadrature error is negligible (smooth pieces); float evaluation errors are ~1e-7 relative.
  EXPECT_NEAR(integral, 1.0, 1e-5);
}

TEST(SamplingWarp, UniformSpherePdfIntegratesToOne) {
  const double integral = fenestra_test::integrate_sphere([](const Vec3& d) { return square_to_uniform_sphere_pdf(d); });
  EXPECT_NEAR(integral, 1.0, 1e-5);
}

std::vector<Vec2> round_trip_points() {
  std::vector<Vec2> us;
  const float last = std::nextafter(1.0f, 0.0f);
  for (int i = 0; i <= 16; ++i)
    for (int j = 0; j <= 16; ++j) us.emplace_back(std::min(i / 16.0f, last), std::min(j / 16.0f, last));
  Rng rng(21, 0);
  for (int i = 0; i < 200000; ++i) us.push_back(next2(rng));
  return us;
}

TEST(SamplingWarp, CosineHemisphereInverseRoundTrips) {
  int failures = 0;
  for (const Vec2& u : round_trip_points()) {
    const Vec3 d = square_to_cosine_hemisphere(u);
    ASSERT_NEAR(d.norm(), 1.0f, 1e-5f) << u.transpose();
    ASSERT_GE(d.z(), 0.0f);
    const Vec2 back = cosine_hemisphere_to_square(d);
    if (std::abs(back.x() - u.x()) > 1e-4f || std::abs(back.y() - u.y()) > 1e-4f) {
      if (++failures <= 10) ADD_FAILURE() << "u = " << u.transpose() << " -> " << d.transpose() << " -> " << back.transpose();
    }
  }
  EXPECT_EQ(failures, 0);
}

TEST(SamplingWarp, UniformSphereInverseRoundTrips) {
  int failures = 0;
  for (const Vec2& u : round_trip_points()) {
    const Vec3 d = square_to_uniform_sphere(u);
    ASSERT_NEAR(d.norm(), 1.0f, 1e-5f) << u.transpose();
    const Vec2 back = uniform_sphere_to_square(d);
    // u.y is the azimuth: periodic, and undefined at the poles.
    const bool pole = d.x() == 0.0f && d.y() == 0.0f;
    if (std::abs(back.x() - u.x()) > 1e-4f || (!pole && std::abs(periodic_difference(back.y(), u.y())) > 1e-4)) {
      if (++failures <= 10) ADD_FAILURE() << "u = " << u.transpose() << " -> " << d.transpose() << " -> " << back.transpose();
    }
    EXPECT_GE(back.y(), 0.0f);
    EXPECT_LE(back.y(), 1.0f);
  }
  EXPECT_EQ(failures, 0);
}

TEST(SamplingWarp, CosineHemisphereChi2) {
  const Chi2Result r = fenestra_test::sphere_chi2(
      hemisphere_grid(), kChi2Samples, 1,
      [](Rng& rng, Vec3* d) {
        *d = square_to_cosine_hemisphere(next2(rng));
        return true;
      },
      [](const Vec3& d) { return square_to_cosine_hemisphere_pdf(d); }, kSignificance);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(SamplingWarp, UniformSphereChi2) {
  const Chi2Result r = fenestra_test::sphere_chi2(
      sphere_grid(), kChi2Samples, 2,
      [](Rng& rng, Vec3* d) {
        *d = square_to_uniform_sphere(next2(rng));
        return true;
      },
      [](const Vec3& d) { return square_to_uniform_sphere_pdf(d); }, kSignificance);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(SamplingUniformSky, SamplesFollowPdf) {
  const UniformSky sky(Rgb(1.0f, 2.0f, 3.0f));
  EXPECT_NEAR(fenestra_test::integrate_sphere([&](const Vec3& d) { return sky.pdf(d); }), 1.0, 1e-5);
  Rng rng(3, 1);
  for (int i = 0; i < 1000; ++i) {
    float pdf = 0.0f;
    const Vec3 d = sky.sample(next2(rng), &pdf);
    ASSERT_FLOAT_EQ(pdf, sky.pdf(d));
    ASSERT_NEAR(d.norm(), 1.0f, 1e-5f);
    ASSERT_TRUE((sky.radiance(d) == Rgb(1.0f, 2.0f, 3.0f)).all());
  }
  const Chi2Result r = fenestra_test::sphere_chi2(
      sphere_grid(), kChi2Samples, 3,
      [&](Rng& rng, Vec3* d) {
        float pdf = 0.0f;
        *d = sky.sample(next2(rng), &pdf);
        return pdf > 0.0f;
      },
      [&](const Vec3& d) { return sky.pdf(d); }, kSignificance);
  EXPECT_TRUE(r.passed) << r.message;
}

// ============================================================================================
// Piecewise-constant distributions.

const std::vector<double> kWeights1D = {2.0, 0.0, 0.0, 5.0, 1.0, 0.0, 3.0, 0.5, 0.0};

// u values at and around every CDF step (as the distribution computes them), plus random ones.
std::vector<float> probe_values_1d(const Distribution1D& d, int random_count, uint64_t seed) {
  const float last = std::nextafter(1.0f, 0.0f);
  std::vector<float> us = {0.0f, last};
  for (int i = 0; i <= d.size(); ++i) {
    const float c = d.to_unit(static_cast<float>(i) / d.size());
    float below = c, above = c;
    us.push_back(std::min(c, last));
    for (int k = 0; k < 8; ++k) {
      below = std::nextafter(below, 0.0f);
      above = std::nextafter(above, 1.0f);
      us.push_back(std::max(below, 0.0f));
      us.push_back(std::min(above, last));
    }
  }
  Rng rng(seed, 0);
  for (int i = 0; i < random_count; ++i) us.push_back(rng.uniform());
  return us;
}

TEST(Distribution1D, PdfMatchesNormalisedWeights) {
  const Distribution1D d(kWeights1D);
  const int n = static_cast<int>(kWeights1D.size());
  double sum = 0.0;
  for (double w : kWeights1D) sum += w;
  const double mean = sum / n;
  EXPECT_EQ(d.size(), n);
  EXPECT_NEAR(d.integral(), mean, 1e-12);
  for (int i = 0; i < n; ++i) {
    const double expected = kWeights1D[i] / mean;
    EXPECT_NEAR(d.cell_pdf(i), expected, 1e-6 * expected) << i;
    for (double f : {0.01, 0.5, 0.99}) EXPECT_NEAR(d.pdf(static_cast<float>((i + f) / n)), expected, 1e-6 * expected) << i;
  }
}

TEST(Distribution1D, ZeroWeightCellsAreNeverSampled) {
  const Distribution1D d(kWeights1D);
  const int n = d.size();
  int bad = 0;
  for (float u : probe_values_1d(d, 1000000, 31)) {
    int index = -1;
    float pdf = 0.0f;
    const float x = d.sample(u, &index, &pdf);
    const int cell = std::clamp(static_cast<int>(x * n), 0, n - 1);  // the cell pdf(x) looks at
    const bool ok = x >= 0.0f && x < 1.0f && index >= 0 && index < n && kWeights1D[index] > 0.0 && cell == index &&
                    pdf > 0.0f && pdf == d.pdf(x);
    if (!ok && ++bad <= 10)
      ADD_FAILURE() << "u = " << u << " (" << std::hexfloat << u << std::defaultfloat << ") -> x = " << x
                    << ", index " << index << ", cell of x " << cell << ", pdf " << pdf << ", pdf(x) " << d.pdf(x);
  }
  EXPECT_EQ(bad, 0);
}

// The guide table only shortens the search: every u lands in the cell a binary search over the
// whole CDF finds (CDF summed as the distribution sums it), for flat, peaked and sparse weights.
TEST(Distribution1D, GuidedSearchFindsTheCellOfAFullBinarySearch) {
  Rng weights_rng(7, 0);
  std::vector<std::vector<double>> cases = {kWeights1D, {1.0}, {0.0, 0.0, 1.0}, std::vector<double>(1000, 1.0)};
  std::vector<double> peaked(4096, 1e-9);  // a sun: almost all the mass in three cells
  peaked[2000] = peaked[2001] = peaked[2002] = 1.0;
  cases.push_back(peaked);
  std::vector<double> sparse(513, 0.0), random(777);
  for (double& w : sparse) w = weights_rng.uniform() < 0.1 ? weights_rng.uniform() : 0.0;
  for (double& w : random) w = std::pow(weights_rng.uniform(), 8.0);
  cases.push_back(sparse);
  cases.push_back(random);
  for (size_t c = 0; c < cases.size(); ++c) {
    const Distribution1D d(cases[c]);
    const int n = d.size();
    double sum = 0.0;
    for (double w : cases[c]) sum += w;
    std::vector<double> f = cases[c];
    if (sum <= 0.0) std::fill(f.begin(), f.end(), 1.0), sum = n;
    std::vector<double> cdf(n + 1, 0.0);
    for (int i = 0; i < n; ++i) cdf[i + 1] = cdf[i] + f[i] / sum;
    cdf[n] = 1.0;
    int bad = 0;
    for (float u : probe_values_1d(d, 200000, 41 + c)) {
      int expected = static_cast<int>(std::upper_bound(cdf.begin(), cdf.end(), static_cast<double>(u)) - cdf.begin()) - 1;
      expected = std::clamp(expected, 0, n - 1);
      while (expected < n - 1 && f[expected] == 0.0) ++expected;
      int index = -1;
      d.sample(u, &index, nullptr);
      if (index != expected && ++bad <= 5) ADD_FAILURE() << "case " << c << ", u = " << u << ": cell " << index << ", expected " << expected;
    }
    EXPECT_EQ(bad, 0) << "case " << c;
  }
}

TEST(Distribution1D, ToUnitInvertsSample) {
  const Distribution1D d(kWeights1D);
  const int n = d.size();
  // x has float rounding (2^-24), amplified by the CDF's slope (pdf <= 5 / (11.5 / 9) < 4): < 1e-6.
  for (float u : probe_values_1d(d, 100000, 32)) {
    const float x = d.sample(u, nullptr, nullptr);
    ASSERT_NEAR(d.to_unit(x), u, 1e-5f) << "u = " << u << ", x = " << x;
  }
  // And sample(to_unit(x)) = x for x in cells that can be sampled.
  Rng rng(33, 0);
  for (int i = 0; i < 100000; ++i) {
    const float x = rng.uniform();
    if (kWeights1D[std::min(static_cast<int>(x * n), n - 1)] == 0.0) continue;
    ASSERT_NEAR(d.sample(d.to_unit(x), nullptr, nullptr), x, 1e-5f) << "x = " << x;
  }
  EXPECT_EQ(d.to_unit(0.0f), 0.0f);
  EXPECT_EQ(d.to_unit(1.0f), 1.0f);
}

TEST(Distribution1D, SampleFrequenciesMatchWeights) {
  const Distribution1D d(kWeights1D);
  const int n = d.size();
  double sum = 0.0;
  for (double w : kWeights1D) sum += w;
  std::vector<double> observed(n, 0.0), expected(n);
  const int samples = 200000;
  Rng rng(34, 0);
  for (int i = 0; i < samples; ++i) {
    int index = 0;
    d.sample(rng.uniform(), &index, nullptr);
    observed[index] += 1.0;
  }
  for (int i = 0; i < n; ++i) expected[i] = samples * kWeights1D[i] / sum;
  const Chi2Result r = fenestra_test::pearson_chi2(observed, expected, kSignificance);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Distribution1D, AllZeroWeightsSampleUniformly) {
  const Distribution1D d(std::vector<double>(5, 0.0));
  EXPECT_EQ(d.integral(), 0.0);
  Rng rng(35, 0);
  for (int i = 0; i < 1000; ++i) {
    const float u = rng.uniform();
    float pdf = 0.0f;
    EXPECT_NEAR(d.sample(u, nullptr, &pdf), u, 1e-6f);
    EXPECT_FLOAT_EQ(pdf, 1.0f);
    EXPECT_FLOAT_EQ(d.pdf(u), 1.0f);
  }
}

TEST(Distribution1D, RejectsInvalidWeights) {
  EXPECT_THROW(Distribution1D(std::vector<double>{}), std::invalid_argument);
  EXPECT_THROW(Distribution1D(std::vector<double>{1.0, -0.5}), std::invalid_argument);
  EXPECT_THROW(Distribution1D(std::vector<double>{1.0, std::nan("")}), std::invalid_argument);
  EXPECT_THROW(Distribution1D(std::vector<double>{1.0, INFINITY}), std::invalid_argument);
}

// 7 x 5 weights (rows are v), with a zero row, zero cells and a dominant cell.
constexpr int kW2 = 7, kH2 = 5;
const std::vector<double> kWeights2D = {
    1.0, 2.0, 0.0, 3.0,  1.0, 1.0, 0.5,  //
    0.0, 0.0, 0.0, 0.0,  0.0, 0.0, 0.0,  //
    2.0, 0.0, 4.0, 40.0, 0.0, 1.0, 0.0,  //
    0.0, 0.0, 0.3, 0.0,  0.0, 0.0, 0.0,  //
    1.0, 1.0, 1.0, 1.0,  1.0, 1.0, 1.0,
};

double weight2d(const Vec2& p) {
  const int x = std::clamp(static_cast<int>(p.x() * kW2), 0, kW2 - 1);
  const int y = std::clamp(static_cast<int>(p.y() * kH2), 0, kH2 - 1);
  return kWeights2D[y * kW2 + x];
}

TEST(Distribution2D, PdfMatchesNormalisedWeights) {
  const Distribution2D d(kWeights2D, kW2, kH2);
  double sum = 0.0;
  for (double w : kWeights2D) sum += w;
  const double mean = sum / (kW2 * kH2);
  EXPECT_NEAR(d.integral(), mean, 1e-12);
  for (int y = 0; y < kH2; ++y)
    for (int x = 0; x < kW2; ++x)
      for (double f : {0.02, 0.5, 0.98}) {
        const Vec2 p(static_cast<float>((x + f) / kW2), static_cast<float>((y + 1.0 - f) / kH2));
        const double expected = kWeights2D[y * kW2 + x] / mean;
        EXPECT_NEAR(d.pdf(p), expected, 1e-6 * expected + 1e-12) << x << "," << y;
      }
}

TEST(Distribution2D, ZeroWeightCellsAreNeverSampledAndPdfsAgree) {
  const Distribution2D d(kWeights2D, kW2, kH2);
  Rng rng(41, 0);
  int bad = 0;
  for (int i = 0; i < 1000000; ++i) {
    const Vec2 u = next2(rng);
    float pdf = 0.0f;
    const Vec2 p = d.sample(u, &pdf);
    const bool ok = p.x() >= 0.0f && p.x() < 1.0f && p.y() >= 0.0f && p.y() < 1.0f && weight2d(p) > 0.0 &&
                    pdf > 0.0f && std::abs(pdf - d.pdf(p)) <= 1e-6f * pdf;
    if (!ok && ++bad <= 10)
      ADD_FAILURE() << "u = " << u.transpose() << " -> " << p.transpose() << ", weight " << weight2d(p) << ", pdf "
                    << pdf << ", pdf(p) " << d.pdf(p);
  }
  EXPECT_EQ(bad, 0);
}

TEST(Distribution2D, ToUnitInvertsSample) {
  const Distribution2D d(kWeights2D, kW2, kH2);
  Rng rng(42, 0);
  for (int i = 0; i < 200000; ++i) {
    const Vec2 u = next2(rng);
    const Vec2 p = d.sample(u, nullptr);
    const Vec2 back = d.to_unit(p);
    // pdf <= 40 / 2.1 < 20 per axis: float rounding of p (6e-8) moves the CDF by < 2e-6.
    ASSERT_NEAR(back.x(), u.x(), 1e-5f) << u.transpose() << " -> " << p.transpose();
    ASSERT_NEAR(back.y(), u.y(), 1e-5f) << u.transpose() << " -> " << p.transpose();
  }
}

TEST(Distribution2D, SampleFrequenciesMatchWeights) {
  const Distribution2D d(kWeights2D, kW2, kH2);
  double sum = 0.0;
  for (double w : kWeights2D) sum += w;
  const int samples = 400000;
  std::vector<double> observed(kWeights2D.size(), 0.0), expected(kWeights2D.size());
  Rng rng(43, 0);
  for (int i = 0; i < samples; ++i) {
    const Vec2 p = d.sample(next2(rng), nullptr);
    const int x = std::min(static_cast<int>(p.x() * kW2), kW2 - 1), y = std::min(static_cast<int>(p.y() * kH2), kH2 - 1);
    observed[y * kW2 + x] += 1.0;
  }
  for (size_t i = 0; i < kWeights2D.size(); ++i) expected[i] = samples * kWeights2D[i] / sum;
  const Chi2Result r = fenestra_test::pearson_chi2(observed, expected, kSignificance);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Distribution2D, RejectsMismatchedSize) {
  EXPECT_THROW(Distribution2D(std::vector<double>(6, 1.0), 4, 2), std::invalid_argument);
  EXPECT_THROW(Distribution2D(std::vector<double>{}, 0, 0), std::invalid_argument);
}

// ============================================================================================
// GGX visible normals.

struct GgxCase {
  float alpha;
  double theta_o_deg;
};
// Near-specular and rough lobes, from normal to grazing view; alpha 1e-3 is the smallest the
// BSDFs use (roughness <= 0.0316).
const std::vector<GgxCase> kGgxCases = {{0.001f, 30.0}, {0.05f, 0.0}, {0.05f, 40.0}, {0.05f, 86.0},
                                        {0.3f, 75.0},   {0.7f, 0.0},  {0.7f, 55.0},  {0.7f, 86.0}};

Vec3 ggx_wo(const GgxCase& c) { return spherical(c.theta_o_deg, 0.7); }

std::string describe(const GgxCase& c) {
  return "alpha " + std::to_string(c.alpha) + ", theta_o " + std::to_string(c.theta_o_deg) + " deg";
}

TEST(Ggx, VisibleNormalPdfIntegratesToOne) {
  for (const GgxCase& c : kGgxCases) {
    const Ggx ggx{c.alpha};
    const Vec3 wo = ggx_wo(c);
    const double integral = fenestra_test::integrate_sphere([&](const Vec3& h) { return ggx.visible_normal_pdf(wo, h); });
    // Peaked lobes (alpha 0.05) still span many quadrature pieces (13 mrad wide).
    EXPECT_NEAR(integral, 1.0, 1e-4) << describe(c);
  }
}

TEST(Ggx, ReflectionPdfIntegratesToAtMostOne) {
  // The reflected-direction density misses the mass of the reflections that go below the horizon,
  // which must match the fraction of sampled reflections that do.
  const int samples = 200000;
  for (const GgxCase& c : kGgxCases) {
    const Ggx ggx{c.alpha};
    const Vec3 wo = ggx_wo(c);
    const double integral = fenestra_test::integrate_sphere([&](const Vec3& wi) { return ggx.reflection_pdf(wo, wi); });
    EXPECT_LE(integral, 1.0 + 1e-4) << describe(c);
    Rng rng(51, 0);
    int above = 0;
    for (int i = 0; i < samples; ++i) above += reflect(wo, ggx.sample_visible_normal(wo, next2(rng))).z() > 0.0f;
    const double p = static_cast<double>(above) / samples;
    const double se = std::sqrt(std::max(p * (1.0 - p), 1.0 / samples) / samples);
    EXPECT_NEAR(integral, p, 4.0 * se + 1e-4) << describe(c);
    // Rough lobes lose a visible part of their reflections below the horizon.
    if (c.alpha >= 0.7f) {
      EXPECT_LT(integral, 1.0 - 10.0 * se) << describe(c);
    }
  }
}

TEST(Ggx, SampledNormalsFaceTheViewer) {
  for (const GgxCase& c : kGgxCases) {
    const Ggx ggx{c.alpha};
    const Vec3 wo = ggx_wo(c);
    Rng rng(52, 0);
    for (int i = 0; i < 20000; ++i) {
      const Vec3 h = ggx.sample_visible_normal(wo, next2(rng));
      ASSERT_NEAR(h.norm(), 1.0f, 1e-5f) << describe(c);
      ASSERT_GT(h.z(), 0.0f) << describe(c);
      ASSERT_GE(wo.dot(h), -1e-6f) << describe(c) << " h " << h.transpose();
    }
  }
}

// One test per lobe so that each stays short; the significance is corrected for the family.
class GgxLobe : public ::testing::TestWithParam<GgxCase> {};

TEST_P(GgxLobe, VisibleNormalChi2) {
  const GgxCase c = GetParam();
  const double alpha = fenestra_test::sidak_correction(kSignificance, static_cast<int>(kGgxCases.size()));
  const Ggx ggx{c.alpha};
  const Vec3 wo = ggx_wo(c);
  const Chi2Result r = fenestra_test::sphere_chi2(
      hemisphere_grid(), kChi2Samples, 53,
      [&](Rng& rng, Vec3* h) {
        *h = ggx.sample_visible_normal(wo, next2(rng));
        return true;
      },
      [&](const Vec3& h) { return ggx.visible_normal_pdf(wo, h); }, alpha);
  EXPECT_TRUE(r.passed) << describe(c) << ": " << r.message;
}

TEST_P(GgxLobe, ReflectionChi2) {
  const GgxCase c = GetParam();
  const double alpha = fenestra_test::sidak_correction(kSignificance, static_cast<int>(kGgxCases.size()));
  const Ggx ggx{c.alpha};
  const Vec3 wo = ggx_wo(c);
  // Reflections below the horizon land in the outside bin, expected to hold 1 - integral of the pdf.
  const Chi2Result r = fenestra_test::sphere_chi2(
      hemisphere_grid(), kChi2Samples, 54,
      [&](Rng& rng, Vec3* wi) {
        *wi = reflect(wo, ggx.sample_visible_normal(wo, next2(rng)));
        return wi->z() > 0.0f;
      },
      [&](const Vec3& wi) { return ggx.reflection_pdf(wo, wi); }, alpha);
  EXPECT_TRUE(r.passed) << describe(c) << ": " << r.message;
}

std::string ggx_case_name(const ::testing::TestParamInfo<GgxCase>& info) {
  std::string s = "alpha" + std::to_string(info.param.alpha) + "_theta" + std::to_string(static_cast<int>(info.param.theta_o_deg));
  for (char& ch : s)
    if (ch == '.') ch = '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(Ggx, GgxLobe, ::testing::ValuesIn(kGgxCases), ggx_case_name);

// ============================================================================================
// Environment maps.

constexpr int kEnvW = 33, kEnvH = 17;

// Gradient sky with a bright sun-like spot, black patches below the horizon and in the sky,
// and a dim ground down to the nadir (bottom three rows).
std::vector<Rgb> gradient_spot_pixels() {
  std::vector<Rgb> px(kEnvW * kEnvH);
  for (int y = 0; y < kEnvH; ++y)
    for (int x = 0; x < kEnvW; ++x) {
      Rgb p(0.2f + 0.8f * x / (kEnvW - 1), 0.1f + 0.9f * (kEnvH - 1 - y) / (kEnvH - 1), 0.3f + 0.02f * x);
      if (y >= kEnvH - 3) p = Rgb(0.05f, 0.04f, 0.03f);
      if ((y == 11 || y == 12) && x >= 10 && x <= 25) p = Rgb::Zero();
      if (y == 6 && x >= 20 && x <= 22) p = Rgb::Zero();
      if (y == 3 && (x == 5 || x == 6)) p = Rgb(300.0f, 250.0f, 200.0f);
      if (y == 4 && x == 5) p = Rgb(80.0f, 60.0f, 40.0f);
      px[y * kEnvW + x] = p;
    }
  return px;
}

// Almost black: one bright pixel near the horizon, one dim pixel next to the zenith.
std::vector<Rgb> spot_pixels() {
  std::vector<Rgb> px(kEnvW * kEnvH, Rgb::Zero());
  px[9 * kEnvW + 24] = Rgb(1000.0f, 1000.0f, 900.0f);
  px[0 * kEnvW + 3] = Rgb(5.0f, 5.0f, 5.0f);
  return px;
}

// Every pixel distinct: (x, y, 1).
std::vector<Rgb> index_pixels(int w, int h) {
  std::vector<Rgb> px(w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) px[y * w + x] = Rgb(float(x), float(y), 1.0f);
  return px;
}

Rgb index_pixel(int x, int y) { return Rgb(float(x), float(y), 1.0f); }

// The map's pixel edges as world-space (theta, phi) breakpoints for the quadrature.
SphereGrid env_grid(float rotation_deg) {
  SphereGrid g = sphere_grid();
  for (int j = 1; j < kEnvH; ++j) g.theta_breaks.push_back(kPiD * j / kEnvH);
  for (int i = 0; i < kEnvW; ++i) g.phi_breaks.push_back(2.0 * kPiD * (0.5 - double(i) / kEnvW) + rotation_deg * kPiD / 180.0);
  return g;
}

struct EnvCase {
  const char* name;
  std::vector<Rgb> pixels;
  float rotation_deg;
};

std::vector<EnvCase> env_cases() {
  return {{"gradient+spot", gradient_spot_pixels(), 0.0f},
          {"gradient+spot rotated 37", gradient_spot_pixels(), 37.0f},
          {"spot", spot_pixels(), 0.0f},
          {"spot rotated -120", spot_pixels(), -120.0f}};
}

void expect_direction_near(const Vec3& a, const Vec3& b, const char* what) {
  EXPECT_NEAR((a - b).norm(), 0.0f, 1e-5f) << what << ": " << a.transpose() << " vs " << b.transpose();
}

void expect_rgb_eq(const Rgb& a, const Rgb& b, const std::string& what) {
  EXPECT_TRUE((a == b).all()) << what << ": " << a.transpose() << " vs " << b.transpose();
}

TEST(EnvironmentMap, TopRowIsZenith) {
  const EnvironmentMap map(kEnvW, kEnvH, index_pixels(kEnvW, kEnvH), 1.0f, 0.0f);
  EXPECT_EQ(map.direction_to_uv(Vec3(0, 0, 1)).y(), 0.0f);
  EXPECT_EQ(map.radiance(Vec3(0, 0, 1))[1], 0.0f);
  EXPECT_EQ(map.radiance(Vec3(0, 0, -1))[1], float(kEnvH - 1));
  // Just off the poles, at any azimuth, the first and last rows.
  for (double phi = 0.05; phi < 2 * kPiD; phi += 0.5) {
    EXPECT_EQ(map.radiance(spherical(2.0, phi))[1], 0.0f) << phi;
    EXPECT_EQ(map.radiance(spherical(178.0, phi))[1], float(kEnvH - 1)) << phi;
    // Rows are uniform in polar angle: the horizon is the middle row.
    EXPECT_EQ(map.radiance(spherical(90.0, phi))[1], float(kEnvH / 2)) << phi;
  }
  for (float u : {0.0f, 0.3f, 0.8f}) {
    expect_direction_near(map.uv_to_direction(Vec2(u, 0.0f)), Vec3(0, 0, 1), "v = 0");
    expect_direction_near(map.uv_to_direction(Vec2(u, 0.5f)).cwiseProduct(Vec3(0, 0, 1)), Vec3(0, 0, 0), "v = 0.5");
  }
}

TEST(EnvironmentMap, CentreColumnLooksAlongPlusX) {
  const EnvironmentMap map(kEnvW, kEnvH, index_pixels(kEnvW, kEnvH), 1.0f, 0.0f);
  const Vec2 uv = map.direction_to_uv(Vec3(1, 0, 0));
  EXPECT_NEAR(uv.x(), 0.5f, 1e-6f);
  EXPECT_NEAR(uv.y(), 0.5f, 1e-6f);
  expect_direction_near(map.uv_to_direction(Vec2(0.5f, 0.5f)), Vec3(1, 0, 0), "uv (0.5, 0.5)");
  expect_rgb_eq(map.radiance(Vec3(1, 0, 0)), index_pixel(kEnvW / 2, kEnvH / 2), "+X");
}

TEST(EnvironmentMap, QuarterAcrossLooksAlongPlusY) {
  const EnvironmentMap map(kEnvW, kEnvH, index_pixels(kEnvW, kEnvH), 1.0f, 0.0f);
  // u = 0.5 - atan2(y, x) / (2 pi): +Y at u = 0.25, -Y at 0.75, -X at the seam.
  EXPECT_NEAR(map.direction_to_uv(Vec3(0, 1, 0)).x(), 0.25f, 1e-6f);
  EXPECT_NEAR(map.direction_to_uv(Vec3(0, -1, 0)).x(), 0.75f, 1e-6f);
  EXPECT_NEAR(periodic_difference(map.direction_to_uv(Vec3(-1, 0, 0)).x(), 0.0), 0.0, 1e-6);
  expect_direction_near(map.uv_to_direction(Vec2(0.25f, 0.5f)), Vec3(0, 1, 0), "uv (0.25, 0.5)");
  expect_direction_near(map.uv_to_direction(Vec2(0.75f, 0.5f)), Vec3(0, -1, 0), "uv (0.75, 0.5)");
  expect_rgb_eq(map.radiance(Vec3(0, 1, 0)), index_pixel(8, kEnvH / 2), "+Y");     // u * 33 = 8.25
  expect_rgb_eq(map.radiance(Vec3(0, -1, 0)), index_pixel(24, kEnvH / 2), "-Y");  // u * 33 = 24.75
  // Azimuth grows counter-clockwise seen from above while u decreases.
  EXPECT_LT(map.direction_to_uv(spherical(90.0, 0.1)).x(), 0.5f);
}

TEST(EnvironmentMap, RotationTurnsTheMapCounterClockwiseAboutZ) {
  const EnvironmentMap map0(kEnvW, kEnvH, index_pixels(kEnvW, kEnvH), 1.0f, 0.0f);
  const EnvironmentMap map90(kEnvW, kEnvH, index_pixels(kEnvW, kEnvH), 1.0f, 90.0f);
  // What the unrotated map shows along +X, the map rotated by 90 degrees shows along +Y.
  expect_rgb_eq(map90.radiance(Vec3(0, 1, 0)), map0.radiance(Vec3(1, 0, 0)), "+Y after 90");
  expect_rgb_eq(map90.radiance(Vec3(-1, 0, 0)), map0.radiance(Vec3(0, 1, 0)), "-X after 90");
  expect_rgb_eq(map90.radiance(Vec3(0, 1, 0)), index_pixel(kEnvW / 2, kEnvH / 2), "+Y after 90");
  const Vec2 uv = map90.direction_to_uv(Vec3(0, 1, 0));
  EXPECT_NEAR(uv.x(), 0.5f, 1e-6f);
  EXPECT_NEAR(uv.y(), 0.5f, 1e-6f);
  expect_direction_near(map90.uv_to_direction(Vec2(0.5f, 0.5f)), Vec3(0, 1, 0), "rotated uv (0.5, 0.5)");
  // Any rotation: looking up direction R_z(angle) d in the rotated map = looking up d in the original.
  for (float deg : {37.0f, -120.0f, 200.0f}) {
    const EnvironmentMap rot(kEnvW, kEnvH, index_pixels(kEnvW, kEnvH), 1.0f, deg);
    const Eigen::Matrix3f rz = Eigen::AngleAxisf(deg * kPi / 180.0f, Vec3::UnitZ()).toRotationMatrix();
    Rng rng(61, 0);
    for (int i = 0; i < 2000; ++i) {
      const Vec3 d = square_to_uniform_sphere(next2(rng));
      const Vec2 a = map0.direction_to_uv(d), b = rot.direction_to_uv(rz * d);
      ASSERT_NEAR(periodic_difference(a.x(), b.x()), 0.0, 1e-5) << deg << " " << d.transpose();
      ASSERT_NEAR(a.y(), b.y(), 1e-5f) << deg << " " << d.transpose();
    }
  }
}

TEST(EnvironmentMap, UvDirectionRoundTrip) {
  for (float deg : {0.0f, 37.0f, -120.0f}) {
    const EnvironmentMap map(kEnvW, kEnvH, index_pixels(kEnvW, kEnvH), 1.0f, deg);
    Rng rng(62, 0);
    for (int i = 0; i < 100000; ++i) {
      Vec2 uv = next2(rng);
      uv.y() = 0.001f + 0.998f * uv.y();  // u is undefined at the poles
      const Vec3 d = map.uv_to_direction(uv);
      ASSERT_NEAR(d.norm(), 1.0f, 1e-5f);
      const Vec2 back = map.direction_to_uv(d);
      ASSERT_NEAR(periodic_difference(back.x(), uv.x()), 0.0, 1e-4) << deg << " " << uv.transpose();
      ASSERT_NEAR(back.y(), uv.y(), 1e-4f) << deg << " " << uv.transpose();
      ASSERT_GE(back.x(), 0.0f);
      ASSERT_LT(back.x(), 1.0f);
    }
  }
}

TEST(EnvironmentMap, ScaleMultipliesRadiance) {
  const EnvironmentMap map(kEnvW, kEnvH, index_pixels(kEnvW, kEnvH), 2.5f, 0.0f);
  expect_rgb_eq(map.radiance(Vec3(1, 0, 0)), index_pixel(kEnvW / 2, kEnvH / 2) * 2.5f, "scaled +X");
}

TEST(EnvironmentMap, RejectsBadPixels) {
  EXPECT_THROW(EnvironmentMap(4, 2, std::vector<Rgb>(7, Rgb::Ones()), 1.0f, 0.0f), std::invalid_argument);
  std::vector<Rgb> px(8, Rgb::Ones());
  px[3] = Rgb(1.0f, -1.0f, 1.0f);
  EXPECT_THROW(EnvironmentMap(4, 2, px, 1.0f, 0.0f), std::invalid_argument);
  px[3] = Rgb(1.0f, NAN, 1.0f);
  EXPECT_THROW(EnvironmentMap(4, 2, px, 1.0f, 0.0f), std::invalid_argument);
}

TEST(EnvironmentMap, PdfIntegratesToOne) {
  for (const EnvCase& c : env_cases()) {
    const EnvironmentMap map(kEnvW, kEnvH, c.pixels, 1.0f, c.rotation_deg);
    const SphereGrid g = env_grid(c.rotation_deg);
    // Split at the pixel edges, pdf * sin(theta) is constant on each quadrature piece: exact up to float.
    const double integral = fenestra_test::integrate_sphere([&](const Vec3& d) { return map.pdf(d); }, g.theta_breaks,
                                                            g.phi_breaks, 4);
    EXPECT_NEAR(integral, 1.0, 1e-4) << c.name;
  }
}

TEST(EnvironmentMap, PdfTimesSinThetaIsConstantWithinAPixelUpToThePoles) {
  // In solid angle the pdf is D(u, v) / (2 pi^2 sin(theta)), so pdf * sin(theta) is constant
  // over a pixel, however close to the zenith or the nadir.
  for (float deg : {0.0f, 37.0f}) {
    const EnvironmentMap map(kEnvW, kEnvH, gradient_spot_pixels(), 1.0f, deg);
    for (double phi : {0.3, 2.0, 4.4}) {
      for (double pole : {0.0, kPiD}) {
        const Vec3 ref = spherical(pole == 0.0 ? 3.0 : 177.0, phi);
        const double expected = map.pdf(ref) * std::hypot(ref.x(), ref.y());
        ASSERT_GT(expected, 0.0);
        for (double eps : {1e-2, 1e-3, 1e-4, 3e-5, 1e-6}) {
          const Vec3 d = SphereGrid::direction(pole == 0.0 ? eps : kPiD - eps, phi);
          const double sin_theta = std::hypot(d.x(), d.y());
          // float directions: a few ulps of relative error in x, y and in the pdf.
          EXPECT_NEAR(map.pdf(d) * sin_theta, expected, 1e-5 * expected)
              << "rotation " << deg << ", theta " << (pole == 0.0 ? eps : kPiD - eps) << ", phi " << phi;
        }
      }
    }
  }
}

TEST(EnvironmentMap, SamplesMatchPdfAndAvoidBlackPixels) {
  for (const EnvCase& c : env_cases()) {
    const EnvironmentMap map(kEnvW, kEnvH, c.pixels, 1.0f, c.rotation_deg);
    Rng rng(63, 0);
    int bad = 0, boundary = 0;
    const int samples = 200000;
    for (int i = 0; i < samples; ++i) {
      float pdf = 0.0f;
      const Vec3 d = map.sample(next2(rng), &pdf);
      const Vec2 uv = map.direction_to_uv(d);
      const double fu = uv.x() * kEnvW, fv = uv.y() * kEnvH;
      // Float rounding may carry a sample lying on a pixel edge into the neighbouring pixel.
      const bool on_edge = std::abs(fu - std::round(fu)) < 1e-4 || std::abs(fv - std::round(fv)) < 1e-4;
      const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - d.z() * d.z()));
      bool ok = std::isfinite(pdf) && pdf > 0.0f && std::abs(d.norm() - 1.0f) < 1e-5f;
      if (!on_edge) {
        ok = ok && luminance(map.radiance(d)) > 0.0f;
        // Near the poles, float z cannot pin theta down well enough to compare densities.
        if (sin_theta > 0.05f) ok = ok && std::abs(map.pdf(d) - pdf) <= 1e-4f * pdf;
      } else {
        ++boundary;
      }
      if (!ok && ++bad <= 10)
        ADD_FAILURE() << c.name << ": sample " << d.transpose() << " uv " << uv.transpose() << " pdf " << pdf
                      << " pdf() " << map.pdf(d) << " radiance " << map.radiance(d).transpose();
    }
    EXPECT_EQ(bad, 0) << c.name;
    EXPECT_LT(boundary, samples / 1000) << c.name;
  }
}

class EnvironmentMapChi2 : public ::testing::TestWithParam<int> {};

TEST_P(EnvironmentMapChi2, SamplesFollowPdf) {
  const std::vector<EnvCase> cases = env_cases();
  const EnvCase& c = cases.at(GetParam());
  const double alpha = fenestra_test::sidak_correction(kSignificance, static_cast<int>(cases.size()));
  const EnvironmentMap map(kEnvW, kEnvH, c.pixels, 1.0f, c.rotation_deg);
  const Chi2Result r = fenestra_test::sphere_chi2(
      env_grid(c.rotation_deg), kChi2Samples, 64,
      [&](Rng& rng, Vec3* d) {
        float pdf = 0.0f;
        *d = map.sample(next2(rng), &pdf);
        return pdf > 0.0f;
      },
      [&](const Vec3& d) { return map.pdf(d); }, alpha);
  EXPECT_TRUE(r.passed) << c.name << ": " << r.message;
}

INSTANTIATE_TEST_SUITE_P(EnvironmentMap, EnvironmentMapChi2, ::testing::Range(0, 4));

}  // namespace
}  // namespace fenestra

namespace fenestra {
namespace {

// Light sampling of a uniform sky toward a surface: cosine-weighted about its normal.
TEST(SamplingUniformSky, TowardANormalIsCosineWeighted) {
  const UniformSky sky(Rgb::Constant(2.0f));
  const Vec3 normal = Vec3(0.3f, -0.5f, 0.8f).normalized();
  Rng rng(11, 3);
  const int n = 200000;
  double sum_cos = 0.0, sum_cos2 = 0.0;
  for (int i = 0; i < n; ++i) {
    float pdf = 0.0f;
    const Vec3 d = sky.sample_toward(next2(rng), normal, &pdf);
    const float c = d.dot(normal);
    ASSERT_GE(c, -1e-6f);
    ASSERT_NEAR(pdf, sky.pdf_toward(d, normal), 1e-5f);
    ASSERT_NEAR(d.norm(), 1.0f, 1e-5f);
    sum_cos += c, sum_cos2 += c * c;
  }
  // E[cos] = 2/3 under the density cos / pi; variance from the samples.
  const double mean = sum_cos / n, se = std::sqrt((sum_cos2 / n - mean * mean) / (n - 1));
  EXPECT_NEAR(mean, 2.0 / 3.0, 4.0 * se);
  // The density integrates to one over the sphere (midpoint rule in theta, phi).
  double integral = 0.0;
  const int m = 400;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < 2 * m; ++j) {
      const double theta = (i + 0.5) * M_PI / m, phi = (j + 0.5) * M_PI / m;
      const Vec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      integral += sky.pdf_toward(d, normal) * std::sin(theta) * (M_PI / m) * (M_PI / m);
    }
  EXPECT_NEAR(integral, 1.0, 1e-3);
}

}  // namespace
}  // namespace fenestra
