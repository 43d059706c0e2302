#pragma once
// Exact sensor values of open-element sets from the path records (Contributions::evaluate), for
// the solver's stages, which evaluate many sets, most of them near one another: every set is
// kept, and a new one is evaluated from a set evaluated before (a reference) by re-evaluating only
// the paths that met an element whose state differs from it. Each sensor keeps two references: the
// last set it was evaluated for, and the one that evaluation started from. A search that scores
// the neighbours of its best set one after another starts each from the best (one move away)
// rather than from the neighbour before (two moves); one that steps from set to set starts each
// from the last. The references follow the sets evaluated, so no change accumulates since some
// earlier set.
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "trace/contributions.h"
#include "trace/replicates.h"

namespace fenestra {

class Progress;

// The solver's samples (RecordQueries::sampled) evaluate one in this many of the paths a change
// met: a quarter of the cost, with the sampling's error about the exact value.
constexpr uint32_t kSampledShare = 4;

class ExactValues {
 public:
  ExactValues(const Contributions& c, const Progress* progress) : c_(c), progress_(progress) {}

  const SensorValues& operator()(const std::vector<uint8_t>& open);
  // Values of `open` from one path in `share` of those that changed (a screen that rules sets out
  // before operator() scores them): per sensor, its nearer reference's exact value plus the
  // change of the sampled paths, scaled. The paths sampled are a fixed choice (the same for every
  // set, so that sets compare on the same paths). `standard_error` is the sampling's, how far the
  // estimate may be from operator()'s value, not the records' own noise. A sensor with few changed
  // paths has them all evaluated (error 0), and a set already evaluated is given exactly. Leaves
  // the references and the counters above as they were, unless no set was evaluated yet: then
  // `open` is evaluated as operator() does (exactly, error 0), and becomes the references.
  SensorValues sampled(const std::vector<uint8_t>& open, uint32_t share);
  // Paths evaluated by sampled() so far, over all sensors, and those of them whose values
  // operator() took again (a set scored after its sample).
  size_t sampled_path_evaluations() const { return sampled_path_evaluations_; }
  size_t sampled_paths_reused() const { return sampled_paths_reused_; }
  // Sensor evaluations done in full so far, and all of them (the others were evaluated from the
  // sensor's reference).
  size_t full_evaluations() const { return full_evaluations_; }
  size_t sensor_evaluations() const { return sensor_evaluations_; }
  // Paths evaluated so far, over all sensors (in full or from the reference; those whose values
  // the last sampled() of the same set had evaluated included).
  size_t path_evaluations() const { return path_evaluations_; }
  // Bytes of the index of paths per element and the reference's per-path values (the cost
  // model's exact_values_index).
  size_t memory_bytes() const;

 private:
  SensorValues evaluate(const std::vector<uint8_t>& open);
  // Sensor i's replicate sums for `open`, which becomes its last reference (slot `slot`): in full,
  // or from whichever of its references fewer paths met an element of `changed[its slot]` (those
  // whose state differs from it) when they are at most kMaxShareFromReference of its paths; that
  // reference becomes the other. `sampled`: this set's sample of sensor i's paths (sampled() of
  // the same set just before), whose values are taken, or nullptr. `evaluated`: the paths
  // evaluated; `reused`: those of them whose values came from the sample.
  struct SampledPaths;
  ReplicateSums sensor_sums(size_t i, const std::vector<uint8_t>& open,
                            const std::vector<std::vector<int32_t>>& changed, int slot, const SampledPaths* sampled,
                            bool* in_full, size_t* evaluated, size_t* reused);
  // Paths of sensor i that met an element of `changed`, counted once per element (a bound).
  size_t paths_met(size_t i, const std::vector<int32_t>& changed) const;
  // Sensor i's paths that met an element of `changed`, each once, in order; false (and `out`
  // partly filled) when they are more than kMaxShareFromReference of its paths.
  bool changed_paths(size_t i, const std::vector<int32_t>& changed, std::vector<uint32_t>* out) const;
  // Per reference slot in use, the elements whose state differs from it in `open`.
  std::vector<std::vector<int32_t>> changed_elements(const std::vector<uint8_t>& open) const;
  // Which of sensor i's references fewer paths' changes separate from `open` (the last on a tie;
  // -1 without one), and that number (counted once per element, a bound).
  int nearer_reference(size_t i, const std::vector<std::vector<int32_t>>& changed, size_t* met) const;
  // Sensor i's sampled() value and its sampling error.
  void sampled_sensor(size_t i, const std::vector<uint8_t>& open, const std::vector<std::vector<int32_t>>& changed,
                      uint32_t share, double* value, double* standard_error, size_t* evaluated);
  // Sensor i's paths in the sample of one in `share` that met an element of `changed`, each once,
  // in order.
  void sampled_paths(size_t i, const std::vector<int32_t>& changed, uint32_t share, std::vector<uint32_t>* out) const;
  void build_index();
  int free_slot();

  const Contributions& c_;
  const Progress* progress_;
  std::map<std::vector<uint8_t>, SensorValues> known_;
  // Per sensor: the paths that met each element, by any of their events or conditions (CSR:
  // element k's at paths[begin[k]] .. paths[begin[k + 1]]).
  std::vector<std::vector<uint32_t>> element_begin_, element_paths_;
  // A sensor's reference: a set it was evaluated for (a slot of reference_sets_, -1 before any),
  // its per-path values and their sums. Every choice is the sensor's own, so a sensor's values do
  // not depend on the others (a study's shards give the same numbers as one process).
  struct Reference {
    int slot = -1;
    std::vector<double> values;  // [path]
    ReplicateSums sums;
  };
  std::vector<std::vector<uint8_t>> reference_sets_;
  std::vector<size_t> reference_users_;  // references per slot (an empty slot is reused)
  std::vector<std::array<Reference, 2>> references_;  // [sensor]
  std::vector<uint8_t> last_;  // [sensor]: which of its two references is the last set evaluated
  // The last set sampled() and, per sensor, the paths it evaluated with their values (ascending):
  // a set scored right after its sample takes them rather than evaluating them again.
  struct SampledPaths {
    std::vector<uint32_t> paths;
    std::vector<double> values;
  };
  std::vector<uint8_t> sampled_set_;
  std::vector<SampledPaths> sampled_paths_;  // [sensor]
  size_t full_evaluations_ = 0, sensor_evaluations_ = 0, path_evaluations_ = 0, sampled_path_evaluations_ = 0;
  size_t sampled_paths_reused_ = 0;
};

}  // namespace fenestra
