#include "solve/linear_start.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "solve/nnls.h"

namespace fenestra {

namespace {

void check_state(const ElementGrid& grid, const Eigen::VectorXd* o) {
  if (!o) throw std::invalid_argument("redistribute_excess: no opening state given");
  if (o->size() != grid.size())
    throw std::invalid_argument("redistribute_excess: the opening state has " + std::to_string(o->size()) +
                                " entries but the grid has " + std::to_string(grid.size()) + " elements");
  for (Eigen::Index j = 0; j < o->size(); ++j)
    if (!std::isfinite((*o)[j]) || (*o)[j] < 0.0)
      throw std::invalid_argument("redistribute_excess: element " + std::to_string(j) + " has state " +
                                  std::to_string((*o)[j]) + "; expected a finite value >= 0");
}

}  // namespace

double redistribute_excess(const ElementGrid& grid, Eigen::VectorXd* o) {
  check_state(grid, o);
  Eigen::VectorXd& state = *o;
  double lost = 0.0;
  // One pass suffices: a neighbour receives at most its room, so it never exceeds 1 itself, and
  // room only shrinks, so an element whose neighbourhood is full when visited stays stuck.
  for (int j = 0; j < grid.size(); ++j) {
    if (!(state[j] > 1.0)) continue;
    const double excess = state[j] - 1.0;
    double room = 0.0;
    for (const int n : grid.neighbours(j))
      if (n != ElementGrid::kNone) room += std::max(0.0, 1.0 - state[n]);
    if (excess >= room) {
      for (const int n : grid.neighbours(j))
        if (n != ElementGrid::kNone) state[n] = std::max(state[n], 1.0);
      lost += excess - room;
    } else {
      const double share = excess / room;  // < 1: every neighbour stays below 1
      for (const int n : grid.neighbours(j))
        if (n != ElementGrid::kNone && state[n] < 1.0) state[n] = std::min(1.0, state[n] + share * (1.0 - state[n]));
    }
    state[j] = 1.0;
  }
  return lost;
}

std::vector<uint8_t> round_to_binary(const Eigen::VectorXd& o, double threshold) {
  if (!std::isfinite(threshold))
    throw std::invalid_argument("round_to_binary: threshold must be finite, got " + std::to_string(threshold));
  std::vector<uint8_t> open(o.size());
  for (Eigen::Index j = 0; j < o.size(); ++j) open[j] = o[j] >= threshold ? 1 : 0;
  return open;
}

LinearStart linear_start(const LinearObjective& o, const ElementGrid& grid, const Progress* progress) {
  const Eigen::VectorXd sqrt_w = o.weight.cwiseSqrt();
  const Eigen::MatrixXd A = sqrt_w.asDiagonal() * o.E;
  const Eigen::VectorXd b = sqrt_w.cwiseProduct(o.target);
  const NnlsResult r = nnls(A, b, 0, 0.0, progress);
  Eigen::VectorXd x = r.x;
  redistribute_excess(grid, &x);
  LinearStart s;
  s.open = round_to_binary(x);
  s.continuous = std::move(x);
  s.relative_rms = r.residual_norm;  // weights make it relative
  s.iterations = r.iterations;
  s.converged = r.converged;
  return s;
}

}  // namespace fenestra
