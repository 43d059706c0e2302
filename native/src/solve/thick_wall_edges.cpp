#include "solve/thick_wall_edges.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "solve/cut_region_search.h"
#include "solve/refinable_openings.h"

namespace fenestra {

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

EdgeSearchScope thick_wall_edge_scope(const OpeningDomain& domain, const OpeningConstraints& constraints) {
  EdgeSearchScope scope;
  scope.whole_elements = false;
  scope.zero_thickness_panels = false;
  scope.real_cuts = true;
  // Sill and head (or jambs) trade against each other in narrow valleys that single moves do not
  // cross: pairs of positions of the two edges are searched first, over the whole span.
  scope.scan_span = thick_wall_edge_span(domain.element_size(), constraints.module);
  return scope;
}

namespace {

struct Placement {
  ThickWallEdges out;
  std::unique_ptr<CutRegionSearch> given, placed;

  CutRegionSearch& chosen() { return out.from_placement ? *placed : *given; }

  void count() {
    out.cuts = given->cuts() + placed->cuts();
    out.rough_cuts = given->rough_cuts() + placed->rough_cuts();
  }
};

Placement placement(const OpeningDomain& domain, RecordQueries& records, const LinearObjective& objective,
                    const OpeningConstraints& constraints, const std::vector<PanelRectangle>& start, int paths) {
  Placement p;
  const Eigen::VectorXd& closed = records.contributions().closed.value;
  const PlacedValues values_of = [&](const std::vector<PanelRectangle>& openings) {
    return Eigen::VectorXd(records.evaluate(openings).value - closed);
  };
  p.out.placed = interpolated_placement(domain, constraints, start, values_of, objective, &p.out.interpolated);
  p.given = std::make_unique<CutRegionSearch>(records, start, paths, kThickWallEdgeCutStream);
  p.placed = std::make_unique<CutRegionSearch>(records, p.out.placed, paths, kThickWallEdgeCutStream);
  p.out.start_values = p.given->current();
  p.out.from_placement = prediction_error(objective, p.placed->values() - closed) <=
                         prediction_error(objective, p.given->values() - closed);
  p.out.edges.openings = p.chosen().rectangles();
  return p;
}

}  // namespace

ThickWallEdges place_thick_wall_edges(const OpeningDomain& domain, RecordQueries& records,
                                      const LinearObjective& objective, const OpeningConstraints& constraints,
                                      const std::vector<PanelRectangle>& start, int paths) {
  Placement p = placement(domain, records, objective, constraints, start, paths);
  p.out.values = p.chosen().current();
  p.count();
  return std::move(p.out);
}

ThickWallEdges search_thick_wall_edges(const OpeningDomain& domain, RecordQueries& records,
                                       const LinearObjective& objective, const OpeningConstraints& constraints,
                                       const std::vector<PanelRectangle>& start, int paths, Progress* progress) {
  Placement p = placement(domain, records, objective, constraints, start, paths);
  p.out.edges = refine_edges(domain, records.contributions().closed.value, objective, constraints, &p.chosen(),
                             progress, thick_wall_edge_scope(domain, constraints));
  p.out.values = p.chosen().whole();
  p.count();
  return std::move(p.out);
}

}  // namespace fenestra
