#include "trace/flip_effects.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "util/progress.h"

namespace fenestra {

Eigen::MatrixXd flip_effects(const Contributions& c, const std::vector<uint8_t>& open, const Progress* progress) {
  if (open.size() != c.element_count())
    throw std::invalid_argument("open-element mask has " + std::to_string(open.size()) + " entries, expected " +
                                std::to_string(c.element_count()));
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(c.records.size(), c.element_count());
  tbb::parallel_for(size_t(0), c.records.size(), [&](size_t i) {
    const SensorRecord& r = c.records[i];
    std::vector<uint8_t> state = open;
    std::vector<int32_t> touched;
    for (size_t p = 0; p < r.path_count(); ++p) {
      if (progress && p % 4096 == 0 && progress->cancelled()) return;
      path_elements(r, p, &touched);
      if (touched.empty()) continue;
      const double base = path_value(r, p, state);
      for (int32_t k : touched) {
        state[k] ^= 1;
        D(i, k) += path_value(r, p, state) - base;
        state[k] ^= 1;
      }
    }
    if (r.path_count() > 0) D.row(i) /= static_cast<double>(r.path_count());
  });
  if (progress) progress->throw_if_cancelled();
  return D;
}

}  // namespace fenestra
