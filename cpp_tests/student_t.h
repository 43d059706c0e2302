#pragma once
// Student's t distribution for tests that compare Monte Carlo values by their standard errors:
// Fenestra's standard errors come from kReplicates independent replicate groups (15 degrees of
// freedom), so "within k standard errors" must use t quantiles, not normal ones, to keep the
// false-alarm rate it claims. Regularized incomplete beta by its continued fraction (Numerical
// Recipes, 3rd ed., section 6.4).
#include <cmath>
#include <limits>

namespace fenestra::test {

inline double incomplete_beta_fraction(double a, double b, double x) {
  const double tiny = std::numeric_limits<double>::min() / std::numeric_limits<double>::epsilon();
  double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::abs(d) < tiny) d = tiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m < 10000; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((a - 1.0 + m2) * (a + m2));
    d = 1.0 + aa * d, c = 1.0 + aa / c;
    if (std::abs(d) < tiny) d = tiny;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d, h *= d * c;
    aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + 1.0 + m2));
    d = 1.0 + aa * d, c = 1.0 + aa / c;
    if (std::abs(d) < tiny) d = tiny;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-15) break;
  }
  return h;
}

// I_x(a, b).
inline double regularized_incomplete_beta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double front = std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x));
  if (x < (a + 1.0) / (a + b + 2.0)) return front * incomplete_beta_fraction(a, b, x) / a;
  return 1.0 - front * incomplete_beta_fraction(b, a, 1.0 - x) / b;
}

// P(|T| > t) for Student's t with nu degrees of freedom.
inline double student_t_two_sided(double t, double nu) {
  return regularized_incomplete_beta(0.5 * nu, 0.5, nu / (nu + t * t));
}

// The t with P(|T| > t) = p (bisection; p in (0, 1)).
inline double student_t_quantile(double p, double nu) {
  double lo = 0.0, hi = 1e3;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (student_t_two_sided(mid, nu) > p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The t quantile with the two-sided tail of a normal k sigma, for nu degrees of freedom.
inline double normal_equivalent_t(double k, double nu) {
  return student_t_quantile(std::erfc(k / std::sqrt(2.0)), nu);
}

}  // namespace fenestra::test
