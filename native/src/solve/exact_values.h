#pragma once
// Exact sensor values of open-element sets from the path records (Contributions::evaluate), for
// the solver's stages, which evaluate many sets, most of them near one another: every set is
// kept, and a new one is evaluated from the last one evaluated (each sensor's reference) by
// re-evaluating only the paths that met an element whose state differs from it. The reference
// follows the sets evaluated (the new paths' values replace the old), so a search that steps from
// set to set re-evaluates only the paths of each step's change, never those of every step since
// some earlier set.
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
  // Sensor evaluations done in full so far, and all of them (the others were evaluated from the
  // sensor's reference).
  size_t full_evaluations() const { return full_evaluations_; }
  size_t sensor_evaluations() const { return sensor_evaluations_; }
  // Paths evaluated so far, over all sensors (in full or from the reference).
  size_t path_evaluations() const { return path_evaluations_; }
  // Bytes of the index of paths per element and the reference's per-path values (the cost
  // model's exact_values_index).
  size_t memory_bytes() const;

 private:
  SensorValues evaluate(const std::vector<uint8_t>& open);
  // Sensor i's replicate sums for `open`, which becomes its reference (slot `slot`): in full, or
  // from its reference when the paths that met an element of `changed` (those whose state differs
  // from it) are at most kMaxShareFromReference of its paths. `evaluated`: the paths evaluated.
  ReplicateSums sensor_sums(size_t i, const std::vector<uint8_t>& open, const std::vector<int32_t>* changed, int slot,
                            bool* in_full, size_t* evaluated);
  // Sensor i's paths that met an element of `changed`, each once, in order; false (and `out`
  // partly filled) when they are more than kMaxShareFromReference of its paths.
  bool changed_paths(size_t i, const std::vector<int32_t>& changed, std::vector<uint32_t>* out) const;
  void build_index();
  int free_slot();

  const Contributions& c_;
  const Progress* progress_;
  std::map<std::vector<uint8_t>, SensorValues> known_;
  // Per sensor: the paths that met each element, by any of their events or conditions (CSR:
  // element k's at paths[begin[k]] .. paths[begin[k + 1]]).
  std::vector<std::vector<uint32_t>> element_begin_, element_paths_;
  // Each sensor's reference: the last set it was evaluated for (a slot of reference_sets_, -1
  // before any), its per-path values and their sums. Every choice is the
  // sensor's own, so a sensor's values do not depend on the others (a study's shards give the
  // same numbers as one process).
  std::vector<std::vector<uint8_t>> reference_sets_;
  std::vector<size_t> reference_users_;  // sensors per slot (an empty slot is reused)
  std::vector<int> reference_of_;
  std::vector<std::vector<double>> reference_values_;  // [sensor][path]
  std::vector<ReplicateSums> reference_sums_;
  size_t full_evaluations_ = 0, sensor_evaluations_ = 0, path_evaluations_ = 0;
};

}  // namespace fenestra
