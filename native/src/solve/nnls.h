#pragma once
// Non-negative least squares, min ||A x - b|| subject to x >= 0: Lawson and Hanson's active-set
// method (Solving Least Squares Problems, 1974, ch. 23), on Eigen.
#include <Eigen/Dense>

namespace fenestra {

struct NnlsResult {
  Eigen::VectorXd x;
  int iterations = 0;       // outer (active-set) iterations
  bool converged = false;   // the KKT conditions hold to the tolerance
  double residual_norm = 0.0;
};

// `max_iterations` 0: 3 x columns. `tolerance` 0: a default scaled to ||A|| and ||b||.
// Throws std::invalid_argument on mismatched sizes or non-finite input.
NnlsResult nnls(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, int max_iterations = 0, double tolerance = 0.0);

}  // namespace fenestra
