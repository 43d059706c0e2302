#include "solve/thick_wall_edges.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "util/memory_limit.h"
#include "util/progress.h"

namespace fenestra {
namespace {

constexpr int kMaxRounds = 2;

bool on_thick_panel(const OpeningDomain& domain, const PanelRectangle& r) {
  return domain.panels()[r.panel].thickness > 0.0f;
}

// The refined records hold about as many events as the coarse ones (the regions' extra tube sides
// against the wall's elsewhere); twice, for safety, must fit beside them.
constexpr double kRefinedRecordShare = 2.0;

// The objective's targets are light added to the coarse records' closed values; refined records
// have their own closed values (other paths, other tube sides).
LinearObjective shifted_objective(const LinearObjective& objective, const Contributions& coarse,
                                  const Contributions& refined) {
  LinearObjective shifted = objective;
  const Eigen::VectorXd shift = coarse.closed.value - refined.closed.value;
  shifted.target += shift;
  if (shifted.lower.size()) shifted.lower += shift;
  if (shifted.upper.size()) shifted.upper += shift;
  return shifted;
}

bool reached_border(const OpeningDomain& domain, const std::vector<PanelRectangle>& from,
                    const std::vector<PanelRectangle>& to, double reach) {
  for (size_t i = 0; i < from.size() && i < to.size(); ++i) {
    if (!on_thick_panel(domain, from[i])) continue;
    const double moved = std::max({std::abs(to[i].u0 - from[i].u0), std::abs(to[i].u1 - from[i].u1),
                                   std::abs(to[i].v0 - from[i].v0), std::abs(to[i].v1 - from[i].v1)});
    if (moved >= reach - 1e-6) return true;
  }
  return false;
}

}  // namespace

std::vector<RefinedRegion> thick_wall_edge_regions(const OpeningDomain& domain,
                                                   const std::vector<PanelRectangle>& openings, double module) {
  std::vector<RefinedRegion> out;
  const double s = domain.element_size(), span = thick_wall_edge_span(s, module);
  for (const PanelRectangle& r : openings) {
    RefinedRegion g{r.panel, r.u0, r.u1, r.v0, r.v1, {}, {}};
    if (on_thick_panel(domain, r)) {
      g.u0 -= span, g.u1 += span, g.v0 -= span, g.v1 += span;
      for (double edge : {r.u0, r.u1})
        for (float x : edge_positions(edge, s, module, true)) g.u_lines.push_back(x);
      for (double edge : {r.v0, r.v1})
        for (float x : edge_positions(edge, s, module, true)) g.v_lines.push_back(x);
    }
    out.push_back(std::move(g));
  }
  return out;
}

bool within_thick_wall_edge_reach(const std::vector<GridRectangle>& from, const std::vector<GridRectangle>& to,
                                  double element_size, double module) {
  if (from.size() != to.size()) return false;
  const int reach = static_cast<int>(std::floor(thick_wall_edge_span(element_size, module) / element_size + 1e-9));
  std::vector<GridRectangle> a = from, b = to;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].panel != b[i].panel || std::abs(a[i].row0 - b[i].row0) > reach || std::abs(a[i].row1 - b[i].row1) > reach ||
        std::abs(a[i].col0 - b[i].col0) > reach || std::abs(a[i].col1 - b[i].col1) > reach)
      return false;
  return true;
}

bool thick_wall_edges_fit(const RecordQueries& coarse_records) {
  return kRefinedRecordShare * coarse_records.record_bytes() <= static_cast<double>(memory_limit().bytes);
}

std::optional<ThickWallEdges> refine_thick_wall_edges(const Scene& scene, RecordQueries& coarse_records,
                                                      const LinearObjective& objective,
                                                      const OpeningConstraints& constraints,
                                                      const std::vector<PanelRectangle>& start, Progress* progress,
                                                      std::string* skipped) {
  bool any = false;
  for (const PanelRectangle& r : start) any = any || on_thick_panel(scene.domain, r);
  if (!any || edge_steps(scene.domain.element_size(), constraints.module, true).size() < 2) return std::nullopt;

  const Contributions& coarse = coarse_records.contributions();
  const double record_bytes = coarse_records.record_bytes();
  const MemoryLimit limit = memory_limit();
  if (!thick_wall_edges_fit(coarse_records)) {
    std::ostringstream m;
    m << "edges in thick walls stay on the element grid: refining them traces the paths again, which needs about "
      << static_cast<long long>(kRefinedRecordShare * record_bytes / (1 << 20)) << " MiB, more than the "
      << limit.bytes / (1 << 20) << " MiB " << limit.source << " (fewer solver paths, or a larger memory limit)";
    if (skipped) *skipped = m.str();
    return std::nullopt;
  }

  const double span = thick_wall_edge_span(scene.domain.element_size(), constraints.module);
  EdgeSearchScope scope;
  scope.scan_span = span;
  scope.whole_elements = false;
  scope.zero_thickness_panels = false;  // searched on the element grid's records already
  ThickWallEdges out;
  std::vector<PanelRectangle> from = start;
  for (out.rounds = 1;; ++out.rounds) {
    if (progress) progress->start("solving: edges in thick walls, tracing a finer grid", 1);
    const std::unique_ptr<RecordQueries> refined =
        coarse_records.refined(thick_wall_edge_regions(scene.domain, from, constraints.module));
    const Contributions& c = refined->contributions();
    const OpeningDomain& domain = refined->scene().domain;
    const LinearObjective shifted = shifted_objective(objective, coarse, c);
    if (progress) progress->start("solving: edges in thick walls", 1);
    const EdgeRefinement round = refine_edges(domain, *refined, shifted, constraints, from, progress, scope);
    out.edges.moves += round.moves;
    out.edges.evaluations += round.evaluations;
    out.edges.openings = round.openings;
    out.start_values = refined->evaluate(from);
    out.values = refined->evaluate(round.openings);
    out.start_error = prediction_error(shifted, out.start_values.value - c.closed.value);
    out.error = prediction_error(shifted, out.values.value - c.closed.value);
    if (out.rounds >= kMaxRounds || !reached_border(scene.domain, from, round.openings, span)) break;
    from = round.openings;
  }
  return out;
}

}  // namespace fenestra
