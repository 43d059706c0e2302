#pragma once
// Non-negative least squares, min ||A x - b|| subject to x >= 0: Lawson and Hanson's active-set
// method (Solving Least Squares Problems, 1974, ch. 23), on Eigen.
#include <Eigen/Dense>

#include "util/progress.h"

namespace fenestra {

struct NnlsResult {
  Eigen::VectorXd x;
  int iterations = 0;       // outer (active-set) iterations
  bool converged = false;   // the KKT conditions hold to the tolerance
  double residual_norm = 0.0;
};

// `max_iterations` 0: 3 x columns; each attempt to free a variable counts as one iteration.
// `tolerance` bounds the gradient w = A^T (b - A x) at the solution: w_j <= tolerance where x_j = 0
// (free variables have w_j ~ 0 up to rounding). 0 selects nnls_default_tolerance(A, b), safely
// above the rounding noise in w. On consistent but ill-conditioned systems (smooth contribution
// columns) a gradient that small still allows a residual of ~1e-7 ||b||; a smaller tolerance
// goes further, but below the noise the iteration limit ends the search (converged = false).
// Throws std::invalid_argument on mismatched sizes, non-finite input or negative settings. With
// `progress`, polls cancellation every outer iteration (throws Cancelled).
NnlsResult nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, int max_iterations = 0, double tolerance = 0.0,
                const Progress* progress = nullptr);

// 10 eps max(m, n) ||A||_1 ||b||_2: |w_j| <= ||A||_1 ||r|| <= ||A||_1 ||b|| bounds the gradient's
// scale, and rounding in a length-max(m, n) product perturbs it by a few eps times that.
double nnls_default_tolerance(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

}  // namespace fenestra
