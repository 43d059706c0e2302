#pragma once
// The paper's error compensation (its Eq. 3): E(i, j) was measured with every other element
// closed, so it holds light that reached sensor i after reflecting off elements k that the
// configuration opens. That part is estimated from A (light reaching i after reflecting off k)
// and T (transport between elements):
//   e(i, j) = sum_{k != j, k open} A(i, k) T(j, k) / sum_m T(m, k),
//   predicted_i = closed_i + sum_{j open} (E(i, j) - e(i, j)).
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "trace/contributions.h"

namespace fenestra {

Eigen::VectorXd linear_prediction(const Contributions& c, const std::vector<uint8_t>& open);
Eigen::VectorXd compensated_prediction(const Contributions& c, const std::vector<uint8_t>& open);

}  // namespace fenestra
