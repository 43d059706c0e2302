#include "solve/compensation.h"

namespace fenestra {

Eigen::VectorXd linear_prediction(const Contributions& c, const std::vector<uint8_t>& open) {
  Eigen::VectorXd p = c.closed.value;
  for (size_t j = 0; j < open.size(); ++j)
    if (open[j]) p += c.E.col(static_cast<Eigen::Index>(j));
  return p;
}

Eigen::VectorXd compensated_prediction(const Contributions& c, const std::vector<uint8_t>& open) {
  Eigen::VectorXd p = linear_prediction(c, open);
  const Eigen::Index no = c.T.cols();
  const Eigen::VectorXd column_sums = c.T.colwise().sum().transpose();
  for (Eigen::Index k = 0; k < no; ++k) {
    if (!open[k] || !(column_sums[k] > 0.0)) continue;
    // Share of the light reflected off k that entered through the other open elements.
    double share = 0.0;
    for (Eigen::Index j = 0; j < no; ++j)
      if (j != k && open[j]) share += c.T(j, k);
    p -= c.A.col(k) * (share / column_sums[k]);
  }
  return p;
}

}  // namespace fenestra
