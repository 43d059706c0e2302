#pragma once
// A stage of the opening solver as its result reports it (docs/solver.md, "Stages"): its name, its
// seconds and why it stopped, so that a solve tells where its time went and what ended each part.
#include <chrono>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "solve/genetic.h"

namespace fenestra {

struct SolveStage {
  std::string name;
  double seconds = 0.0;
  std::string stopped_because;  // one of stop_reason's
  // The relative RMS error against the goals before and after the stage, where it changes the
  // answer's openings (NaN elsewhere).
  double error_before = std::numeric_limits<double>::quiet_NaN();
  double error_after = std::numeric_limits<double>::quiet_NaN();
};

// Why a stage stopped: it ran to its end, or a limit or a test ended it, or it did not run
// ("skipped: " and why). docs/solver.md lists them; a new one is added there too.
namespace stop_reason {
inline constexpr const char* kDone = "done";                        // one pass, run to its end
inline constexpr const char* kConverged = "converged";              // NNLS: its optimality conditions hold
inline constexpr const char* kIterationLimit = "iteration limit";   // NNLS: its iterations ran out first
inline constexpr const char* kGenerationLimit = "generation limit"; // every generation asked for ran
inline constexpr const char* kTimeBudget = "time budget";           // solver.time_budget_s ran out first
inline constexpr const char* kNoImprovement = "no improvement";     // a round gained nothing
inline constexpr const char* kRoundLimit = "round limit";           // every round ran, each gaining
inline constexpr const char* kGoalsMet = "goals met";               // every climate goal is met
inline constexpr const char* kNoCoarseToFine = "skipped: solver.coarse_to_fine is off";
inline constexpr const char* kGridTooSmall = "skipped: the grid is too small for a coarser one";
inline constexpr const char* kNoGenerations = "skipped: solver.generations is 0";
inline constexpr const char* kNoImproveIterations = "skipped: solver.improve_iterations is 0";
inline constexpr const char* kNothingOutOfBounds = "skipped: no open element lies outside the constraints";
inline constexpr const char* kNoClimateGoals = "skipped: no climate goals";
inline constexpr const char* kNoSensorGoals = "skipped: no per-sensor goals";
inline constexpr const char* kCostLittle = "skipped: the constraints cost little";
inline constexpr const char* kClimateTellsCost = "skipped: the climate figures tell what the constraints cost";
inline constexpr const char* kNoOpenings = "skipped: no openings";
inline constexpr const char* kNoCatalogue = "skipped: no catalogue";
inline constexpr const char* kCatalogueSizes = "skipped: the catalogue sets the openings' sizes";
inline constexpr const char* kNoRefineEdges = "skipped: solver.refine_edges is off";
inline constexpr const char* kClimateThickWalls = "skipped: climate goals keep thick-wall edges on the grid";
inline constexpr const char* kNoThickWallEdge = "skipped: no edge in a thick wall can leave the grid";
inline constexpr const char* kWithinNoise = "skipped: the openings on the grid meet the goals within the records' noise";
inline constexpr const char* kNoThickWallEdgeSearch = "skipped: the thick-wall edges were not searched";
inline constexpr const char* kOneOpening = "skipped: one opening";
inline constexpr const char* kCutsWithinNoise = "skipped: the openings' cut meets the goals within its noise";
inline constexpr const char* kNoFacadeRules = "skipped: no facade rules";
inline constexpr const char* kNothingToAlign = "skipped: no facade has two openings to align";
inline constexpr const char* kNoTradeoffs = "skipped: solver.tradeoffs is off";
inline constexpr const char* kNoLeastGlazing = "skipped: goals.least_glazing is off";
inline constexpr const char* kNoVerify = "skipped: solver.verify is off";
inline constexpr const char* kNoSearchEvaluations = "skipped: solver.search_evaluations is 0";
inline constexpr const char* kEvaluationLimit = "evaluation limit";  // solver.search_evaluations ran out first
inline constexpr const char* kClimateFollowsLight = "skipped: climate goals choose openings by the year";
}  // namespace stop_reason

// Why a genetic run stopped.
inline const char* genetic_stop_reason(const GeneticResult& r) {
  return r.out_of_time ? stop_reason::kTimeBudget : stop_reason::kGenerationLimit;
}

// Runs a stage: `run()` returns why it stopped; the stage is listed when it returns (one that
// throws, e.g. cancelled, leaves no result to list it in). Returns its seconds.
template <class Run>
double run_stage(std::vector<SolveStage>* stages, const char* name, Run&& run) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  std::string why = run();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  stages->push_back({name, seconds, std::move(why)});
  return seconds;
}

inline void skip_stage(std::vector<SolveStage>* stages, const char* name, const char* why) {
  stages->push_back({name, 0.0, why});
}

}  // namespace fenestra
