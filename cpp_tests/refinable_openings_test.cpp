// Openings on the grid chosen by the error they reach once their edges leave it
// (solve/refinable_openings.h), on light with known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "solve/edge_refinement.h"
#include "solve/refinable_openings.h"
#include "test_scenes.h"

namespace fenestra {
namespace {

LinearObjective objective_for(const Eigen::VectorXd& target) {
  LinearObjective o;
  o.target = target;
  o.weight = Eigen::VectorXd::Constant(target.size(), 1.0 / target.squaredNorm());
  return o;
}

// Side light of straight sides: each side's values moved out are `columns`, moved in the negatives.
SideLight straight(const Eigen::MatrixXd& columns) {
  std::vector<Eigen::VectorXd> out, in;
  for (Eigen::Index j = 0; j < columns.cols(); ++j) out.push_back(columns.col(j)), in.push_back(-columns.col(j));
  return side_light(out, in, std::vector<size_t>(out.size(), 0), columns.rows());
}

TEST(InterpolatedError, ReachesATargetWithinHalfAnElementAndNoFarther) {
  const Eigen::Vector3d values(1.0, 2.0, 3.0);
  Eigen::MatrixXd columns(3, 2);
  columns << 1.0, 0.0, 1.0, 0.5, 1.0, 2.0;
  const SideLight sides = straight(columns);
  // Within reach, out and in: the values plus 0.3 of the first side and less 0.2 of the second.
  const Eigen::Vector3d within = values + 0.3 * columns.col(0) - 0.2 * columns.col(1);
  EXPECT_LT(interpolated_error(objective_for(within), values, sides), 1e-10);  // coordinate descent's tolerance
  // Beyond it: 0.8 of the first side; the least squares stops at half an element.
  const Eigen::Vector3d beyond = values + 0.8 * columns.col(0);
  const LinearObjective o = objective_for(beyond);
  EXPECT_NEAR(interpolated_error(o, values, straight(columns.leftCols(1))),
              prediction_error(o, values + 0.5 * columns.col(0)), 1e-12);
  EXPECT_GT(interpolated_error(o, values, sides), 0.0);
  // No side: the values' own error.
  EXPECT_DOUBLE_EQ(interpolated_error(o, values, straight(Eigen::MatrixXd(3, 0))), prediction_error(o, values));
  // A lower bound counts as in prediction_error (its excess squared times bound_weight): with the
  // target at s = 0 and the bound at s = 0.5, the least is at s = 0.5 b / (1 + b).
  LinearObjective bounded = objective_for(values);
  bounded.lower = values + 0.5 * columns.col(0);
  bounded.upper = Eigen::Vector3d::Constant(INFINITY);
  const double s = 0.5 * bounded.bound_weight / (1.0 + bounded.bound_weight);
  const double e = interpolated_error(bounded, values, straight(columns.leftCols(1)));
  EXPECT_LT(e, prediction_error(bounded, values));
  EXPECT_NEAR(e, prediction_error(bounded, values + s * columns.col(0)), 1e-9 * e);
}

// Light that grows faster than linearly with a side's position follows the parabola through the
// side moved in, kept and moved out; a side that cannot move in moves only out.
TEST(InterpolatedError, FollowsEachSidesParabola) {
  const Eigen::Vector3d values(1.0, 2.0, 3.0), a(1.0, 2.0, 0.5), c(0.5, 0.5, 1.0);
  const SideLight curved = side_light({a + c}, {-a + c}, {0}, 3);
  EXPECT_EQ(curved.slope.col(0), a);
  EXPECT_EQ(curved.curve.col(0), c);
  // Its values at s = 0.3 (between the grid lines): met exactly along the parabola, not along a
  // straight line through the side moved out.
  const LinearObjective o = objective_for(values + 0.3 * a + 0.09 * c);
  EXPECT_LT(interpolated_error(o, values, curved), 1e-10);
  EXPECT_GT(interpolated_error(o, values, straight(a + c)), 1e-5);
  // Moving in is impossible: the target below the values is not reached (s stays at 0).
  const SideLight out_only = side_light({a + c}, {Eigen::VectorXd()}, {0}, 3);
  EXPECT_EQ(out_only.low[0], 0.0);
  const LinearObjective below = objective_for(values - 0.2 * a);
  EXPECT_DOUBLE_EQ(interpolated_error(below, values, out_only), prediction_error(below, values));
  // Dropping an opening's sides.
  const SideLight two = side_light({a, c}, {-a, -c}, {0, 1}, 3);
  const SideLight one = two.without(0);
  ASSERT_EQ(one.slope.cols(), 1);
  EXPECT_EQ(one.slope.col(0), c);
  EXPECT_EQ(one.opening, std::vector<size_t>{1});
}

// A 6 x 2.5 m wall of 0.25 m elements (24 x 10).
OpeningDomain wall() {
  return test::domain_of_quads({{Vec3(0, 0, 0), Vec3(6, 0, 0), Vec3(6, 0, 2.5f), Vec3(0, 0, 2.5f)}}, 0.25f);
}

// Light through openings whose edges may lie anywhere (in elements): each element lights the
// sensors by the share of it that is open, over their squared distance plus one, times the square
// root of the opening's area when superlinear (light grows faster than area, as through a thick
// wall).
struct FractionalLight {
  bool superlinear = true;
  std::vector<std::array<double, 2>> sensors;  // row, column
  FractionalLight() {
    for (double r = 0.5; r < 10; r += 3) for (double c = 0.5; c < 24; c += 2.5) sensors.push_back({r, c});
  }
  struct Box { double row0, row1, col0, col1; };  // element units, [row0, row1) x [col0, col1)
  Eigen::VectorXd light(const std::vector<Box>& boxes) const {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(sensors.size()));
    for (const Box& b : boxes) {
      const double gain = superlinear ? std::sqrt((b.row1 - b.row0) * (b.col1 - b.col0)) : 1.0;
      for (int row = static_cast<int>(std::floor(b.row0)); row < b.row1; ++row)
        for (int col = static_cast<int>(std::floor(b.col0)); col < b.col1; ++col) {
          const double share = (std::min(b.row1, row + 1.0) - std::max(b.row0, double(row))) *
                               (std::min(b.col1, col + 1.0) - std::max(b.col0, double(col)));
          for (size_t i = 0; i < sensors.size(); ++i) {
            const double dr = sensors[i][0] - (row + 0.5), dc = sensors[i][1] - (col + 0.5);
            v[static_cast<Eigen::Index>(i)] += gain * share / (dr * dr + dc * dc + 1.0);
          }
        }
    }
    return v;
  }
  Eigen::VectorXd light(const std::vector<GridRectangle>& rects) const {
    std::vector<Box> boxes;
    for (const GridRectangle& r : rects) boxes.push_back({double(r.row0), r.row1 + 1.0, double(r.col0), r.col1 + 1.0});
    return light(boxes);
  }
};

// The truth: two openings with every edge between grid lines.
struct TwoOpenings {
  OpeningDomain d = wall();
  OpeningConstraints c;
  FractionalLight model;
  std::vector<FractionalLight::Box> truth = {{2.4, 7.6, 3.3, 8.6}, {3.5, 8.5, 14.6, 19.4}};
  // The truth's elements (those more than half open).
  std::vector<GridRectangle> truth_cells = {{0, 2, 7, 3, 8}, {0, 4, 8, 15, 18}};
  LinearObjective objective = objective_for(model.light(truth));
  int calls = 0;
  OpeningValues values_of = [this](const std::vector<GridRectangle>& rects) {
    ++calls;
    EXPECT_TRUE(std::is_sorted(rects.begin(), rects.end()));
    for (const GridRectangle& r : rects) {  // the records evaluate nothing beyond the panel's grid
      EXPECT_TRUE(r.row0 >= 0 && r.col0 >= 0 && r.row1 < d.panels()[0].rows && r.col1 < d.panels()[0].cols)
          << r.to_string();
    }
    return model.light(rects);
  };
  TwoOpenings() {
    c.min_width = c.min_height = 0.5;
    c.min_gap = 0.5;
  }
};

// How far a side may be interpolated: the constraints hold whatever every side does within its
// reach (half of a gap between two openings is each one's; the opposite side moves as far).
TEST(SideReach, KeepsEverySideWithinTheConstraints) {
  const OpeningDomain d = wall();  // 6 x 2.5 m, 0.25 m elements
  OpeningConstraints c;
  c.min_width = c.min_height = 0.5;
  c.min_gap = 0.5;
  c.margin = 0.2;
  // a: 1.0 m wide, its left side 0.25 m from the wall's edge; b: 0.625 m to its right (0.125 m of
  // slack over min_gap, 0.0625 m each).
  const std::vector<PanelRectangle> openings = {{0, 0.25, 1.25, 0.75, 1.75}, {0, 1.875, 2.375, 0.75, 1.75}};
  const double s = d.element_size();
  // a's left side: 0.05 m to the margin, so a quarter of the half element (0.03125 m) out.
  EXPECT_DOUBLE_EQ(side_reach(d, c, openings, 0, 0, true), 0.25 * kInterpolatedReach);
  // a's right side: 0.0625 m of its gap to b, a half of the half element.
  EXPECT_DOUBLE_EQ(side_reach(d, c, openings, 0, 1, true) * s, 0.0625);
  // Moving in, a's sides go the whole reach (1.0 m wide, 0.75 m at least left with both moved).
  EXPECT_DOUBLE_EQ(side_reach(d, c, openings, 0, 0, false), kInterpolatedReach);
  // b is 0.5 m wide, at min_width: its sides cannot move in, nor (conservatively: the size check
  // shrinks both axes) its bottom.
  EXPECT_DOUBLE_EQ(side_reach(d, c, openings, 1, 1, false), 0.0);
  EXPECT_DOUBLE_EQ(side_reach(d, c, openings, 1, 2, false), 0.0);
  // Every bound together keeps the two openings within the constraints.
  for (bool out : {true, false}) {
    std::vector<PanelRectangle> moved = openings;
    for (size_t i = 0; i < 2; ++i) {
      const double by[4] = {side_reach(d, c, openings, i, 0, out), side_reach(d, c, openings, i, 1, out),
                            side_reach(d, c, openings, i, 2, out), side_reach(d, c, openings, i, 3, out)};
      const double sign = out ? s : -s;
      moved[i].u0 -= sign * by[0], moved[i].u1 += sign * by[1], moved[i].v0 -= sign * by[2], moved[i].v1 += sign * by[3];
    }
    EXPECT_TRUE(constraint_violations(d, moved, c).empty()) << (out ? "out" : "in");
  }
}

// From openings misplaced by one or two elements, the descent brings every side within an element
// of the truth's, where the interpolated error is far below the start's and below the grid error
// of the truth's elements.
TEST(RefinableOpenings, BringsMisplacedOpeningsWithinAnElementOfTheTruth) {
  TwoOpenings t;
  ASSERT_EQ(t.d.panels().size(), 1u);
  const std::vector<GridRectangle> start = {{0, 1, 6, 4, 9}, {0, 3, 7, 12, 17}};
  ASSERT_TRUE(satisfies_all(t.d, start, t.c));
  const RefinableOpenings found = search_refinable_openings(t.d, t.c, {start}, t.values_of, t.objective, 0);
  ASSERT_EQ(found.rects.size(), 2u);
  EXPECT_GT(found.moves, 0);
  EXPECT_EQ(found.evaluations, t.calls);  // each set once
  EXPECT_LT(found.error, 0.05 * found.start_error);
  EXPECT_LT(found.error, prediction_error(t.objective, t.model.light(t.truth_cells)));
  for (size_t i = 0; i < 2; ++i) {
    const GridRectangle& r = found.rects[i];
    const FractionalLight::Box& b = t.truth[i];
    EXPECT_LE(std::abs(r.row0 - b.row0), 1.0) << r.to_string();
    EXPECT_LE(std::abs(r.row1 + 1 - b.row1), 1.0) << r.to_string();
    EXPECT_LE(std::abs(r.col0 - b.col0), 1.0) << r.to_string();
    EXPECT_LE(std::abs(r.col1 + 1 - b.col1), 1.0) << r.to_string();
  }
  // The same start and light give the same answer; an evaluation limit ends it early.
  const RefinableOpenings again = search_refinable_openings(t.d, t.c, {start}, t.values_of, t.objective, 0);
  EXPECT_EQ(again.rects, found.rects);
  EXPECT_EQ(again.error, found.error);
  const RefinableOpenings limited = search_refinable_openings(t.d, t.c, {start}, t.values_of, t.objective, 20);
  EXPECT_TRUE(limited.out_of_evaluations);
  EXPECT_EQ(limited.evaluations, 20);
  EXPECT_GE(limited.error, found.error);
}

// An opening the truth does not have, far from its light, is removed. (Light in proportion to the
// open area: the interpolation then holds but for the corners, and no other opening helps.)
TEST(RefinableOpenings, RemovesAnOpeningTheTruthHasNot) {
  TwoOpenings t;
  t.model.superlinear = false;
  t.objective = objective_for(t.model.light(t.truth));
  std::vector<GridRectangle> start = t.truth_cells;
  start.push_back({0, 8, 9, 22, 23});  // at the panel's corner: its sides cannot move out
  ASSERT_TRUE(satisfies_all(t.d, start, t.c));
  const RefinableOpenings found = search_refinable_openings(t.d, t.c, {start}, t.values_of, t.objective, 0);
  EXPECT_EQ(found.rects.size(), 2u);
  EXPECT_LT(found.error, found.start_error);
}

}  // namespace
}  // namespace fenestra
