#pragma once
// Stage 1 of the solver (the paper's section 4.1): a continuous opening state from NNLS, its
// excess over 1 moved to neighbouring elements, then rounded to a 0/1 state.
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "solve/element_grid.h"

namespace fenestra {

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

}  // namespace fenestra
