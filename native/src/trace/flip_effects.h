#pragma once
// The exact linear model about a set of open elements: what flipping each element alone (opening it
// when closed, closing it when open) changes at each sensor, from the same path records.
#include <Eigen/Dense>
#include <cstdint>
#include <vector>

#include "trace/contributions.h"

namespace fenestra {

class Progress;

// D(i, k) = value_i(open with k flipped) - value_i(open), averaged over sensor i's paths.
Eigen::MatrixXd flip_effects(const Contributions& c, const std::vector<uint8_t>& open, const Progress* progress);

}  // namespace fenestra
