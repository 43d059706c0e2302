#pragma once
// How many openings, judged by real cutters. The records that chose the openings misjudge whole
// openings in thick walls (each element's light depends on its neighbours, and the reveals on both),
// so the edge search there (thick_wall_edges.h) may start from one opening split in two, or from an
// opening the goals do not need. After it, a thick panel's several openings are tried as one (two
// merged, or one left alone), and each opening removed, every candidate cut for real; the one
// opening's edges are searched again before it is compared, since it rarely lands where its edges
// belong.
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
  int merges_searched = 0;               // panels whose one opening's edges were searched
  size_t sensors_traced = 0, sensors_cut = 0;  // CutRegionSearch's
};

// A panel's one opening has its edges searched (single moves of its sides at the thick walls' edge
// steps, about fifty cuts; with a catalogue also pairs of edges, about a hundred) only when its
// first cut misses the goals by at most this times the error of the openings before: its edges
// then move by a few centimetres, which changes the error by less. Measured: the tries that
// gained began at 0.07-0.14 of the error before (cpp_tests' thick walls). On the solid off-grid
// two-room study, from the records' placement, the roof's two openings merged and the west wall's
// small one removed searched 99 cuts in all, where pairs of edges took 99 cuts and 173 of half
// the paths for the same choice; after a search of the five openings' edges by pairs (each panel's
// openings tuned to make up for the other's) the west wall's large opening left alone missed the
// goals 1.47 times as much as the five openings, with the roof's two merged as well 2.1 times.
constexpr double kThickWallMergeWorthSearching = 1.25;

// On each thick panel with several openings, once: one opening instead, the best by its cut of
// each pair merged (merged_openings; with the panel's other openings kept, and alone on it) and
// each opening left alone on the panel, its edges then
// searched alone (as the thick-wall edge search's; see kThickWallMergeWorthSearching), kept when
// the error of the real cuts (`paths` per sensor on random numbers `stream`) falls. Then single
// openings removed while that lowers the error. `start`: the edge search's openings.
ThickWallMerges merge_thick_wall_openings(const OpeningDomain& domain, RecordQueries& records,
                                          const LinearObjective& objective, const OpeningConstraints& constraints,
                                          const std::vector<PanelRectangle>& start, int paths, uint64_t stream,
                                          Progress* progress);

// The merged openings tried for a and b (one panel): their bounding box, and a rectangle of their
// joint area and the box's aspect about their joint centroid; edges snapped to `unit` (meters).
std::vector<PanelRectangle> merged_openings(const PanelRectangle& a, const PanelRectangle& b, double unit);

}  // namespace fenestra
