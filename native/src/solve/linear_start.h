#pragma once
// Stage 1 of the solver (the paper's section 4.1): a continuous opening state from NNLS, its
// excess over 1 moved to neighbouring elements, then rounded to a 0/1 state.
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "solve/element_grid.h"
#include "solve/genetic.h"

namespace fenestra {

class Progress;

// Moves the excess of every o_j > 1 to j's N-8 neighbours in its panel (in proportion to the
// room they have below 1), repeating while any element exceeds 1 and its neighbourhood has
// room; the total sum of o is conserved except for excess that has nowhere to go (returned).
// Such excess is removed: the element is clamped to 1, so o ends in [0, 1] and
// sum(o after) + returned == sum(o before), up to rounding. Elements are visited in index order
// (deterministic). Throws std::invalid_argument if o is null, its size is not grid.size(), or an
// entry is negative or not finite.
double redistribute_excess(const ElementGrid& grid, Eigen::VectorXd* o);
// 1 where o_j >= threshold.
std::vector<uint8_t> round_to_binary(const Eigen::VectorXd& o, double threshold = 0.5);

struct LinearStart {
  std::vector<uint8_t> open;
  Eigen::VectorXd continuous;  // before rounding: NNLS's answer with its excess moved, in [0, 1]
  double relative_rms = 0.0;  // of the continuous solution
  int iterations = 0;
  bool converged = false;     // NNLS met its optimality conditions (else its iteration limit ended it)
};
// The stage on the weighted system of `objective`: NNLS, the excess over 1 to the neighbours,
// rounded. `progress` is polled for cancellation.
LinearStart linear_start(const LinearObjective& objective, const ElementGrid& grid, const Progress* progress);

}  // namespace fenestra
