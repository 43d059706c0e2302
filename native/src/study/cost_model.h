#pragma once
// The cost model: memory and time a computation will need, estimated from the scene's sizes and
// settings before anything large is allocated (docs/cost.md). check_cost() refuses what will not
// fit in the memory limit (util/memory_limit.h) or exceeds a stage's time limit, naming the
// figure and the setting to change.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/cost_context.h"
#include "util/cost_error.h"
#include "util/memory_limit.h"

namespace fenestra {

struct Scene;

struct MemoryItem {
  std::string key;          // "E", "T", "path_records", ...
  std::string description;  // for messages: "the error-compensation matrix T"
  double bytes = 0.0;
  std::string phase;        // "": kept in the result; else the stage during which it exists
                            // ("tracing", "solving", "writing"): stages follow one another
  std::string setting;      // what to change to make it smaller
  bool copy = false;        // a stage's working copy of kept items (named through them)
};

struct TimeItem {
  std::string key;          // "tracing", "genetic", "local_search"
  std::string description;
  double seconds = 0.0;     // on the reference machine (2 cores; docs/cost.md)
  double limit_seconds = 0.0;  // 0: not limited
  std::string setting;
};

struct CostEstimate {
  CostCommand command = CostCommand::Any;
  size_t sensors = 0, elements = 0, triangles = 0;
  long long paths_per_sensor = 0;
  double bytes_per_path = 0.0;  // path records, per path per sensor
  std::vector<MemoryItem> memory;
  std::vector<TimeItem> time;

  double kept_bytes() const;  // what the result holds (compare with Contributions::memory_bytes())
  double peak_bytes() const;  // kept + the largest stage's transient memory: what must fit
  const MemoryItem* largest_to_name() const;  // the item a refusal names
};

// Path-record bytes per path per sensor: 8 + 40 x (3 + 1.75 x (1 + sum_{k=1..B} rho^k)) events,
// rho the largest albedo of the scene's materials and B render.max_bounces (measured 1.0-3.7x
// the actual on the example scenes; docs/cost.md).
double path_record_bytes(const Scene& scene);

// "contributions", "evaluate", "solve", "solver", "sky", "annual_cutters", "any"
CostCommand cost_command(const std::string& name);
std::string cost_command_name(CostCommand command);

// `elements` >= 0 stands in for the domain's element count (what another element size would give).
// `elements` and `paths` (per sensor) replace the scene's when >= 0 (what would fit, for messages).
CostEstimate estimate_cost(const Scene& scene, CostCommand command, double elements = -1.0, double paths = -1.0);

// What a computation will hold, in a line: "path records 61.5 MB (1 024 paths per sensor x 100
// sensors), 157 MB at the peak; 20.1 GB available (MemAvailable)".
std::string memory_summary(const Scene& scene, CostCommand command, const MemoryLimit& limit);

// Throws CostError when the estimate's peak exceeds `limit` or a stage exceeds its time limit.
// `paths` (per sensor) replaces the scene's when >= 0 (annual(cutters=True, paths=N) in Python).
void check_cost(const Scene& scene, CostCommand command, const MemoryLimit& limit, double paths = -1.0);
// With the limit in force (memory_limit()).
void check_cost(const Scene& scene, CostCommand command);

}  // namespace fenestra
