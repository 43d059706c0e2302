#pragma once
// Openings' edges, moved (one, or two opposite ones together so that the opening slides) while
// the exact error from the path records falls and the openings stay admissible: by whole elements on every panel (an exact local search), then in halving steps from
// half an element down to the module (or 1 cm when edges are continuous) on zero-thickness panels;
// in thick walls the elements' tubes follow the element grid.
#include <string>
#include <vector>

#include "solve/constraints.h"
#include "solve/genetic.h"
#include "trace/contributions.h"
#include "trace/open_region.h"

namespace fenestra {

class Progress;

// Smallest step of continuous edges (solver.constraints.module 0), meters.
constexpr double kContinuousEdgeStep = 0.01;

PanelRectangle panel_rectangle(const GridRectangle& r, double element_size);

// One opening of panel `panel` off the grid: on existing elements (every element square it
// overlaps, `margin` around it included), within the size, aspect, sill and head limits.
bool admissible(const PanelRectangle& r, const Panel& panel, const OpeningConstraints& constraints, double element_size,
                std::string* why = nullptr);
// Two openings of one panel at least min_gap (and 1 cm) apart.
bool apart(const PanelRectangle& a, const PanelRectangle& b, const OpeningConstraints& constraints);

struct EdgeRefinement {
  std::vector<PanelRectangle> openings;
  int moves = 0;         // accepted edge moves
  int evaluations = 0;   // candidate regions evaluated
};

EdgeRefinement refine_edges(const OpeningDomain& domain, const Contributions& c, const LinearObjective& objective,
                            const OpeningConstraints& constraints, const std::vector<PanelRectangle>& start,
                            Progress* progress);

}  // namespace fenestra
