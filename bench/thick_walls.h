#pragma once
// [5] Thick walls: the same scene with its domain a 0.3 m wall, against the zero-thickness wall:
// time to the same accuracy and path-record memory, with the one pass and with real cutters.
#include <string>

#include "bench_common.h"

namespace bench {

// Reads the scene at `scene_path` with a 0.3 m and a zero-thickness domain, prints the comparison
// and returns it ("thick_walls").
json thick_wall_comparison(const std::string& scene_path);

}  // namespace bench
