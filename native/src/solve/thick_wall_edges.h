#pragma once
// Edges of openings in thick walls below the element size. The path records of a thick wall follow
// the tubes of the grid they were traced on, so an edge between grid lines cannot be evaluated from
// them. The element grid is the coarse level: about each opening a region of the panel is cut
// along the positions its edges may reach (edge_positions), the rest of the panel stays wall, the
// paths are traced again on that grid (same seed and paths), and the edges are searched on its
// lines, exactly. When an edge ends at its region's border, once more about the new openings.
#include <optional>
#include <string>
#include <vector>

#include "solve/edge_refinement.h"
#include "trace/contributions.h"

namespace fenestra {

struct ThickWallEdges {
  EdgeRefinement edges;         // the search's result (moves and evaluations over all rounds)
  // Exact values from the last round's records, and the objective's error, of its start and result.
  SensorValues start_values, values;
  double start_error = 0.0, error = 0.0;
  int rounds = 0;
};

// The regions to refine: about each opening on a thick panel, the rectangle its edges may reach,
// with a line at every position they may take; each opening elsewhere, itself (it stays open).
std::vector<RefinedRegion> thick_wall_edge_regions(const OpeningDomain& domain,
                                                   const std::vector<PanelRectangle>& openings, double module);

// Whether the edge search on the refined grid could reach `to` from `from` (openings on the element
// grid): as many openings, each on the same panel with every side within the search's span of its
// own (whole elements).
bool within_thick_wall_edge_reach(const std::vector<GridRectangle>& from, const std::vector<GridRectangle>& to,
                                  double element_size, double module);

// Whether the refined records fit in memory beside `coarse_records` (an estimate from theirs).
bool thick_wall_edges_fit(const RecordQueries& coarse_records);

// Nothing when no opening lies on a thick panel or the steps stop at whole elements. Otherwise the
// refined records and the edges searched on them, starting from `start`. When the refined records
// would not fit in memory (estimated from `coarse`'s), nothing, and *skipped says why.
std::optional<ThickWallEdges> refine_thick_wall_edges(const Scene& scene, RecordQueries& coarse_records,
                                                      const LinearObjective& objective,
                                                      const OpeningConstraints& constraints,
                                                      const std::vector<PanelRectangle>& start, Progress* progress,
                                                      std::string* skipped);

}  // namespace fenestra
