#pragma once
// [2b] Estimators side by side: the stratified first decisions (render.sampler "sobol", the
// default) against independent random numbers (the estimator before them), same scene, same reference.
#include <vector>

#include "accuracy_ladder.h"
#include "raw_embree.h"

namespace bench {

// The ladder again with independent random numbers, printed, and both estimators' time and record
// memory to the targets with their ratios ("estimators").
json estimator_comparison(const Scene& scene, int top, const Reference& ref, const std::vector<int>& columns,
                          const std::vector<Rung>& sobol_ladder, const RawThroughput& raw);

}  // namespace bench
