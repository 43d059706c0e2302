#pragma once
// A choice of trade-offs: besides the answer with N openings, the best found with N - 1, N - 2,
// ..., 1 (at most kMaxTradeoffs of them), so that a simpler design can be picked knowing what it
// costs. From the answer, the opening whose removal raises the error least is removed, and the
// edges of the rest are searched again (they often grow to make up for it); that set is the next
// entry and the start of the one after.
//
// Values are exact from the path records on zero-thickness panels; when an opening lies in a thick
// wall (whose records are exact only on the element grid) every set is cut for real (evaluate,
// `check_paths` paths per sensor; 0: the contributions').
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "scene/opening_constraints.h"
#include "scene/scene.h"
#include "solve/genetic.h"
#include "solve/record_queries.h"
#include "trace/contributions.h"
#include "trace/open_region.h"

namespace fenestra {

class Progress;

constexpr int kMaxTradeoffs = 8;

struct Tradeoff {
  std::vector<PanelRectangle> openings;
  SensorValues values;  // per sensor, as the answer's `predicted`
  bool cut = false;     // values from real cutters (thick walls), not the records
};

using Recompose = std::function<std::vector<PanelRectangle>(const std::vector<PanelRectangle>&)>;

// Entries with fewer openings than `openings`, most openings first. `opening_light` (optional,
// sensors x elements) screens the edge search as in the solver. With `recompose` (facade
// composition rules), it replaces the edge search: each set is composed again.
std::vector<Tradeoff> fewer_openings(const Scene& scene, RecordQueries& records, const LinearObjective& objective,
                                     const OpeningConstraints& constraints, const std::vector<PanelRectangle>& openings,
                                     const Eigen::MatrixXd* opening_light, int check_paths,
                                     const Recompose& recompose, Progress* progress);

}  // namespace fenestra
