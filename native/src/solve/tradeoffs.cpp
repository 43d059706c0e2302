#include "solve/tradeoffs.h"

#include <algorithm>
#include <limits>
#include <optional>

#include "solve/edge_refinement.h"
#include "trace/evaluate.h"
#include "util/progress.h"

namespace fenestra {
namespace {

// The trade-offs' edge search stops at this step (meters): a few centimetres change their errors
// little, and the list must stay quick to compute.
constexpr double kTradeoffEdgeStep = 0.05;

bool any_thick(const OpeningDomain& domain, const std::vector<PanelRectangle>& openings) {
  return std::any_of(openings.begin(), openings.end(),
                     [&](const PanelRectangle& r) { return domain.panels()[r.panel].thickness > 0.0f; });
}

std::vector<PanelRectangle> without(std::vector<PanelRectangle> openings, size_t i) {
  openings.erase(openings.begin() + static_cast<std::ptrdiff_t>(i));
  return openings;
}

}  // namespace

std::vector<Tradeoff> fewer_openings(const Scene& scene, RecordQueries& records, const LinearObjective& objective,
                                     const OpeningConstraints& constraints, const std::vector<PanelRectangle>& openings,
                                     const Eigen::MatrixXd* opening_light, int check_paths,
                                     const Recompose& recompose, Progress* progress) {
  std::vector<Tradeoff> out;
  const OpeningDomain& domain = scene.domain;
  const bool cut = any_thick(domain, openings);
  auto cut_values = [&](const std::vector<PanelRectangle>& set) {
    std::vector<OpeningInput> cutters(set.begin(), set.end());
    return records.cut(cutters, check_paths, 0);
  };
  const Eigen::VectorXd& closed = records.contributions().closed.value;
  auto error_of = [&](const Eigen::VectorXd& values) { return prediction_error(objective, values - closed); };
  std::vector<PanelRectangle> current = openings;
  // One index of the records' points serves every removal and edge search (zero-thickness panels).
  std::unique_ptr<RegionQueries> search;
  if (!cut) search = records.region_search(current);
  while (current.size() > 1 && static_cast<int>(out.size()) < kMaxTradeoffs) {
    if (progress) progress->throw_if_cancelled();
    // The opening whose removal raises the error least.
    size_t removed = 0;
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < current.size(); ++i) {
      const std::vector<PanelRectangle> fewer = without(current, i);
      const double e = error_of(cut ? cut_values(fewer).value : search->try_region(fewer));
      if (e < best) best = e, removed = i;
    }
    current = without(current, removed);
    if (recompose) current = recompose(current);
    if (!cut) {
      search->try_region(current);
      search->accept();
      // The rest's edges, searched again (exact on zero-thickness panels).
      if (!recompose) {
        EdgeSearchScope scope;
        scope.opening_light = opening_light;
        scope.coarsest_finest_step = kTradeoffEdgeStep;
        current = refine_edges(domain, closed, objective, constraints, search.get(), progress, scope).openings;
      }
    }
    Tradeoff entry;
    entry.cut = cut;
    entry.values = cut ? cut_values(current) : records.evaluate(current);
    entry.openings = current;
    out.push_back(std::move(entry));
  }
  return out;
}

}  // namespace fenestra
