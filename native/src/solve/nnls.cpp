#include "solve/nnls.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Jacobi>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace fenestra {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Thin QR factorization A_P = Q R of the free ("passive") columns, kept current as columns join
// (Gram-Schmidt against Q, done twice so Q stays orthonormal to working precision even for nearly
// collinear columns) and leave (Givens rotations restore R's triangle). Each change costs
// O(m |P|) instead of the O(m |P|^2) of a fresh factorization. Q^T b rides along.
class PassiveQr {
 public:
  PassiveQr(const MatrixXd& A, const VectorXd& b) : A_(A), b_(b) {}

  int size() const { return static_cast<int>(columns_.size()); }
  // Columns of A in the factorization's order; solve() returns coefficients in this order.
  const std::vector<int>& columns() const { return columns_; }

  // Adds column j of A; returns false, changing nothing, when the column lies numerically in the
  // span of the free columns (a variable there could only cycle).
  bool append(int j) {
    const Index m = A_.rows();
    const int p = size();
    if (p == m) return false;
    reserve(p + 1);
    const auto a = A_.col(j);
    const auto Qp = Q_.leftCols(p);
    VectorXd h = Qp.transpose() * a;
    VectorXd q = a - Qp * h;
    const VectorXd h2 = Qp.transpose() * q;
    q -= Qp * h2;
    h += h2;
    const double norm = q.norm();
    if (!(norm > kDependence * a.norm())) return false;
    Q_.col(p) = q / norm;
    R_.col(p).head(p) = h;
    R_(p, p) = norm;
    qtb_(p) = Q_.col(p).dot(b_);
    columns_.push_back(j);
    return true;
  }

  void remove_last() { remove_at(size() - 1); }

  // Removes the column at position k of columns(): R loses column k, which leaves rows k.. upper
  // Hessenberg; rotations of neighbouring rows (and of Q's columns, and of Q^T b) clear the
  // subdiagonal.
  void remove_at(int k) {
    const int p = size();
    for (int c = k; c + 1 < p; ++c) R_.col(c).head(p) = R_.col(c + 1).head(p);
    for (int i = k; i + 1 < p; ++i) {
      Eigen::JacobiRotation<double> G;
      G.makeGivens(R_(i, i), R_(i + 1, i));
      R_.middleCols(i, p - 1 - i).applyOnTheLeft(i, i + 1, G.adjoint());
      R_(i + 1, i) = 0.0;
      qtb_.applyOnTheLeft(i, i + 1, G.adjoint());
      Q_.applyOnTheRight(i, i + 1, G);
    }
    // Keep everything outside the live p-1 triangle zero for the next append.
    R_.col(p - 1).head(p).setZero();
    R_.row(p - 1).head(p).setZero();
    columns_.erase(columns_.begin() + k);
  }

  // The least-squares coefficients min ||A_P z - b||, in columns() order.
  VectorXd solve() const {
    const int p = size();
    return R_.topLeftCorner(p, p).triangularView<Eigen::Upper>().solve(qtb_.head(p));
  }

 private:
  // A column joins only if at least this fraction of its norm is new to the span.
  static constexpr double kDependence = 1e3 * kEps;

  // Storage grows geometrically: the free set is usually far smaller than min(m, n), and a full
  // m x min(m, n) Q would be large for big problems.
  void reserve(int p) {
    if (p <= Q_.cols()) return;
    const Index capacity = std::min<Index>(A_.rows(), std::max<Index>(2 * Q_.cols(), std::max(p, 32)));
    const Index old = Q_.cols();
    Q_.conservativeResize(A_.rows(), capacity);
    R_.conservativeResize(capacity, capacity);
    qtb_.conservativeResize(capacity);
    R_.rightCols(capacity - old).setZero();
    R_.bottomRows(capacity - old).setZero();
  }

  const MatrixXd& A_;
  const VectorXd& b_;
  MatrixXd Q_, R_;
  VectorXd qtb_;
  std::vector<int> columns_;
};

// w = A^T r, the negative gradient of ||A x - b||^2 / 2. It is the O(mn) cost of every iteration,
// so large problems spread it over threads. Blocks are fixed so that the result does not depend
// on the thread count.
void gradient(const MatrixXd& A, const VectorXd& r, VectorXd* w) {
  constexpr Index kBlockColumns = 256;
  const Index n = A.cols();
  const Index blocks = (n + kBlockColumns - 1) / kBlockColumns;
  const auto block = [&](Index k) {
    const Index first = k * kBlockColumns, count = std::min(kBlockColumns, n - first);
    w->segment(first, count).noalias() = A.middleCols(first, count).transpose() * r;
  };
  if (A.size() < (Index(1) << 18)) {
    for (Index k = 0; k < blocks; ++k) block(k);
  } else {
    tbb::parallel_for(tbb::blocked_range<Index>(0, blocks), [&](const tbb::blocked_range<Index>& range) {
      for (Index k = range.begin(); k != range.end(); ++k) block(k);
    });
  }
}

// r = b - A x over the nonzero entries of x only.
VectorXd residual(const MatrixXd& A, const VectorXd& b, const VectorXd& x) {
  VectorXd r = b;
  for (Index j = 0; j < x.size(); ++j)
    if (x[j] != 0.0) r.noalias() -= x[j] * A.col(j);
  return r;
}

void check_input(const MatrixXd& A, const VectorXd& b, int max_iterations, double tolerance) {
  if (A.rows() != b.size())
    throw std::invalid_argument("nnls: A has " + std::to_string(A.rows()) + " rows but b has " +
                                std::to_string(b.size()) + " entries");
  if (!A.allFinite()) {
    for (Index j = 0; j < A.cols(); ++j)
      for (Index i = 0; i < A.rows(); ++i)
        if (!std::isfinite(A(i, j)))
          throw std::invalid_argument("nnls: A(" + std::to_string(i) + ", " + std::to_string(j) +
                                      ") is not finite");
  }
  for (Index i = 0; i < b.size(); ++i)
    if (!std::isfinite(b[i])) throw std::invalid_argument("nnls: b(" + std::to_string(i) + ") is not finite");
  if (max_iterations < 0)
    throw std::invalid_argument("nnls: max_iterations must be >= 0 (0: default), got " +
                                std::to_string(max_iterations));
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
    throw std::invalid_argument("nnls: tolerance must be finite and >= 0 (0: default), got " +
                                std::to_string(tolerance));
}

}  // namespace

double nnls_default_tolerance(const MatrixXd& A, const VectorXd& b) {
  const double a_norm1 = A.size() == 0 ? 0.0 : A.cwiseAbs().colwise().sum().maxCoeff();
  return 10.0 * kEps * static_cast<double>(std::max(A.rows(), A.cols())) * a_norm1 * b.norm();
}

NnlsResult nnls(const MatrixXd& A, const VectorXd& b, int max_iterations, double tolerance,
                const Progress* progress) {
  check_input(A, b, max_iterations, tolerance);
  const Index n = A.cols();
  if (max_iterations == 0) max_iterations = static_cast<int>(std::min<Index>(3 * n, std::numeric_limits<int>::max()));
  const double tol = tolerance > 0.0 ? tolerance : nnls_default_tolerance(A, b);

  NnlsResult result;
  VectorXd x = VectorXd::Zero(n);
  VectorXd r = b, w(n);
  std::vector<char> is_free(n, 0);
  // Variables that failed to join since x last changed; the gradient is the same, so retrying
  // them would repeat the failure.
  std::vector<char> refused(n, 0);
  PassiveQr qr(A, b);

  VectorXd z;  // least-squares solution on the free set, in qr.columns() order
  for (;;) {
    if (progress) progress->throw_if_cancelled();  // an iteration is O(rows x columns)
    gradient(A, r, &w);
    // Free the bound variable with the largest gradient component.
    bool joined = false;
    for (;;) {
      Index t = -1;
      double best = tol;
      for (Index j = 0; j < n; ++j)
        if (!is_free[j] && !refused[j] && w[j] > best) best = w[j], t = j;
      if (t < 0) {
        result.converged = true;
        break;
      }
      if (result.iterations == max_iterations) break;
      ++result.iterations;
      // Refused candidates can follow one another by thousands, each O(rows x free columns).
      if (progress) progress->throw_if_cancelled();
      if (!qr.append(static_cast<int>(t))) {
        refused[t] = 1;
        continue;
      }
      // In exact arithmetic z_t > 0 when w_t > 0; a rounding-sized gradient can give z_t <= 0,
      // and letting t in then would only send it straight back (cycling).
      z = qr.solve();
      if (!(z[qr.size() - 1] > 0.0)) {
        qr.remove_last();
        refused[t] = 1;
        continue;
      }
      is_free[t] = 1;
      joined = true;
      break;
    }
    if (!joined) break;
    std::fill(refused.begin(), refused.end(), 0);

    // Inner loop: while the unconstrained solution on the free set has a non-positive entry, move
    // from x toward it as far as feasibility allows and bind the variables that reach zero.
    while (qr.size() > 0 && z.minCoeff() <= 0.0) {
      const std::vector<int>& free_columns = qr.columns();
      double alpha = 1.0;
      int blocking = -1;
      for (int k = 0; k < qr.size(); ++k) {
        if (z[k] > 0.0) continue;
        const double xj = x[free_columns[k]];
        const double step = xj > 0.0 ? xj / (xj - z[k]) : 0.0;
        if (blocking < 0 || step < alpha) alpha = step, blocking = k;
      }
      for (int k = 0; k < qr.size(); ++k) x[free_columns[k]] += alpha * (z[k] - x[free_columns[k]]);
      x[free_columns[blocking]] = 0.0;
      for (int k = qr.size() - 1; k >= 0; --k) {
        const int j = free_columns[k];
        if (x[j] > 0.0) continue;
        x[j] = 0.0;
        is_free[j] = 0;
        qr.remove_at(k);
      }
      z = qr.solve();
    }
    for (int k = 0; k < qr.size(); ++k) x[qr.columns()[k]] = z[k];
    r = residual(A, b, x);
  }

  result.residual_norm = r.norm();
  result.x = std::move(x);
  return result;
}

}  // namespace fenestra
