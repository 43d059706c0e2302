#pragma once
// Chi-square goodness-of-fit machinery for sampling tests, after Mitsuba's chi2 module and
// pbrt's bsdfs_test: draw N directions, histogram them on a (theta, phi) grid, integrate the
// claimed pdf over every cell to get expected counts, pool sparse cells, and compare with
// Pearson's statistic. The p-value is the regularized upper incomplete gamma function
// Q(dof/2, chi2/2) (Numerical Recipes, 3rd ed., section 6.2).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "math/vec.h"
#include "util/rng.h"

namespace fenestra_test {

constexpr double kSignificance = 0.01;  // family-wise, per TEST (Sidak-corrected inside loops)

// Two uniforms in a fixed order (argument evaluation order is unspecified).
inline fenestra::Vec2 next2(fenestra::Rng& rng) {
  const float a = rng.uniform();
  const float b = rng.uniform();
  return fenestra::Vec2(a, b);
}

using fenestra::Vec2;
using fenestra::Vec3;
using fenestra::kPiD;

// ---------------------------------------------------------------------------------------------
// Incomplete gamma function.

// P(a, x) by its series; converges quickly for x < a + 1.
inline double gamma_p_series(double a, double x) {
  double ap = a, del = 1.0 / a, sum = del;
  for (int n = 0; n < 100000; ++n) {
    ap += 1.0;
    del *= x / ap;
    sum += del;
    if (std::abs(del) < std::abs(sum) * 1e-16) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) by its continued fraction (modified Lentz); converges quickly for x >= a + 1.
inline double gamma_q_continued_fraction(double a, double x) {
  const double tiny = std::numeric_limits<double>::min() / std::numeric_limits<double>::epsilon();
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-16) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

// Regularized upper incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a).
inline double regularized_gamma_q(double a, double x) {
  if (!(a > 0.0) || !(x >= 0.0)) throw std::invalid_argument("regularized_gamma_q: needs a > 0, x >= 0");
  if (x == 0.0) return 1.0;
  if (x < a + 1.0) return 1.0 - gamma_p_series(a, x);
  return gamma_q_continued_fraction(a, x);
}

// Probability that a chi-square variable with `dof` degrees of freedom is >= `statistic`.
inline double chi2_p_value(double statistic, int dof) { return regularized_gamma_q(0.5 * dof, 0.5 * statistic); }

// Wilson-Hilferty approximation of the same tail probability (good for large dof).
inline double chi2_p_value_wilson_hilferty(double statistic, int dof) {
  const double k = dof;
  const double z = (std::cbrt(statistic / k) - (1.0 - 2.0 / (9.0 * k))) / std::sqrt(2.0 / (9.0 * k));
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

// Per-test significance level keeping the family-wise false-rejection rate at `alpha`.
inline double sidak_correction(double alpha, int tests) { return 1.0 - std::pow(1.0 - alpha, 1.0 / tests); }

// ---------------------------------------------------------------------------------------------
// Pearson's test on binned counts.

struct Chi2Result {
  bool passed = false;
  double statistic = 0.0;
  int dof = 0;
  double p_value = 0.0;
  int pooled_cells = 0;
  std::string message;
};

// Cells with expected count < min_expected are pooled (smallest first, as in pbrt) until the pool
// reaches min_expected. Any observation in a cell whose expected count is exactly zero rejects.
inline Chi2Result pearson_chi2(const std::vector<double>& observed, const std::vector<double>& expected,
                               double significance, double min_expected = 5.0) {
  if (observed.size() != expected.size()) throw std::invalid_argument("pearson_chi2: size mismatch");
  Chi2Result r;
  std::vector<size_t> order(observed.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });
  double pooled_obs = 0.0, pooled_exp = 0.0;
  int cells = 0;
  for (size_t i : order) {
    if (expected[i] <= 0.0) {
      if (observed[i] > 0.0) {
        std::ostringstream s;
        s << observed[i] << " samples in cell " << i << " whose expected count is 0";
        r.message = s.str();
        r.passed = false;
        r.p_value = 0.0;
        return r;
      }
    } else if (expected[i] < min_expected || (pooled_exp > 0.0 && pooled_exp < min_expected)) {
      pooled_obs += observed[i];
      pooled_exp += expected[i];
      ++r.pooled_cells;
    } else {
      const double d = observed[i] - expected[i];
      r.statistic += d * d / expected[i];
      ++cells;
    }
  }
  if (pooled_exp > 0.0) {
    const double d = pooled_obs - pooled_exp;
    r.statistic += d * d / pooled_exp;
    ++cells;
  }
  r.dof = cells - 1;
  if (r.dof < 1) {
    r.message = "fewer than two cells after pooling";
    return r;
  }
  r.p_value = chi2_p_value(r.statistic, r.dof);
  r.passed = r.p_value >= significance;
  std::ostringstream s;
  s << "chi2 = " << r.statistic << ", dof = " << r.dof << ", p = " << r.p_value << " (significance "
    << significance << ", " << r.pooled_cells << " cells pooled)";
  r.message = s.str();
  return r;
}

// ---------------------------------------------------------------------------------------------
// Spherical (theta, phi) grid, +Z the pole.

struct SphereGrid {
  int theta_res = 21;
  int phi_res = 41;
  double theta_max = kPiD;  // kPiD: whole sphere; kPiD / 2: upper hemisphere
  // Discontinuities of the pdf (in theta and in phi): integration splits at them.
  std::vector<double> theta_breaks, phi_breaks;

  int cells() const { return theta_res * phi_res; }
  // One extra bin after the grid: samples outside the domain (below the horizon, or failed).
  int bins() const { return cells() + 1; }
  int outside_bin() const { return cells(); }

  int bin(const Vec3& d) const {
    if (!fenestra::is_finite(d)) return outside_bin();
    const double len = std::sqrt(double(d.x()) * d.x() + double(d.y()) * d.y() + double(d.z()) * d.z());
    if (!(len > 0.0)) return outside_bin();
    const double theta = std::acos(std::clamp(d.z() / len, -1.0, 1.0));
    if (theta > theta_max) return outside_bin();
    double phi = std::atan2(double(d.y()), double(d.x()));
    if (phi < 0.0) phi += 2.0 * kPiD;
    const int it = std::min(static_cast<int>(theta / theta_max * theta_res), theta_res - 1);
    const int ip = std::min(static_cast<int>(phi / (2.0 * kPiD) * phi_res), phi_res - 1);
    return it * phi_res + ip;
  }
  static Vec3 direction(double theta, double phi) {
    const double st = std::sin(theta);
    return Vec3(float(st * std::cos(phi)), float(st * std::sin(phi)), float(std::cos(theta)));
  }
};

// Sub-intervals of [a, b]: `n` equal pieces, further split at the breakpoints inside.
inline std::vector<double> split_interval(double a, double b, int n, const std::vector<double>& breaks,
                                          double period = 0.0) {
  std::vector<double> pts;
  for (int i = 0; i <= n; ++i) pts.push_back(a + (b - a) * i / n);
  const double margin = 1e-9 * (b - a);
  for (double x : breaks) {
    if (period > 0.0) x -= period * std::floor(x / period);
    if (x > a + margin && x < b - margin) pts.push_back(x);
  }
  std::sort(pts.begin(), pts.end());
  std::vector<double> out;
  for (double x : pts)
    if (out.empty() || x - out.back() > margin) out.push_back(x);
  out.back() = b;
  return out;
}

// 3 x 3-point Gauss-Legendre rule for f(theta, phi) * sin(theta) on a (theta, phi) rectangle.
template <class Pdf>
double gauss_legendre_rect(Pdf& pdf, double t0, double t1, double p0, double p1) {
  static const double x[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static const double w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const double tc = 0.5 * (t0 + t1), th = 0.5 * (t1 - t0), pc = 0.5 * (p0 + p1), ph = 0.5 * (p1 - p0);
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double theta = tc + th * x[i];
    double row = 0.0;
    for (int j = 0; j < 3; ++j) row += w[j] * double(pdf(SphereGrid::direction(theta, pc + ph * x[j])));
    sum += w[i] * std::sin(theta) * row;
  }
  return sum * th * ph;
}

// Adaptive quadrature: split the rectangle in four until the four-piece estimate agrees with
// the whole-piece estimate `whole` to max(abs_tol, rel_tol * |estimate|). abs_tol is not divided
// among the pieces: near the poles the float directions the pdfs see make their values noisy
// at a level that does not shrink with the piece, and only a fixed floor ends the recursion.
template <class Pdf>
double adaptive_rect(Pdf& pdf, double t0, double t1, double p0, double p1, double whole, double abs_tol,
                     double rel_tol, int depth) {
  const double tm = 0.5 * (t0 + t1), pm = 0.5 * (p0 + p1);
  const double q[4] = {gauss_legendre_rect(pdf, t0, tm, p0, pm), gauss_legendre_rect(pdf, t0, tm, pm, p1),
                       gauss_legendre_rect(pdf, tm, t1, p0, pm), gauss_legendre_rect(pdf, tm, t1, pm, p1)};
  const double sum = q[0] + q[1] + q[2] + q[3];
  if (depth <= 0 || std::abs(sum - whole) <= std::max(abs_tol, rel_tol * std::abs(sum))) return sum;
  return adaptive_rect(pdf, t0, tm, p0, pm, q[0], abs_tol, rel_tol, depth - 1) +
         adaptive_rect(pdf, t0, tm, pm, p1, q[1], abs_tol, rel_tol, depth - 1) +
         adaptive_rect(pdf, tm, t1, p0, pm, q[2], abs_tol, rel_tol, depth - 1) +
         adaptive_rect(pdf, tm, t1, pm, p1, q[3], abs_tol, rel_tol, depth - 1);
}

// Probability mass of `pdf` (solid-angle density of a direction) in every grid cell: each cell is
// cut into `subdiv` x `subdiv` pieces, further split at the grid's breakpoints so discontinuities
// fall on piece boundaries, and each piece is integrated adaptively (Gauss-Legendre, error
// estimated by halving). The tolerance, 1e-10 absolute per piece (a smooth cell has 16 pieces;
// a cell with a sharp peak some hundreds) or 1e-4 relative, keeps the error of an expected count
// E from N <= 1e6 samples near 0.01 + 1e-4 E, a tenth of its Poisson noise sqrt(E) or less (and
// the halving estimate is pessimistic: Gauss-Legendre converges as h^6). The relative part
// cannot be much tighter: the library's pdfs are evaluated in float.
template <class Pdf>
std::vector<double> cell_probabilities(const SphereGrid& g, Pdf&& pdf, int subdiv = 4) {
  std::vector<double> prob(g.cells(), 0.0);
  const double dt = g.theta_max / g.theta_res, dp = 2.0 * kPiD / g.phi_res;
  const double abs_tol = 1e-10, rel_tol = 1e-4;
  for (int it = 0; it < g.theta_res; ++it) {
    const std::vector<double> ts = split_interval(it * dt, (it + 1) * dt, subdiv, g.theta_breaks);
    for (int ip = 0; ip < g.phi_res; ++ip) {
      const std::vector<double> ps = split_interval(ip * dp, (ip + 1) * dp, subdiv, g.phi_breaks, 2.0 * kPiD);
      double sum = 0.0;
      for (size_t a = 0; a + 1 < ts.size(); ++a)
        for (size_t b = 0; b + 1 < ps.size(); ++b) {
          const double whole = gauss_legendre_rect(pdf, ts[a], ts[a + 1], ps[b], ps[b + 1]);
          sum += adaptive_rect(pdf, ts[a], ts[a + 1], ps[b], ps[b + 1], whole, abs_tol, rel_tol, 8);
        }
      prob[it * g.phi_res + ip] = sum;
    }
  }
  return prob;
}

// Integral of `pdf` over the whole sphere (a pdf's total mass).
template <class Pdf>
double integrate_sphere(Pdf&& pdf, std::vector<double> theta_breaks = {}, std::vector<double> phi_breaks = {},
                        int subdiv = 4) {
  SphereGrid g;
  g.theta_res = 15;
  g.phi_res = 31;
  g.theta_max = kPiD;
  g.theta_breaks = std::move(theta_breaks);
  g.theta_breaks.push_back(kPiD / 2);  // hemispherical pdfs jump at the horizon
  g.phi_breaks = std::move(phi_breaks);
  const std::vector<double> p = cell_probabilities(g, pdf, subdiv);
  return std::accumulate(p.begin(), p.end(), 0.0);
}

// Expected counts for `n` sampling attempts: the grid cells, then the outside bin with the mass
// the pdf leaves outside the grid (samples below the horizon, failed samples).
template <class Pdf>
std::vector<double> expected_counts(const SphereGrid& g, double n, Pdf&& pdf, int subdiv = 4) {
  std::vector<double> p = cell_probabilities(g, pdf, subdiv);
  const double total = std::accumulate(p.begin(), p.end(), 0.0);
  for (double& x : p) x *= n;
  p.push_back(n * std::max(0.0, 1.0 - total));
  return p;
}

// Histogram of `n` sampling attempts. `sampler(rng, &dir)` returns false for a failed sample,
// which is counted in the outside bin like directions outside the grid's domain.
template <class Sampler>
std::vector<double> histogram(const SphereGrid& g, int n, uint64_t seed, Sampler&& sampler) {
  std::vector<double> h(g.bins(), 0.0);
  fenestra::Rng rng(seed, 7);
  for (int i = 0; i < n; ++i) {
    Vec3 d;
    h[sampler(rng, &d) ? g.bin(d) : g.outside_bin()] += 1.0;
  }
  return h;
}

inline std::string format_histograms(const SphereGrid& g, const std::vector<double>& observed,
                                     const std::vector<double>& expected) {
  std::ostringstream s;
  auto table = [&](const char* title, const std::vector<double>& v) {
    s << title << " (rows: theta from 0 to " << g.theta_max << ", columns: phi from 0 to 2 pi)\n";
    for (int it = 0; it < g.theta_res; ++it) {
      for (int ip = 0; ip < g.phi_res; ++ip) s << std::setw(7) << std::llround(v[it * g.phi_res + ip]);
      s << "\n";
    }
    s << "outside / failed: " << v[g.outside_bin()] << "\n";
  };
  table("observed", observed);
  table("expected", expected);
  return s.str();
}

// Full test: histogram `n` samples, integrate `pdf`, run Pearson's test at `significance`.
template <class Sampler, class Pdf>
Chi2Result sphere_chi2(const SphereGrid& g, int n, uint64_t seed, Sampler&& sampler, Pdf&& pdf,
                       double significance, int subdiv = 4) {
  const std::vector<double> obs = histogram(g, n, seed, sampler);
  const std::vector<double> exp = expected_counts(g, n, pdf, subdiv);
  Chi2Result r = pearson_chi2(obs, exp, significance);
  if (!r.passed) r.message += "\n" + format_histograms(g, obs, exp);
  return r;
}

// The same for a sampler whose every sample lies on a region it covers whole (portals): the outside
// bin must stay empty (a failed or stray sample fails the test), and is left out of Pearson's test,
// where its expected count would be the quadrature's error along the region's curved edges alone.
template <class Sampler, class Pdf>
Chi2Result sphere_chi2_every_sample_drawn(const SphereGrid& g, int n, uint64_t seed, Sampler&& sampler, Pdf&& pdf,
                                          double significance, int subdiv = 4) {
  const std::vector<double> obs = histogram(g, n, seed, sampler);
  const std::vector<double> exp = expected_counts(g, n, pdf, subdiv);
  if (obs.back() != 0.0) {
    Chi2Result failed;
    failed.message = std::to_string(static_cast<long long>(obs.back())) + " samples failed or fell outside the grid";
    return failed;
  }
  Chi2Result r = pearson_chi2(std::vector<double>(obs.begin(), obs.end() - 1),
                              std::vector<double>(exp.begin(), exp.end() - 1), significance);
  if (!r.passed) r.message += "\n" + format_histograms(g, obs, exp);
  return r;
}

}  // namespace fenestra_test
