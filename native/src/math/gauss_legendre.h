#pragma once
// Gauss-Legendre quadrature on [0, 1]: n nodes integrate polynomials of degree 2n - 1 exactly.
#include <cmath>
#include <vector>

namespace fenestra {

struct QuadratureRule {
  std::vector<double> nodes, weights;  // weights sum to 1
};

// Nodes in increasing order (Newton on the Legendre polynomial from Tricomi's initial guesses).
inline QuadratureRule gauss_legendre(int n) {
  QuadratureRule rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(3.14159265358979323846 * (i + 0.75) / (n + 0.5)), dp = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-15) break;
    }
    rule.nodes[i] = 0.5 * (1.0 - x);
    rule.weights[i] = 1.0 / ((1.0 - x * x) * dp * dp);  // 2 / ((1 - x^2) P'^2), halved for [0, 1]
  }
  return rule;
}

}  // namespace fenestra
