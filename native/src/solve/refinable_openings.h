#pragma once
// Openings on the element grid chosen for the error they reach once their edges leave the grid.
//
// In thick walls light grows faster than an opening's area, so a truth between grid lines has no
// close set of whole elements: the grid's best compensates with other openings (a window widened
// on another wall, small extra ones), and edges moved off the grid afterwards start from the wrong
// openings. Scored instead by where its edges could go, the truth's neighbourhood wins: on a
// two-room study with 0.3 m walls, the grid's best 6.1 % (checked with real cutters, five openings
// for three), the truth's elements 15 % on the grid but 1.4 % interpolated.
//
// The interpolated error of a set: each side of each opening moved out, and in, by one element
// (exact, from the records) gives, per sensor, the parabola through the three values (in, on the
// grid line, out); the error is the least the objective reaches with every side moved by at most
// half an element along its parabola (a small box-constrained least squares), so that each side
// stays nearer its grid line than any other. Light in thick walls grows faster than linearly with
// an edge's position: a straight line through the side moved out and the set's own value promised
// 4.0 % for the grid's best above, whose sides placed so and cut for real gave 6.0 %; the parabola
// promised 4.3 % and gave 4.4 %.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "scene/opening_constraints.h"
#include "scene/opening_domain.h"
#include "solve/genetic.h"
#include "trace/open_region.h"

namespace fenestra {

class Progress;

// Farthest a side is interpolated from its grid line, in elements.
constexpr double kInterpolatedReach = 0.5;

// Exact sensor values (light added to the closed domain) of a set of openings.
using OpeningValues = std::function<Eigen::VectorXd(const std::vector<GridRectangle>&)>;

// How the light of a set of grid openings changes as each side leaves its grid line: side j moved
// by s elements (out > 0) gives values + slope_j s + curve_j s^2, for s in [low_j, high_j].
struct SideLight {
  Eigen::MatrixXd slope, curve;  // sensors x sides
  Eigen::VectorXd low, high;     // elements
  std::vector<size_t> opening;   // each side's opening (an index into the set)
  // The same without opening i's sides.
  SideLight without(size_t i) const;
};

// The side light from each side's values moved out and in by one element, less the set's. An
// empty vector where the move cannot be made (it would empty the opening or leave its panel's
// grid): the side then moves only the other way, along the straight line of the move that can.
// `opening`: each side's opening.
SideLight side_light(const std::vector<Eigen::VectorXd>& out, const std::vector<Eigen::VectorXd>& in,
                     const std::vector<size_t>& opening, Eigen::Index sensors, double reach = kInterpolatedReach);

// How far side `side` (0..3: left, right, bottom, top) of openings[i] may move out (`out`) or in,
// in elements up to `reach`, so that the openings stay within the constraints (admissible, apart)
// whatever the other sides do within theirs: the opposite side moved the same way as far, and the
// other openings grown on every side as far (half of any gap is each one's). The largest of reach,
// 3/4, 1/2 and 1/4 of it that does, else 0.
double side_reach(const OpeningDomain& domain, const OpeningConstraints& constraints,
                  const std::vector<PanelRectangle>& openings, size_t i, int side, bool out,
                  double reach = kInterpolatedReach);

// The objective's error (prediction_error) at values + slope s + curve s^2, least over s within
// [low, high] (coordinate Newton steps, Gauss-Newton where the parabolas make it concave).
double interpolated_error(const LinearObjective& objective, const Eigen::VectorXd& values, const SideLight& sides,
                          Eigen::VectorXd* offsets = nullptr);

// Exact sensor values (light added to the closed domain) of openings whose sides in thick walls
// lie on the element grid (the others anywhere).
using PlacedValues = std::function<Eigen::VectorXd(const std::vector<PanelRectangle>&)>;

// The openings with each side of those in thick walls placed where the side light's parabolas
// meet the objective best: within its reach (side_reach), then at the nearest thick-wall edge
// position (edge_positions) no farther from its grid line. Openings elsewhere stay. When the
// placement still breaks a constraint, the openings given. `interpolated`: its interpolated error.
std::vector<PanelRectangle> interpolated_placement(const OpeningDomain& domain, const OpeningConstraints& constraints,
                                                   const std::vector<PanelRectangle>& openings,
                                                   const PlacedValues& values_of, const LinearObjective& objective,
                                                   double* interpolated = nullptr);

struct RefinableOpenings {
  std::vector<GridRectangle> rects;  // sorted; empty when no start was within the constraints
  double start_error = 0.0;          // interpolated error of the start the answer descends from
  double error = 0.0;                // and of rects (infinite when empty)
  int start = -1;                    // that start's rank among the starts, by interpolated error
  // Each start's interpolated error, in the order given (NaN: outside the constraints, or not
  // evaluated when the evaluations ran out).
  std::vector<double> start_errors;
  int evaluations = 0;               // distinct sets evaluated
  int moves = 0;                     // moves from that start
  bool out_of_evaluations = false;
};

// Descents on the interpolated error from the `descents` starts (those within the constraints)
// whose interpolated errors are lowest: each admissible neighbour (an opening removed, moved by an
// element along either axis, or one side out or in) is screened with the current set's side light
// (one evaluation) and, if the screen gains, scored with its own; the first that gains is taken,
// until a scan gains nothing. The best answer. Every set is evaluated once; `max_evaluations`
// bounds them (0: no bound).
RefinableOpenings search_refinable_openings(const OpeningDomain& domain, const OpeningConstraints& constraints,
                                            const std::vector<std::vector<GridRectangle>>& starts,
                                            const OpeningValues& values_of, const LinearObjective& objective,
                                            int max_evaluations, const Progress* progress = nullptr,
                                            size_t descents = 2);

}  // namespace fenestra
