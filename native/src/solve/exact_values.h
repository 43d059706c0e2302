#pragma once
// Exact sensor values of open-element sets from the path records (Contributions::evaluate), for
// the solver's stages, which evaluate many sets, most of them near one another: every set is
// kept, and a new one is evaluated from the last one evaluated in full (the reference) by
// re-evaluating only the paths that met an element whose state differs from it.
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "trace/contributions.h"
#include "trace/replicates.h"

namespace fenestra {

class Progress;

class ExactValues {
 public:
  ExactValues(const Contributions& c, const Progress* progress) : c_(c), progress_(progress) {}

  const SensorValues& operator()(const std::vector<uint8_t>& open);
  // Sets evaluated in full so far (the others were evaluated from the reference).
  size_t full_evaluations() const { return full_evaluations_; }
  // Bytes of the index of paths per element and the reference's per-path values (the cost
  // model's exact_values_index).
  size_t memory_bytes() const;

 private:
  SensorValues evaluate(const std::vector<uint8_t>& open);
  SensorValues evaluate_in_full(const std::vector<uint8_t>& open);
  SensorValues evaluate_from_reference(const std::vector<uint8_t>& open, const std::vector<int32_t>& changed);
  void build_index();

  const Contributions& c_;
  const Progress* progress_;
  std::map<std::vector<uint8_t>, SensorValues> known_;
  // Per sensor: the paths that met each element, by any of their events or conditions (CSR:
  // element k's at paths[begin[k]] .. paths[begin[k + 1]]).
  std::vector<std::vector<uint32_t>> element_begin_, element_paths_;
  std::vector<uint8_t> reference_;
  std::vector<std::vector<double>> reference_values_;  // [sensor][path]
  std::vector<ReplicateSums> reference_sums_;
  size_t full_evaluations_ = 0;
};

}  // namespace fenestra
