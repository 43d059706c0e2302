#pragma once
// A search over whole openings on the element grid, every candidate scored exactly (the solver
// scores it from the path records). The linear models that guide the earlier stages misjudge whole
// openings where elements light the room together (in thick walls each element's light depends
// on its neighbours by tens of percent); this search trusts only the exact score.
//
//  1. Descent from each start, the best scored first: the neighbours of the current openings are
//     scored in turn and the first that gains is taken, the scan going on from the next, until a
//     whole scan gains nothing. Neighbours: an opening removed; moved by an element along either
//     axis; one side, or both sides of an axis, out or in by an element; a side of one axis out and one of the other in (width
//     traded for height); two openings of a panel merged into the rectangle holding both. Only
//     sets within the constraints (satisfies_all) are scored.
//  2. Restarts from the best: each of its openings removed, or moved by two elements along either
//     axis; each opening of the pool (every start's openings) added, or put in place of one on its
//     panel, and fitted alone first (its own moves, while they improve). Descent again from the
//     four that then score best.
//  3. Refits of the best: each opening with every side moved by at most one element at once (81
//     rectangles, reaching what single moves cannot through worse sets), then descent.
//  4. Pair moves of the best (with a screen): two openings moved at once, each by one of its moves
//     above; the screen ranks every such pair from the two moves alone and the best few are
//     scored, then descent. Two
//     openings that light the same room can each compensate the other's error, so that neither
//     alone can move.
// Restarts, refits and pair moves repeat while any gains.
// Every set is considered once (kept by its openings). With a bound (a cheap score no set's can be
// below with any likelihood), a set that must beat a score is scored only when its bound does not
// rule it out: the moves that lose, most of them, cost the bound alone, and the search takes the
// same steps as without it. The same starts, score and bound give the same answer.
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "scene/opening_constraints.h"
#include "scene/opening_domain.h"

namespace fenestra {

class Progress;

constexpr size_t kSearchAlternatives = 3;

// Lower is better; the openings given satisfy_all().
using OpeningScore = std::function<double(const std::vector<GridRectangle>&)>;
// Optional: the scores of pair moves from `about` as predicted from each move alone (e.g. the
// light each adds to `about`'s, summed): for each entry {A, B} of `singles`, the score of A's
// change and B's at once. It only ranks them; the score decides.
using OpeningScreen = std::function<std::vector<double>(
    const std::vector<GridRectangle>& about, const std::vector<std::array<std::vector<GridRectangle>, 2>>& singles)>;

// Optional: a score the set's is not below (but for a small chance), cheaper than the score (e.g.
// from a sample of the records' paths, with its sampling error).
using OpeningBound = std::function<double(const std::vector<GridRectangle>&)>;

struct OpeningSearchResult {
  std::vector<GridRectangle> rects;  // sorted
  // Other sets where a descent ended (local optima), best first, at most kSearchAlternatives: the
  // grid's best is not always the best once edges leave the grid.
  std::vector<std::vector<GridRectangle>> alternatives;
  double score = std::numeric_limits<double>::infinity();
  double start_score = std::numeric_limits<double>::infinity();  // the best start's, before any move
  int best_start = -1;   // which start the answer descends from
  int evaluations = 0;   // distinct sets considered: scored, or ruled out by the bound
  int scored = 0;        // sets scored (the others were ruled out by the bound)
  int best_found_after = 0;  // sets considered when the answer was found
  int moves = 0;         // moves taken, over every descent
  int restarts = 0;      // restarts run
  int pair_moves = 0;    // pair moves taken
  bool out_of_evaluations = false;  // max_evaluations ended it
};

// `starts`: sets of openings; those breaking the constraints are skipped (none left: the result
// is empty with an infinite score). `max_evaluations` bounds the sets considered (0: no bound).
// `progress` advances by one per set considered (its total is the caller's to start) and cancels.
OpeningSearchResult search_whole_openings(const OpeningDomain& domain, const OpeningConstraints& constraints,
                                          const std::vector<std::vector<GridRectangle>>& starts,
                                          const OpeningScore& score, int max_evaluations,
                                          Progress* progress = nullptr, const OpeningScreen& screen = nullptr,
                                          const OpeningBound& bound = nullptr);

}  // namespace fenestra
