#pragma once
// The paper's final refinement: the solver's open elements turned into admissible rectangular
// openings (constraints.h) that best match the light of the regions they replace, and a short
// local search over whole rectangles that lowers the linear model's error further.
//
// refine_openings, step by step:
//  1. Open elements are clustered into regions (N-8 connectivity, within a panel).
//  2. A region that already is an admissible rectangle is kept as it is.
//  3. Otherwise every admissible rectangle in the region's bounding box (grown to the smallest
//     admissible size when the region is smaller) is scored by how well its light matches the
//     region's: sum_i w_i ((E 1_rect)_i - (E 1_region)_i)^2. Rectangles that split the region
//     (meet it in several N-8 pieces, or not at all) are excluded.
//  4. A region no single admissible opening could cover (its bounding box breaks the aspect
//     limits or is wider, higher or, in elements, larger than allowed) is also split across the
//     side that is too long, into two halves with the gap openings need between them (min_gap,
//     at least one element; the strip in between is dropped), and each connected part of each
//     half is refined on its own (from step 2). Of the best rectangle, the halves' openings and
//     no opening at all, the one whose light matches the region's best is kept.
//  5. The union of the kept rectangles is clustered and refined again, until the number of
//     openings is stable.
//  6. Openings closer than min_gap (or touching) are parted by the least change: among trimming
//     either one (its side facing the other pulled back just far enough, leaving an admissible
//     opening) and dropping the smaller, the change that loses the fewest elements, then the one
//     that leaves the lowest objective error.
//  7. Beyond max_openings, the opening whose removal raises the error least is dropped, one at
//     a time.
// The result is sorted (GridRectangle::operator<) and satisfies_all(); refining its own mask
// returns it unchanged.
#include <cstdint>
#include <vector>

#include "scene/opening_constraints.h"
#include "scene/opening_domain.h"
#include "solve/genetic.h"
#include "util/progress.h"

namespace fenestra {

// With `progress`, both poll cancellation often (every band of rows, region, conflict or few
// hundred proposals) and throw Cancelled.
std::vector<GridRectangle> refine_openings(const OpeningDomain& domain, const std::vector<uint8_t>& open,
                                           const LinearObjective& objective, const OpeningConstraints& constraints,
                                           const Progress* progress = nullptr);

// Stochastic descent over whole openings: each of `iterations` proposals moves one opening by an
// element, moves one of its sides out or in by an element, removes it, or adds a new opening of
// the smallest admissible size; a proposal is taken when the openings still satisfy_all() and the
// linear model's error (objective_error) drops. Same seed, same result. The openings given must
// satisfy_all() (refine_openings' result does); otherwise std::invalid_argument says why.
std::vector<GridRectangle> improve_rectangles(const OpeningDomain& domain, std::vector<GridRectangle> rectangles,
                                              const LinearObjective& objective, const OpeningConstraints& constraints,
                                              uint64_t seed, int iterations, const Progress* progress = nullptr);

}  // namespace fenestra
