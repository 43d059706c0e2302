// The sensor's portal sampling: solid-angle sampling of a rectangle (Urena et al. 2013), the
// bilinear warp that follows a receiver's cosine, and the view-weighted choice of elements.
// Densities: solid angles against the closed form, uniformity in solid angle by chi-square, the
// bilinear density's integral, and estimates of a view factor against Lambert's formula.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "chi2.h"
#include "sampling/spherical_rectangle.h"
#include "sampling/warp.h"
#include "trace/portal_selection.h"
#include "util/rng.h"

namespace fenestra {
namespace {

using fenestra_test::kSignificance;
using fenestra_test::next2;

// Solid angle of the rectangle [0, a] x [0, b] in the plane z = h seen from the origin (the
// closed form for a corner-on rectangle: atan(ab / (h sqrt(h^2 + a^2 + b^2)))).
double corner_solid_angle(double a, double b, double h) {
  return std::atan(a * b / (h * std::sqrt(h * h + a * a + b * b)));
}

TEST(SphericalRectangle, SolidAngleMatchesTheClosedForm) {
  for (const double h : {0.1, 1.0, 7.0}) {
    const SphericalRectangle r(Vec3(0, 0, 0), Vec3(0, 0, h), Vec3(2, 0, 0), Vec3(0, 0.5, 0));
    EXPECT_NEAR(r.solid_angle(), corner_solid_angle(2.0, 0.5, h), 1e-6 * corner_solid_angle(2.0, 0.5, h)) << h;
    // The same rectangle seen from below its plane, and with its edges given the other way round.
    const SphericalRectangle flipped(Vec3(0, 0, 2 * h), Vec3(0, 0, h), Vec3(0, 0.5, 0), Vec3(2, 0, 0));
    EXPECT_NEAR(flipped.solid_angle(), r.solid_angle(), 1e-6 * r.solid_angle());
  }
  // A rectangle around the foot of the perpendicular: four corner rectangles.
  const SphericalRectangle centred(Vec3(0, 0, 0), Vec3(-1, -2, 1.5), Vec3(3, 0, 0), Vec3(0, 5, 0));
  const double expected = corner_solid_angle(1, 2, 1.5) + corner_solid_angle(2, 2, 1.5) +
                          corner_solid_angle(1, 3, 1.5) + corner_solid_angle(2, 3, 1.5);
  EXPECT_NEAR(centred.solid_angle(), expected, 1e-6 * expected);
  // Edge-on: nothing.
  EXPECT_EQ(SphericalRectangle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)).solid_angle(), 0.0);
}

TEST(SphericalRectangle, SamplesLieOnTheRectangleUniformInSolidAngle) {
  // A rectangle seen obliquely from near by (1/d^2 and the cosine vary by 20x over it): the
  // samples' points, histogrammed on a 12 x 12 grid of the rectangle, against each cell's solid
  // angle (from a fine midpoint rule over the cell).
  const Vec3 from(0.3f, -0.4f, 0.0f), corner(0.0f, 0.0f, 0.2f), u(1.5f, 0.0f, 0.0f), v(0.0f, 0.0f, 1.0f);
  const Vec3 shifted = corner + Vec3(0, 0.3f, 0);  // the plane y = 0.3 ... seen from y = -0.4
  const SphericalRectangle r(from, shifted, u, v);
  const double omega = r.solid_angle();
  ASSERT_GT(omega, 0.0);
  constexpr int kGrid = 12, kSamples = 400000;
  std::vector<double> observed(kGrid * kGrid, 0.0), expected(kGrid * kGrid, 0.0);
  Rng rng(5, 1);
  for (int i = 0; i < kSamples; ++i) {
    const Vec3 p = r.sample(next2(rng));
    const double s = (p - shifted).dot(u) / u.squaredNorm(), t = (p - shifted).dot(v) / v.squaredNorm();
    ASSERT_NEAR((p - shifted).dot(Vec3(0, 1, 0)), 0.0, 1e-5);  // on the plane
    ASSERT_GE(s, -1e-5);
    ASSERT_LE(s, 1 + 1e-5);
    ASSERT_GE(t, -1e-5);
    ASSERT_LE(t, 1 + 1e-5);
    observed[std::min(kGrid - 1, int(s * kGrid)) * kGrid + std::min(kGrid - 1, int(t * kGrid))] += 1;
  }
  constexpr int kFine = 20;
  double total = 0.0;
  for (int a = 0; a < kGrid; ++a)
    for (int b = 0; b < kGrid; ++b) {
      double cell = 0.0;
      for (int i = 0; i < kFine; ++i)
        for (int j = 0; j < kFine; ++j) {
          const Vec3 p = shifted + ((a + (i + 0.5) / kFine) / kGrid) * u + ((b + (j + 0.5) / kFine) / kGrid) * v;
          const Vec3 d = p - from;
          const double r2 = d.squaredNorm();
          cell += std::abs(d.normalized().y()) / r2 * (u.norm() * v.norm()) / (kGrid * kGrid * kFine * kFine);
        }
      expected[a * kGrid + b] = cell;
      total += cell;
    }
  EXPECT_NEAR(total, omega, 1e-3 * omega);  // the midpoint rule agrees with the solid angle
  for (double& e : expected) e *= kSamples / total;
  const auto result = fenestra_test::pearson_chi2(observed, expected, kSignificance);
  EXPECT_TRUE(result.passed) << result.message;
}

TEST(BilinearWarp, DensityIntegratesToOneAndFollowsTheCorners) {
  const float w[4] = {0.1f, 1.0f, 0.5f, 2.0f};
  double integral = 0.0;
  constexpr int n = 200;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) integral += bilinear_pdf(Vec2((i + 0.5f) / n, (j + 0.5f) / n), w) / (n * n);
  EXPECT_NEAR(integral, 1.0, 1e-6);
  // Samples follow the density: chi-square on a 10 x 10 grid.
  constexpr int kGrid = 10, kSamples = 200000;
  std::vector<double> observed(kGrid * kGrid, 0.0), expected(kGrid * kGrid, 0.0);
  Rng rng(3, 2);
  for (int s = 0; s < kSamples; ++s) {
    const Vec2 p = square_to_bilinear(next2(rng), w);
    ASSERT_GE(p.x(), 0.0f);
    ASSERT_LT(p.x(), 1.0f);
    ASSERT_GE(p.y(), 0.0f);
    ASSERT_LT(p.y(), 1.0f);
    observed[std::min(kGrid - 1, int(p.x() * kGrid)) * kGrid + std::min(kGrid - 1, int(p.y() * kGrid))] += 1;
  }
  for (int a = 0; a < kGrid; ++a)
    for (int b = 0; b < kGrid; ++b)
      for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j)
          expected[a * kGrid + b] +=
              kSamples * bilinear_pdf(Vec2((a + (i + 0.5f) / 10) / kGrid, (b + (j + 0.5f) / 10) / kGrid), w) /
              (kGrid * kGrid * 100.0);
  const auto result = fenestra_test::pearson_chi2(observed, expected, kSignificance);
  EXPECT_TRUE(result.passed) << result.message;
}

TEST(PortalSampling, ViewFactorOfARectangleFromSolidAngleAndBilinearSamples) {
  // The point-to-rectangle view factor (Lambert's formula, a corner-on rectangle in a plane
  // perpendicular to the receiver, the classic table case) from 4 096 samples: cos / pdf. The
  // estimate's spread is far below area sampling's.
  const Vec3 x(0, 0, 0), n(0, 0, 1);
  const double a = 1.0, b = 2.0, c = 0.5;  // rectangle in the plane y = c: x in [0, a], z in [0, b]
  const Vec3 corner(0.0f, float(c), 0.0f), u(float(a), 0, 0), v(0, 0, float(b));
  // F = 1/(2 pi) [atan(1/Y) - Y / sqrt(X^2 + Y^2) atan(1 / sqrt(X^2 + Y^2))], X = b / a, Y = c / a,
  // with a the side along the line the two planes share (Howell's catalogue, B-3).
  const double X = b / a, Y = c / a, r = std::sqrt(X * X + Y * Y);
  const double exact = (std::atan(1.0 / Y) - Y / r * std::atan(1.0 / r)) / (2.0 * M_PI);
  const SphericalRectangle seen(x, corner, u, v);
  const Vec3 corners[4] = {corner, corner + u, corner + v, corner + u + v};
  float w[4];
  for (int k = 0; k < 4; ++k) w[k] = std::max(0.01f, (corners[k] - x).normalized().dot(n));
  Rng rng(9, 4);
  constexpr int kSamples = 4096, kTrials = 64;
  double sum = 0.0, sum_sq = 0.0;
  for (int t = 0; t < kTrials; ++t) {
    double estimate = 0.0;
    for (int s = 0; s < kSamples; ++s) {
      const Vec2 warped = square_to_bilinear(next2(rng), w);
      const Vec3 d = (seen.sample(warped) - x).normalized();
      const double pdf = bilinear_pdf(warped, w) / seen.solid_angle();
      estimate += std::max(0.0f, d.dot(n)) / M_PI / pdf / kSamples;
    }
    sum += estimate, sum_sq += estimate * estimate;
  }
  const double mean = sum / kTrials, sd = std::sqrt(std::max(0.0, sum_sq / kTrials - mean * mean));
  EXPECT_NEAR(mean, exact, 4.0 * sd / std::sqrt(double(kTrials)) + 1e-9);
  EXPECT_LT(sd / exact, 0.002) << "relative spread of one 4096-sample estimate";
}

TEST(SphericalRectangle, SolidAngleByTrianglesAgreesWithTheAngles) {
  Rng rng(11, 3);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 from(rng.uniform() * 4 - 2, rng.uniform() * 4 - 2, rng.uniform() * 4 - 2);
    const Vec3 corner(rng.uniform(), rng.uniform(), 0.5f), u(0.3f + rng.uniform(), 0, 0), v(0, 0.2f + rng.uniform(), 0);
    const double a = SphericalRectangle(from, corner, u, v).solid_angle(), b = rectangle_solid_angle(from, corner, u, v);
    ASSERT_NEAR(a, b, 1e-9 + 1e-7 * b) << i;
  }
}

TEST(PortalSelection, ProbabilitiesFollowTheViewWithAnEvenShare) {
  // Three elements seen, one behind the sensor (no share), weights 1, 3 and 6.
  const PortalSelection s({1.0, 3.0, 0.0, 6.0});
  const double even = kEvenPortalShare / 3.0, view = 1.0 - kEvenPortalShare;
  EXPECT_NEAR(s.probability(0), view * 0.1 + even, 1e-9);
  EXPECT_NEAR(s.probability(1), view * 0.3 + even, 1e-9);
  EXPECT_EQ(s.probability(2), 0.0);
  EXPECT_NEAR(s.probability(3), view * 0.6 + even, 1e-9);
  // Every 32-bit number picks the element whose interval holds it; the remainder is uniform.
  const uint32_t starts[3] = {0u, static_cast<uint32_t>(s.probability(0) * 4294967296.0),
                              static_cast<uint32_t>((s.probability(0) + s.probability(1)) * 4294967296.0)};
  EXPECT_EQ(s.choose(0).element, 0);
  EXPECT_EQ(s.choose(starts[1] + 1).element, 1);
  EXPECT_EQ(s.choose(starts[2] + 1).element, 3);
  EXPECT_EQ(s.choose(0xFFFFFFFFu).element, 3);
  EXPECT_NEAR(s.choose(starts[1] / 2).remainder, 0.5f, 1e-6f);
  // Nothing seen: any element, evenly.
  const PortalSelection none({0.0, 0.0});
  EXPECT_NEAR(none.probability(0), 0.5, 1e-9);
}

TEST(PortalSelection, ElementsBehindTheSensorWeighNothing) {
  PortalShape front, behind;
  front.corner = Vec3(-0.5f, 1.0f, 0.5f), front.u = Vec3(1, 0, 0), front.v = Vec3(0, 0, 1), front.normal = Vec3(0, 1, 0);
  behind = front;
  behind.corner = Vec3(-0.5f, 1.0f, -1.6f);  // z in [-1.6, -0.6]: below an upward sensor's plane
  const Vec3 point(0, 0, 0), up(0, 0, 1);
  EXPECT_GT(portal_view_weight(point, up, front), 0.0);
  EXPECT_EQ(portal_view_weight(point, up, behind), 0.0);
}

}  // namespace
}  // namespace fenestra
