#pragma once
// Every side of every opening in thick walls moved at once, by real cuts. The edge search
// (thick_wall_edges.h) moves one side or one pair of sides at a time, so it stops where one
// panel's openings make up for another's: no single move gains though moving them together does.
// Its cuts also carry noise of the size of the error it minimises (2 % of the goals at 4096 paths
// per sensor in the solid two-room study), so its last moves follow that noise. Here each side's
// effect on every sensor is measured by central differences of cuts sharing their random numbers
// (a Jacobian; their sky samples, aimed at each cut's own openings, differ a little), and
// Levenberg-Marquardt steps of all sides together are judged by cuts of more paths.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "solve/edge_refinement.h"
#include "solve/record_queries.h"

namespace fenestra {

// Paths per sensor of the cuts that judge a step, as a multiple of the differences' paths (at most
// the solver's): differences share their random numbers and cancel most of their noise, a step's
// error does not.
constexpr int kJointEdgeJudgeFactor = 4;
// Those judged cuts' paths per sensor, for cuts of `cut_paths` in a solve of `solver_paths`.
inline int joint_edge_judge_paths(int cut_paths, int solver_paths) {
  return std::max(cut_paths, std::min(kJointEdgeJudgeFactor * cut_paths, solver_paths));
}
// Their random numbers: neither the edge search's (kThickWallEdgeCutStream) nor the check's (0).
constexpr uint64_t kThickWallJointEdgeStream = 2;
// Steps at most; each costs about two difference cuts per side and kJointEdgeDampings judged cuts.
// Measured on the solid off-grid two-room study (three openings, 12 sides, from the records'
// placement and the merges): seven steps, the judged error 2.76 % -> 0.92 %; from the five
// openings of a search by pairs of edges, two steps (2.04 % -> 1.84 %).
constexpr int kJointEdgeMaxSteps = 8;
// Levenberg-Marquardt dampings tried at each step, relative to the mean of J'J's diagonal: the
// differences are linear over a step of about one difference width only.
constexpr double kJointEdgeDampings[] = {0.001, 0.01, 0.1};
// A step is taken when it lowers the judged error by more than this share.
constexpr double kJointEdgeGain = 0.01;

struct ThickWallJointEdges {
  std::vector<PanelRectangle> openings;  // the start when no step gained
  SensorValues start_values, values;     // judged cuts of the start and of `openings`
  int steps = 0;                         // steps taken
  int sides = 0;                         // sides moved (four per opening in a thick wall)
  int cuts = 0;                          // difference cuts (`paths` per sensor)
  int judged_cuts = 0;                   // judged cuts (`judge_paths` per sensor)
  bool scanned = false;                  // scan_stalled_joint_edges ran
  int scan_cuts = 0, scan_rough_cuts = 0;  // its cuts (`paths`, and half as many)
  int scan_moves = 0;                    // its moves, when kept
  // Sensors the difference and scan cuts traced, and as many as tracing every sensor each time
  // (a side's cuts trace the sensors its moves can reach: RecordQueries::sensors_reached).
  size_t sensors_traced = 0, sensors_cut = 0;
};

// The sides of the openings in thick walls of `start` moved together while the judged error (the
// objective over cuts of `judge_paths` on `stream`) falls: differences of +-one finest edge step
// (one-sided where a side cannot move both ways), steps clipped to the edge search's span and
// snapped to the module (1 cm when edges are continuous); the sides of an opening a step would make
// inadmissible are held, and the others' step solved again.
ThickWallJointEdges joint_thick_wall_edges(const OpeningDomain& domain, RecordQueries& records,
                                           const LinearObjective& objective, const OpeningConstraints& constraints,
                                           const std::vector<PanelRectangle>& start, int paths, int judge_paths,
                                           uint64_t stream, Progress* progress);

// The joint steps follow a smooth error: where a sill and a head trade against each other in a
// narrow valley (sensors just below the sill) they stall. Measured on make validate's
// thick_walls_off_grid (one window, 4 sides): four steps from the placement took the judged error
// from 6.4 % to 4.2 %, where the pair scans from the same placement had reached 1.4 %; from the
// steps' openings the scans found no move (another valley). So, when the solver finds `joint`
// beyond the noise, the edge search's pair scans and single moves (refine_edges with
// thick_wall_edge_scope, cuts of `paths` on kThickWallEdgeCutStream) run from `start`, the
// openings the steps began from; their result is judged as a step is (`judge_paths` on `stream`)
// and replaces the steps' when the judged error is lower.
void scan_stalled_joint_edges(const OpeningDomain& domain, RecordQueries& records, const LinearObjective& objective,
                              const OpeningConstraints& constraints, const std::vector<PanelRectangle>& start,
                              int paths, int judge_paths, uint64_t stream, Progress* progress,
                              ThickWallJointEdges* joint);

}  // namespace fenestra
