#pragma once
// Whether a solve's numbers can be trusted: the prediction (exact evaluation of the same paths the
// solver chose from) against the real-cutter check (independent paths), and whether the paths are
// too few for the elements. Each check returns a warning in words, or "" when all is well.
#include <string>

#include "solve/solver.h"

namespace fenestra {

// Fewer direct (portal) samples per sensor than elements: E is unbiased but noisy, and a solver
// choosing among noisy columns overfits the noise.
std::string sparse_sampling_warning(int paths_per_sensor, size_t elements);

// The verified values disagree with the predicted ones beyond their standard errors (a chi-square
// test over the sensors at about 4 sigma, or the sum of their z-scores beyond 3.5 sigma: a shift
// to one side) by more than 1 % RMS of the prediction.
std::string prediction_mismatch_warning(const SolveResult& result);

}  // namespace fenestra
