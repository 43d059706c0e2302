#pragma once
// A coarser discretisation of the opening domain for the coarse-to-fine start (the paper's
// Fig. 3): blocks of factor x factor elements of a panel act as one element, whose contribution
// in the linear model is the sum of its members' columns.
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "solve/element_grid.h"

namespace fenestra {

struct CoarseGrid {
  ElementGrid grid;              // the coarse elements
  std::vector<int> coarse_of;    // fine element -> coarse element
  Eigen::MatrixXd columns(const Eigen::MatrixXd& fine) const;  // sums of member columns
  std::vector<uint8_t> expand(const std::vector<uint8_t>& coarse_open) const;  // to the fine grid
};

CoarseGrid coarsen(const ElementGrid& fine, int factor);

}  // namespace fenestra
