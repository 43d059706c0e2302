#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

#include "solve/linear_start.h"
#include "solve/nnls.h"

using namespace fenestra;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

MatrixXd random_matrix(int m, int n, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  MatrixXd A(m, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i) A(i, j) = normal(rng);
  return A;
}

VectorXd random_vector(int m, std::mt19937& rng) { return random_matrix(m, 1, rng).col(0); }

// Irradiance-like contributions: sensors in a room facing a wall of rows x cols elements at y = 0,
// each column the (positive, smooth) view factor of one element. Neighbouring elements give
// nearly collinear columns, as in the solver's contribution matrices.
MatrixXd wall_contributions(int sensors, int rows, int cols, std::mt19937& rng) {
  std::uniform_real_distribution<double> x(0.0, 4.0), y(0.5, 4.0), z(0.5, 1.5);
  MatrixXd E(sensors, rows * cols);
  const double size = 3.0 / rows;
  for (int i = 0; i < sensors; ++i) {
    const double sx = x(rng), sy = y(rng), sz = z(rng);
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        const double dx = (c + 0.5) * 4.0 / cols - sx, dz = (r + 0.5) * size - sz;
        const double d2 = dx * dx + sy * sy + dz * dz;
        E(i, r * cols + c) = sy * size * size / (d2 * std::sqrt(d2));
      }
  }
  return E;
}

// Checks the optimality conditions of min ||A x - b|| s.t. x >= 0: x >= 0, and the gradient
// w = A^T (b - A x) is <= tol where x = 0 and ~0 where x > 0.
void expect_kkt(const MatrixXd& A, const VectorXd& b, const NnlsResult& result, double tol) {
  ASSERT_EQ(result.x.size(), A.cols());
  const VectorXd w = A.transpose() * (b - A * result.x);
  for (Eigen::Index j = 0; j < A.cols(); ++j) {
    ASSERT_GE(result.x[j], 0.0) << "x(" << j << ")";
    if (result.x[j] == 0.0)
      EXPECT_LE(w[j], tol) << "bound variable " << j << " could still lower the residual";
    else
      EXPECT_LE(std::abs(w[j]), tol) << "free variable " << j << " is not at its least-squares value";
  }
  EXPECT_NEAR(result.residual_norm, (b - A * result.x).norm(), 1e-12 * (1.0 + b.norm()));
}

// Tolerance of the optimality checks: a little above the solver's own stopping tolerance.
double kkt_tolerance(const MatrixXd& A, const VectorXd& b) { return 100.0 * nnls_default_tolerance(A, b) + 1e-300; }

// The smallest residual over all supports whose (full-rank) least-squares solution is
// non-negative: an optimal solution with linearly independent support always exists.
double brute_force_residual(const MatrixXd& A, const VectorXd& b) {
  const int n = static_cast<int>(A.cols());
  double best = b.norm();
  for (unsigned mask = 1; mask < (1u << n); ++mask) {
    std::vector<int> support;
    for (int j = 0; j < n; ++j)
      if (mask & (1u << j)) support.push_back(j);
    MatrixXd As(A.rows(), support.size());
    for (size_t k = 0; k < support.size(); ++k) As.col(k) = A.col(support[k]);
    Eigen::ColPivHouseholderQR<MatrixXd> qr(As);
    if (qr.rank() < static_cast<Eigen::Index>(support.size())) continue;
    const VectorXd z = qr.solve(b);
    if (z.minCoeff() < 0.0) continue;
    best = std::min(best, (b - As * z).norm());
  }
  return best;
}

}  // namespace

TEST(Nnls, RecoversNonnegativeSolutionWithZeros) {
  std::mt19937 rng(1);
  const MatrixXd A = random_matrix(40, 25, rng);
  VectorXd x_true = random_vector(25, rng).cwiseAbs();
  for (int j = 0; j < 25; j += 3) x_true[j] = 0.0;
  const VectorXd b = A * x_true;
  const NnlsResult result = nnls(A, b);
  EXPECT_TRUE(result.converged);
  EXPECT_LE((result.x - x_true).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LE(result.residual_norm, 1e-10 * b.norm());
  expect_kkt(A, b, result, kkt_tolerance(A, b));
}

TEST(Nnls, BindsVariablesWhoseUnconstrainedValueIsNegative) {
  // Unconstrained: x = (2, -1). With x >= 0 the optimum is x = (1, 0), residual (0, -1).
  MatrixXd A(2, 2);
  A << 1, 1, 0, 1;
  const VectorXd b = (VectorXd(2) << 1, -1).finished();
  const NnlsResult result = nnls(A, b);
  EXPECT_TRUE(result.converged);
  EXPECT_NEAR(result.x[0], 1.0, 1e-15);
  EXPECT_EQ(result.x[1], 0.0);
  EXPECT_NEAR(result.residual_norm, 1.0, 1e-15);
}

TEST(Nnls, StepsBackToFeasibilityInsideTheInnerLoop) {
  // x0 and x1 are freed in turn; once x2 joins, the least-squares solution on all three is
  // (4, -6, 14) and the inner loop binds x1 again. The optimum is x = (1, 0, 1), residual (1, -2, -1).
  MatrixXd A(3, 3);
  A << 0, 2, 1, -1, 2, 1, 2, -1, -1;
  const VectorXd b = (VectorXd(3) << 2, -2, 0).finished();
  const NnlsResult result = nnls(A, b);
  EXPECT_TRUE(result.converged);
  EXPECT_NEAR(result.x[0], 1.0, 1e-14);
  EXPECT_EQ(result.x[1], 0.0);
  EXPECT_NEAR(result.x[2], 1.0, 1e-14);
  EXPECT_NEAR(result.residual_norm, std::sqrt(6.0), 1e-14);
  expect_kkt(A, b, result, kkt_tolerance(A, b));
}

TEST(Nnls, SatisfiesKktOnRandomProblems) {
  std::mt19937 rng(7);
  const int shapes[][2] = {{30, 10}, {50, 50}, {20, 60}, {5, 100}, {100, 200}};
  for (const auto& shape : shapes)
    for (int trial = 0; trial < 5; ++trial) {
      const MatrixXd A = random_matrix(shape[0], shape[1], rng);
      const VectorXd b = random_vector(shape[0], rng);
      const NnlsResult result = nnls(A, b);
      SCOPED_TRACE(std::to_string(shape[0]) + " x " + std::to_string(shape[1]) + ", trial " + std::to_string(trial));
      EXPECT_TRUE(result.converged);
      expect_kkt(A, b, result, kkt_tolerance(A, b));
    }
}

TEST(Nnls, MatchesBruteForceOnSmallProblems) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 40; ++trial) {
    const int m = 3 + trial % 7, n = 2 + trial % 8;
    const MatrixXd A = random_matrix(m, n, rng);
    const VectorXd b = random_vector(m, rng);
    const NnlsResult result = nnls(A, b);
    EXPECT_TRUE(result.converged);
    EXPECT_NEAR(result.residual_norm, brute_force_residual(A, b), 1e-12 * (1.0 + b.norm())) << m << " x " << n;
  }
}

TEST(Nnls, HandlesNearlyCollinearColumns) {
  std::mt19937 rng(3);
  // Columns differing by 1e-7 relative: the least-squares subproblems have condition ~1e7.
  const MatrixXd base = random_matrix(30, 4, rng);
  MatrixXd A(30, 8);
  for (int j = 0; j < 8; ++j) A.col(j) = base.col(j / 2) + (j % 2) * 1e-7 * random_vector(30, rng);
  for (int trial = 0; trial < 10; ++trial) {
    const VectorXd b = random_vector(30, rng);
    const NnlsResult result = nnls(A, b);
    EXPECT_TRUE(result.converged);
    expect_kkt(A, b, result, kkt_tolerance(A, b));
    EXPECT_NEAR(result.residual_norm, brute_force_residual(A, b), 1e-9 * b.norm());
  }
  // Contribution-like matrix: smooth positive columns, neighbours almost parallel.
  const MatrixXd E = wall_contributions(60, 12, 16, rng);
  const VectorXd goal = VectorXd::Constant(60, E.rowwise().sum().mean() * 0.3);
  const NnlsResult result = nnls(E, goal);
  EXPECT_TRUE(result.converged);
  expect_kkt(E, goal, result, kkt_tolerance(E, goal));
}

TEST(Nnls, ExactlyDuplicatedColumnsShareOneFreeVariable) {
  std::mt19937 rng(5);
  MatrixXd A = random_matrix(10, 4, rng);
  A.col(3) = A.col(1);
  const VectorXd b = A.col(1) * 2.0 + A.col(0);
  const NnlsResult result = nnls(A, b);
  EXPECT_TRUE(result.converged);
  EXPECT_NEAR(result.x[1] + result.x[3], 2.0, 1e-12);
  EXPECT_NEAR(result.x[0], 1.0, 1e-12);
  EXPECT_LE(result.residual_norm, 1e-12 * b.norm());
}

TEST(Nnls, MoreColumnsThanRows) {
  std::mt19937 rng(9);
  const MatrixXd A = random_matrix(20, 80, rng);
  const VectorXd x_true = random_vector(80, rng).cwiseMax(0.0);
  const VectorXd b = A * x_true;
  const NnlsResult result = nnls(A, b);
  EXPECT_TRUE(result.converged);
  EXPECT_LE(result.residual_norm, 1e-10 * b.norm());  // consistent: any non-negative solution fits exactly
  EXPECT_LE((result.x.array() > 0.0).count(), 20);    // an extreme point: at most m free variables
  expect_kkt(A, b, result, kkt_tolerance(A, b));
}

TEST(Nnls, ZeroRightHandSideGivesZero) {
  std::mt19937 rng(2);
  const MatrixXd A = random_matrix(10, 15, rng);
  const NnlsResult result = nnls(A, VectorXd::Zero(10));
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_TRUE(result.x.isZero(0.0));
  EXPECT_EQ(result.residual_norm, 0.0);
}

TEST(Nnls, EmptyProblems) {
  const NnlsResult no_columns = nnls(MatrixXd(3, 0), VectorXd::Ones(3));
  EXPECT_TRUE(no_columns.converged);
  EXPECT_EQ(no_columns.x.size(), 0);
  EXPECT_DOUBLE_EQ(no_columns.residual_norm, std::sqrt(3.0));
  const NnlsResult no_rows = nnls(MatrixXd(0, 4), VectorXd(0));
  EXPECT_TRUE(no_rows.converged);
  EXPECT_TRUE(no_rows.x.isZero(0.0));
}

TEST(Nnls, IterationCapIsReported) {
  std::mt19937 rng(4);
  const MatrixXd A = random_matrix(30, 20, rng).cwiseAbs();
  const VectorXd b = A * VectorXd::Ones(20);
  const NnlsResult capped = nnls(A, b, 3);
  EXPECT_FALSE(capped.converged);
  EXPECT_EQ(capped.iterations, 3);
  EXPECT_GE(capped.x.minCoeff(), 0.0);
  EXPECT_TRUE(nnls(A, b).converged);
}

TEST(Nnls, RejectsInvalidInput) {
  const MatrixXd A = MatrixXd::Ones(3, 2);
  EXPECT_THROW(nnls(A, VectorXd::Ones(4)), std::invalid_argument);
  MatrixXd bad = A;
  bad(1, 1) = kNaN;
  EXPECT_THROW(nnls(bad, VectorXd::Ones(3)), std::invalid_argument);
  VectorXd b = VectorXd::Ones(3);
  b[2] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(nnls(A, b), std::invalid_argument);
  EXPECT_THROW(nnls(A, VectorXd::Ones(3), -1), std::invalid_argument);
  EXPECT_THROW(nnls(A, VectorXd::Ones(3), 0, -1.0), std::invalid_argument);
  try {
    nnls(A, VectorXd::Ones(4));
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("3 rows"), std::string::npos) << e.what();
  }
}

TEST(Nnls, LargeContributionProblemCompletes) {
  std::mt19937 rng(12);
  const MatrixXd E = wall_contributions(1000, 40, 50, rng);  // 1,000 sensors x 2,000 elements
  const VectorXd goal = VectorXd::Constant(1000, E.rowwise().sum().mean() * 0.25);
  const auto start = std::chrono::steady_clock::now();
  const NnlsResult result = nnls(E, goal);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(result.converged);
  expect_kkt(E, goal, result, kkt_tolerance(E, goal));
  RecordProperty("seconds", std::to_string(seconds));
}

TEST(Nnls, LargeRandomProblemCompletes) {
  std::mt19937 rng(13);
  // Gaussian entries: about m variables end up free, the most iterations a problem this size needs.
  const MatrixXd A = random_matrix(1000, 2000, rng);
  const VectorXd b = random_vector(1000, rng);
  const auto start = std::chrono::steady_clock::now();
  const NnlsResult result = nnls(A, b);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(result.converged);
  expect_kkt(A, b, result, kkt_tolerance(A, b));
  RecordProperty("seconds", std::to_string(seconds));
}

// ---- Redistribution and rounding ----

TEST(LinearStart, MovesExcessToNeighboursInProportionToTheirRoom) {
  const ElementGrid grid = ElementGrid::rectangle(3, 3);
  VectorXd o = VectorXd::Constant(9, 0.5);
  o[4] = 1.4;  // centre: 0.4 to spread over 8 neighbours with 0.5 room each
  o[0] = 0.9;  // room 0.1
  const double lost = redistribute_excess(grid, &o);
  EXPECT_EQ(lost, 0.0);
  EXPECT_EQ(o[4], 1.0);
  const double room = 7 * 0.5 + 0.1;
  EXPECT_NEAR(o[0], 0.9 + 0.4 * 0.1 / room, 1e-15);
  EXPECT_NEAR(o[8], 0.5 + 0.4 * 0.5 / room, 1e-15);
}

TEST(LinearStart, ConservesTotalAndStaysInUnitInterval) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> low(0.0, 0.6);
  const ElementGrid grid = ElementGrid::rectangle(9, 11);
  for (int trial = 0; trial < 20; ++trial) {
    VectorXd o(grid.size());
    for (int j = 0; j < grid.size(); ++j) o[j] = low(rng);
    for (int j = trial % 3; j < grid.size(); j += 5) o[j] = 1.0 + low(rng);  // room everywhere around
    const double before = o.sum();
    const double lost = redistribute_excess(grid, &o);
    EXPECT_EQ(lost, 0.0);
    EXPECT_NEAR(o.sum(), before, 1e-12);
    EXPECT_GE(o.minCoeff(), 0.0);
    EXPECT_LE(o.maxCoeff(), 1.0);
  }
}

TEST(LinearStart, ReturnsExcessThatHasNowhereToGo) {
  const ElementGrid grid = ElementGrid::rectangle(2, 2);
  VectorXd o = (VectorXd(4) << 1.5, 0.9, 0.95, 1.0).finished();  // room 0.15, excess 0.5
  const double before = o.sum();
  const double lost = redistribute_excess(grid, &o);
  EXPECT_NEAR(lost, 0.35, 1e-15);
  EXPECT_TRUE(o.isOnes(0.0));
  EXPECT_NEAR(o.sum() + lost, before, 1e-15);

  // Heavily over-full states: every element ends in [0, 1] and the books balance.
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> state(0.0, 3.0);
  const ElementGrid wide = ElementGrid::rectangle(7, 8);
  VectorXd p(wide.size());
  for (int j = 0; j < wide.size(); ++j) p[j] = state(rng);
  const double total = p.sum();
  const double lost_wide = redistribute_excess(wide, &p);
  EXPECT_GT(lost_wide, 0.0);
  EXPECT_NEAR(p.sum() + lost_wide, total, 1e-12);
  EXPECT_GE(p.minCoeff(), 0.0);
  EXPECT_LE(p.maxCoeff(), 1.0);
}

TEST(LinearStart, KeepsExcessInsideItsPanel) {
  // Two 1 x 2 panels at the same rows and columns: the full element's only neighbour is full.
  const ElementGrid grid({{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {1, 0, 1}});
  VectorXd o = (VectorXd(4) << 1.3, 1.0, 0.0, 0.0).finished();
  const double lost = redistribute_excess(grid, &o);
  EXPECT_NEAR(lost, 0.3, 1e-15);
  EXPECT_EQ(o[2], 0.0);
  EXPECT_EQ(o[3], 0.0);
}

TEST(LinearStart, IsDeterministic) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> state(0.0, 1.8);
  const ElementGrid grid = ElementGrid::rectangle(10, 10);
  VectorXd o(grid.size());
  for (int j = 0; j < grid.size(); ++j) o[j] = state(rng);
  VectorXd a = o, b = o;
  EXPECT_EQ(redistribute_excess(grid, &a), redistribute_excess(grid, &b));
  EXPECT_TRUE(a == b);
}

TEST(LinearStart, RejectsInvalidState) {
  const ElementGrid grid = ElementGrid::rectangle(2, 2);
  VectorXd wrong_size = VectorXd::Zero(3);
  EXPECT_THROW(redistribute_excess(grid, &wrong_size), std::invalid_argument);
  EXPECT_THROW(redistribute_excess(grid, nullptr), std::invalid_argument);
  VectorXd negative = VectorXd::Zero(4);
  negative[1] = -0.1;
  EXPECT_THROW(redistribute_excess(grid, &negative), std::invalid_argument);
  VectorXd nan = VectorXd::Zero(4);
  nan[2] = kNaN;
  EXPECT_THROW(redistribute_excess(grid, &nan), std::invalid_argument);
}

TEST(LinearStart, RoundsAtTheThreshold) {
  const VectorXd o = (VectorXd(5) << 0.0, 0.49, 0.5, 0.51, 1.0).finished();
  EXPECT_EQ(round_to_binary(o), (std::vector<uint8_t>{0, 0, 1, 1, 1}));
  EXPECT_EQ(round_to_binary(o, 0.75), (std::vector<uint8_t>{0, 0, 0, 0, 1}));
  EXPECT_TRUE(round_to_binary(VectorXd(0)).empty());
  EXPECT_THROW(round_to_binary(o, kNaN), std::invalid_argument);
}
