#pragma once
// The climate goals' figures of a solve's final openings (the result's "climate"): the year from the
// path records and, with verification, with real cutters; which of the two is shown when they
// disagree beyond the noise; and each goal the openings miss, in words.
#include <string>
#include <vector>

#include "scene/scene.h"
#include "solve/climate_design.h"
#include "solve/solve_result.h"

namespace fenestra {

class RecordQueries;  // solve/record_queries.h

// "41.0 %" for fractions, "512 lx" for the annual mean.
std::string figure_text(const ClimateGoal& goal, double x);

// The final openings' year and each climate goal's figure: from the path records, and with real
// cutters when verification is on; fills out->climate and adds its warnings.
void report_climate(const Scene& scene, RecordQueries& records, const ClimateProblem& problem,
                    const std::vector<PanelRectangle>& openings, bool verify, int verify_paths, SolveResult* out);

// A trade-off's climate figures: the answer's (out's headline), or its openings' year from the path
// records (empty when they cannot tell: edges off the grid lines of a thick wall).
std::vector<ClimateFigure> tradeoff_climate(RecordQueries& records, const ClimateProblem& problem,
                                            const TradeoffResult& entry, const SolveResult& out);

}  // namespace fenestra
