#pragma once
// How many openings, judged by real cutters. The records that chose the openings misjudge whole
// openings in thick walls (each element's light depends on its neighbours, and the reveals on both),
// so the edge search there (thick_wall_edges.h) may start from one opening split in two, or from an
// opening the goals do not need. After it, each opening is removed and each pair on one thick panel
// merged into one, each candidate cut for real; a merged opening's edges are searched again before
// it is compared, since a merge rarely lands where its edges belong.
#include <cstdint>
#include <vector>

#include "solve/edge_refinement.h"
#include "solve/record_queries.h"

namespace fenestra {

struct ThickWallMerges {
  std::vector<PanelRectangle> openings;  // the openings kept (the start when nothing gained)
  SensorValues values;                   // their cut
  int removed = 0, merged = 0;           // openings removed, pairs merged into one
  int cuts = 0, rough_cuts = 0;          // as ThickWallEdges' (the start's cut included)
  int merges_searched = 0;               // merged openings whose edges were searched (one per round)
};

// Rounds of: the best removal of one opening (each cut), and the best merge of two on one thick
// panel (each merged_openings cut, the best then with its edges searched alone); the better kept
// while it lowers the error of the real cuts of `paths` per sensor on random numbers `stream`.
// `start`: the edge search's openings.
ThickWallMerges merge_thick_wall_openings(const OpeningDomain& domain, RecordQueries& records,
                                          const LinearObjective& objective, const OpeningConstraints& constraints,
                                          const std::vector<PanelRectangle>& start, int paths, uint64_t stream,
                                          Progress* progress);

// The merged openings tried for a and b (one panel): their bounding box, and a rectangle of their
// joint area and the box's aspect about their joint centroid; edges snapped to `unit` (meters).
std::vector<PanelRectangle> merged_openings(const PanelRectangle& a, const PanelRectangle& b, double unit);

}  // namespace fenestra
