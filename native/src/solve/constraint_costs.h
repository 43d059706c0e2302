#pragma once
// Which constraints keep the answer from the goals. When the openings within the constraints meet
// the goals much worse than the free answer, each family of limits (the smallest size, the largest,
// proportions, margin, sills and heads, gap, counts, catalogue) is lifted in turn and the openings
// are searched again without it; the error each family's absence leaves says what it costs.
//
// Measured on the element grid (the constraints stage's rectangles and local search, scored by
// the exact evaluation), before catalogue snapping and edge refinement: a guide to which limit to
// relax, not a promise of the final error.
#include <functional>
#include <string>
#include <vector>

#include "scene/opening_constraints.h"

namespace fenestra {

struct ConstraintCost {
  std::vector<std::string> keys;  // the family lifted, e.g. {"min_gap"}
  double error_without = 0.0;     // relative RMS error against the goals without it
};

// The families of `constraints` that constrain anything, each with the error `error_with` gives
// with that family lifted (on every panel), least error first. When none alone brings the error
// halfway from `constrained_error` back to `free_error`, two more entries may follow: the families
// that on their own (the others lifted) keep it beyond halfway, lifted at once (when two or more,
// but not all, do so), and every family lifted at once.
// `error_with` is called at most 2 x families + 2 times; it should not return more than
// `constrained_error` (lifting a limit never excludes the openings found within it).
std::vector<ConstraintCost> constraint_costs(
    const OpeningConstraints& constraints, const std::function<double(const OpeningConstraints&)>& error_with,
    double free_error, double constrained_error);

// Whether the constraints cost enough light to explain: the constrained error is above both
// 1.25 x the free answer's and the free answer's plus 2 points (relative RMS).
bool constraints_cost_much(double free_error, double constrained_error);

// "the openings within the constraints meet the goals at 5.7 % on the element grid, the free
// answer at 1.9 %; without margin, sill_min, ... it would be 2.0 % (constraint_costs in the result)",
// or, when no entry gets a tenth of the way back to the free answer, that lifting them does not.
std::string constraint_cost_warning(double free_error, double constrained_error,
                                    const std::vector<ConstraintCost>& costs);

}  // namespace fenestra
