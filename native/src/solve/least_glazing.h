#pragma once
// Least glazing (goals.least_glazing): of the designs a solve evaluated, the answer is the one with
// the least glass among those that meet every climate goal, so that no design shown beside it (the
// trade-off list) meets them with less.
#include <cstddef>
#include <vector>

#include "scene/scene.h"
#include "solve/climate_design.h"
#include "solve/solve_result.h"

namespace fenestra {

struct GlazingCandidate {
  double area_m2 = 0.0;  // glazing area
  bool meets = false;    // every climate goal met
  int openings = 0;      // how many
};

// Glazing areas within this share of the least are equal: fewer, larger openings are preferred.
inline constexpr double kEqualGlazingShare = 0.05;

// The candidates that meet the goals, least glass first; among those within kEqualGlazingShare of
// the least glass left, the fewest openings first (then less glass; equal ones keep their order).
std::vector<size_t> passing_by_glazing(const std::vector<GlazingCandidate>& candidates);

class RecordQueries;  // solve/record_queries.h

// The entry of the trade-off list (the answer included) with the least glass among those whose
// year meets every climate goal, from the path records and, with verification on, with real
// cutters too. Fills each entry's `climate` (the answer's from `answer_figures`). Returns its
// index, or -1 when none meets the goals.
int least_glazing_entry(const Scene& scene, RecordQueries& records, const ClimateProblem& problem,
                        const std::vector<ClimateFigure>& answer_figures, bool verify, int verify_paths,
                        std::vector<TradeoffResult>* tradeoffs);

}  // namespace fenestra
