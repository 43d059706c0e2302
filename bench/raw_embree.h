#pragma once
// [1] Raw Embree throughput: RayScene::intersect alone on the scene's mesh, incoherent rays, on one
// thread and on all: the ceiling the one-pass tracer's rays per second are compared with.
#include "bench_common.h"

namespace bench {

struct RawThroughput {
  double one_thread = 0.0, all_threads = 0.0;  // rays per second
  double hit_fraction = 0.0;                   // sanity: rays from inside a closed room nearly all hit
};

// Each of 2^20 rays traced once per pass, passes repeated for at least 1.5 s, flushing denormals as
// the tracer's workers do.
RawThroughput raw_embree_throughput(const Scene& scene);
// Its report: JSON ("raw_embree") and printed lines.
json raw_json(const RawThroughput& raw);
void print_raw(const RawThroughput& raw);

}  // namespace bench
