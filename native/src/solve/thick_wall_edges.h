#pragma once
// Edges of openings in thick walls below the element size. The path records of a thick wall follow
// the tubes of the grid they were traced on, so an edge between grid lines cannot be evaluated from
// them: the sides are placed where the element grid's records interpolate them best, and searched
// from there with real cutters (the scene path-traced with the openings cut, reveals and all).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "solve/edge_refinement.h"
#include "trace/contributions.h"

namespace fenestra {

// Whether the edge search with real cutters could reach `to` from `from` (openings on the element
// grid): as many openings, each on the same panel with every side within the search's span of its
// own (whole elements).
bool within_thick_wall_edge_reach(const std::vector<GridRectangle>& from, const std::vector<GridRectangle>& to,
                                  double element_size, double module);

// Paths per sensor of each cut of the edge search with real cutters, at most. The
// candidates share their random numbers (each path's, by sensor and index), so that they differ
// mostly by the light their edges change; their sky samples aim at each candidate's own openings
// (as the check's), which gives the cuts of a thick wall about a third of the variance per path of
// sampling the sky alone. Measured on the solid off-grid two-room study: at 1 024 paths the
// thick-wall stages took 39 s and the answer checked at 0.86 %, against 281 s and 1.30 % at 4 096
// paths with the sky sampled alone.
constexpr int kThickWallEdgeCutPaths = 1024;
// The fewest paths per sensor of those cuts (a solve with fewer paths cuts with its own).
constexpr int kThickWallEdgeCutPathsAtLeast = 128;
// The cuts' paths follow the solve's quality: a sixteenth of the solve's paths per sensor, from
// 128 to 1 024. A final solve (16 384 paths) cuts with 1 024; a preview (2 048) with 128, and its
// judged cuts with 512, as many as the add-on's preview check. On the thick-walled room example
// at preview, a re-solve's thick-wall stages took 19 s with 1 024 paths and 3.5 s with 128, and the
// answer (the same single opening) checked at 28.9 % and 29.8 % against its goals (noise 5 %).
inline int thick_wall_cut_paths(int solver_paths) {
  return std::clamp(solver_paths / 16, std::min(kThickWallEdgeCutPathsAtLeast, solver_paths), kThickWallEdgeCutPaths);
}
// Their random numbers are not the check's (RecordQueries::cut's stream 0): a check of the chosen
// openings does not repeat the noise they were chosen by.
constexpr uint64_t kThickWallEdgeCutStream = 1;

struct ThickWallEdges {
  EdgeRefinement edges;                // the cut search's moves and cuts, and its openings
  std::vector<PanelRectangle> placed;  // the openings placed by interpolation (its start if better)
  double interpolated = 0.0;           // the placement's interpolated error
  bool from_placement = false;         // the search started from `placed`
  SensorValues start_values, values;   // cut: the openings given, and the result
  int cuts = 0;                        // all the search's cuts of `paths`
  int rough_cuts = 0;                  // and of half as many (CutRegionSearch::rough_values)
};

// The edge search with real cutters in thick walls: finer steps only, on thick panels only, pairs
// of edges scanned over thick_wall_edge_span first (refine_edges).
EdgeSearchScope thick_wall_edge_scope(const OpeningDomain& domain, const OpeningConstraints& constraints);

// Edges in thick walls placed by the interpolation of the element grid's records
// (interpolated_placement) and cut: the placed openings, or the start when its cut meets the goals
// better. `edges.openings` holds them, with no moves; two cuts.
ThickWallEdges place_thick_wall_edges(const OpeningDomain& domain, RecordQueries& records,
                                      const LinearObjective& objective, const OpeningConstraints& constraints,
                                      const std::vector<PanelRectangle>& start, int paths);

// Edges in thick walls searched with real cutters: placed (place_thick_wall_edges), then moved in
// steps below the element (edge_steps in thick walls) while the error of the real cuts falls. The
// solver searches so only where sizes are fixed (a catalogue): elsewhere every side moves at once
// (thick_wall_joint_edges.h), for a fifth of these cuts.
ThickWallEdges search_thick_wall_edges(const OpeningDomain& domain, RecordQueries& records,
                                       const LinearObjective& objective, const OpeningConstraints& constraints,
                                       const std::vector<PanelRectangle>& start, int paths, Progress* progress);

}  // namespace fenestra
