#pragma once
// Openings' edges, moved (one, or two opposite ones together so that the opening slides) while
// the exact error from the path records falls and the openings stay admissible: by whole elements
// (an exact local search), then in halving steps from half an element down to the module (or 1 cm
// when edges are continuous). In thick walls the records follow the tubes of the grid they were
// traced on, so edges move only along its lines: whole elements on the element grid; finer steps
// (down to kThickWallEdgeStep) with real cutters (EdgeSearchScope::real_cuts, thick_wall_edges.h).
#include <string>
#include <vector>

#include "scene/opening_constraints.h"
#include "solve/genetic.h"
#include "solve/record_queries.h"
#include "trace/contributions.h"
#include "trace/open_region.h"

namespace fenestra {

class Progress;

// Smallest step of continuous edges (solver.constraints.module 0), meters.
constexpr double kContinuousEdgeStep = 0.01;
// Smallest step of edges in thick walls, meters: each position tried is a real cut (the scene
// path-traced again), so their number is kept small.
constexpr double kThickWallEdgeStep = 0.05;

// Steps of the edge search, meters: a whole element, then halving steps down to the module
// (continuous edges: 1 cm; in thick walls at least kThickWallEdgeStep), snapped to the module.
std::vector<double> edge_steps(double element_size, double module, bool thick);
// How far an edge in a thick wall is searched from where the element grid left it, meters: an
// element and the finer steps' sum (a truth between grid lines may lie beyond the nearest line
// that the grid's records preferred), 0 when the steps stop at whole elements.
double thick_wall_edge_span(double element_size, double module);
// Positions (grid coordinates) an edge at `edge` may take below a whole element, within the span
// (one element on zero-thickness panels): the edge plus multiples of the finest step, or module
// multiples.
std::vector<float> edge_positions(double edge, double element_size, double module, bool thick);

PanelRectangle panel_rectangle(const GridRectangle& r, double element_size);

// One opening of panel `panel` off the grid: on existing elements (every element square it
// overlaps, `margin` around it included), within the size, aspect, sill and head limits.
bool admissible(const PanelRectangle& r, const OpeningDomain& domain, const OpeningConstraints& constraints,
                std::string* why = nullptr);
// Two openings of one panel at least min_gap (and 1 cm) apart.
bool apart(const PanelRectangle& a, const PanelRectangle& b, const OpeningConstraints& constraints);

// Sensor values when an opening moves from `from` to `to` (one panel), predicted from `values` by
// the light each element adds when opened (opening_light, sensors x elements), in proportion to
// the share of its cell that opens or closes.
Eigen::VectorXd screened_values(const OpeningDomain& domain, const Eigen::MatrixXd& opening_light,
                                const Eigen::VectorXd& values, const PanelRectangle& from, const PanelRectangle& to);

// What the openings break of the constraints (one line each, empty when nothing): an opening not
// admissible(), two not apart(), more than max_openings, or more than a panel's limit.
std::vector<std::string> constraint_violations(const OpeningDomain& domain, const std::vector<PanelRectangle>& openings,
                                               const OpeningConstraints& constraints);

struct EdgeRefinement {
  std::vector<PanelRectangle> openings;
  int moves = 0;         // accepted edge moves
  int evaluations = 0;   // candidate regions evaluated
};

// Which moves the search makes: whole-element steps or only the finer ones; on every panel or only
// in thick walls (the search with real cutters).
struct EdgeSearchScope {
  bool whole_elements = true;
  bool zero_thickness_panels = true;
  bool thick_panels = true;  // false: openings in thick walls stay as they are
  int only_opening = -1;     // >= 0: only this opening (its index in the start) moves
  // > 0 with real_cuts: first, for each opening in a thick wall and each axis, pairs of positions
  // of its two edges within this distance are searched (its error along a sill or head can have
  // narrow valleys that single steps do not cross), coarse to fine down to the finest thick-wall
  // step, and the best pair kept; again one step about it while a pass gains.
  double scan_span = 0.0;
  // Optional, sensors x elements: the light each element adds when opened (a linearisation about
  // the start). It ranks the moves of every step but the finest, so that few are evaluated.
  const Eigen::MatrixXd* opening_light = nullptr;
  // > 0: the steps stop at the first not below this (meters): a quicker, coarser search.
  double coarsest_finest_step = 0.0;
  // The values are real cuts: edges in thick walls need not lie on grid lines.
  bool real_cuts = false;
};

EdgeRefinement refine_edges(const OpeningDomain& domain, RecordQueries& records, const LinearObjective& objective,
                            const OpeningConstraints& constraints, const std::vector<PanelRectangle>& start,
                            Progress* progress, const EdgeSearchScope& scope = {});
// The same from the openings `search` holds, which it holds, moved, afterwards (so that one index
// serves several searches).
// (`closed`: the all-closed values per sensor, which the objective's targets are net of.)
EdgeRefinement refine_edges(const OpeningDomain& domain, const Eigen::VectorXd& closed,
                            const LinearObjective& objective, const OpeningConstraints& constraints,
                            RegionQueries* search, Progress* progress, const EdgeSearchScope& scope = {});

}  // namespace fenestra
