// The exact search over whole openings (solve/opening_search.h) on scores with known minima.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "solve/opening_search.h"
#include "util/progress.h"
#include "test_scenes.h"

namespace fenestra {
namespace {

// Two panels: a 5 x 2.5 m wall (y = 0) and a 4 x 3 m flat roof at z = 3, both of 0.25 m elements.
OpeningDomain wall_and_roof() {
  return test::domain_of_quads({{Vec3(0, 0, 0), Vec3(5, 0, 0), Vec3(5, 0, 2.5f), Vec3(0, 0, 2.5f)},
                                {Vec3(0, 1, 3), Vec3(0, 4, 3), Vec3(4, 4, 3), Vec3(4, 1, 3)}},
                               0.25f);
}

int panel_of_rows(const OpeningDomain& d, int rows) {
  for (size_t p = 0; p < d.panels().size(); ++p)
    if (d.panels()[p].rows == rows) return static_cast<int>(p);
  return -1;
}

// Light at sensors that grows faster than an opening's area (as through a thick wall, where
// elements opened together pass more than apart): a linear model misjudges it, the search scores
// it as it is. Sensors sit on a grid over each panel; each element of an opening lights them by
// one over their squared distance (in elements, plus 1), times the square root of the opening's
// area.
struct SuperlinearLight {
  const OpeningDomain& domain;
  std::vector<std::array<double, 3>> sensors;  // panel, row, column

  explicit SuperlinearLight(const OpeningDomain& d) : domain(d) {
    for (size_t p = 0; p < d.panels().size(); ++p)
      for (int r = 0; r < d.panels()[p].rows; r += 2)
        for (int c = 0; c < d.panels()[p].cols; c += 2) sensors.push_back({double(p), double(r), double(c)});
  }
  std::vector<double> light(const std::vector<GridRectangle>& rects) const {
    std::vector<double> v(sensors.size(), 0.0);
    for (const GridRectangle& r : rects) {
      const double gain = std::sqrt(double(r.element_count()));
      for (size_t i = 0; i < sensors.size(); ++i) {
        if (sensors[i][0] != r.panel) continue;
        for (int row = r.row0; row <= r.row1; ++row)
          for (int col = r.col0; col <= r.col1; ++col) {
            const double dr = sensors[i][1] - row, dc = sensors[i][2] - col;
            v[i] += gain / (dr * dr + dc * dc + 1.0);
          }
      }
    }
    return v;
  }
};

OpeningConstraints automatic_like() {
  OpeningConstraints c;
  c.min_width = c.min_height = 0.5;
  c.min_gap = 0.5;
  c.margin = 0.2;
  return c;
}

TEST(OpeningSearch, FindsThreeOpeningsFromStartsThatMissOneAndMisplaceTheOthers) {
  const OpeningDomain d = wall_and_roof();
  const int wall = panel_of_rows(d, 10), roof = 1 - wall;
  ASSERT_GE(wall, 0);
  const OpeningConstraints c = automatic_like();
  const std::vector<GridRectangle> truth = {{wall, 2, 7, 2, 6}, {wall, 3, 6, 12, 16}, {roof, 4, 8, 5, 8}};
  ASSERT_TRUE(satisfies_all(d, truth, c));
  const SuperlinearLight model(d);
  const std::vector<double> goal = model.light(truth);
  int calls = 0;
  std::set<std::vector<GridRectangle>> scored;
  const OpeningScore score = [&](const std::vector<GridRectangle>& rects) {
    ++calls;
    EXPECT_TRUE(satisfies_all(d, rects, c));
    EXPECT_TRUE(std::is_sorted(rects.begin(), rects.end()));
    EXPECT_TRUE(scored.insert(rects).second) << "a set scored twice";
    const std::vector<double> v = model.light(rects);
    double e = 0.0, g = 0.0;
    for (size_t i = 0; i < v.size(); ++i) e += (v[i] - goal[i]) * (v[i] - goal[i]), g += goal[i] * goal[i];
    return e / g;
  };
  // One start lacks the roof's opening and has the wall's too small and shifted, plus a small
  // extra one; another holds only a roof opening too large and off to the side.
  const std::vector<std::vector<GridRectangle>> starts = {
      {{wall, 3, 6, 3, 5}, {wall, 2, 5, 13, 16}, {wall, 2, 3, 9, 10}},
      {{roof, 2, 9, 6, 11}},
  };
  const OpeningSearchResult r = search_whole_openings(d, c, starts, score, 0);
  std::vector<GridRectangle> sorted_truth = truth;
  std::sort(sorted_truth.begin(), sorted_truth.end());
  EXPECT_EQ(r.rects, sorted_truth);
  EXPECT_LT(r.score, 1e-12);
  EXPECT_GT(r.start_score, 0.05);
  EXPECT_EQ(r.evaluations, calls);
  EXPECT_GT(r.moves, 3);
  EXPECT_FALSE(r.out_of_evaluations);
}

TEST(OpeningSearch, StopsAtItsEvaluationLimitWithTheBestSoFar) {
  const OpeningDomain d = wall_and_roof();
  const int wall = panel_of_rows(d, 10);
  const OpeningConstraints c = automatic_like();
  const SuperlinearLight model(d);
  const std::vector<double> goal = model.light({{wall, 2, 7, 2, 6}});
  int calls = 0;
  const OpeningScore score = [&](const std::vector<GridRectangle>& rects) {
    ++calls;
    const std::vector<double> v = model.light(rects);
    double e = 0.0;
    for (size_t i = 0; i < v.size(); ++i) e += (v[i] - goal[i]) * (v[i] - goal[i]);
    return e;
  };
  Progress progress;
  progress.start("searching", 25);
  const OpeningSearchResult r = search_whole_openings(d, c, {{{wall, 5, 6, 12, 13}}}, score, 25, &progress);
  EXPECT_EQ(calls, 25);
  EXPECT_DOUBLE_EQ(progress.fraction(), 1.0);  // one step per set scored
  EXPECT_EQ(r.evaluations, 25);
  EXPECT_TRUE(r.out_of_evaluations);
  EXPECT_LE(r.score, r.start_score);
  EXPECT_TRUE(satisfies_all(d, r.rects, c));
}

TEST(OpeningSearch, SkipsStartsThatBreakTheConstraints) {
  const OpeningDomain d = wall_and_roof();
  const int wall = panel_of_rows(d, 10);
  const OpeningConstraints c = automatic_like();
  int calls = 0;
  const OpeningScore score = [&](const std::vector<GridRectangle>&) { return double(++calls); };
  // Inside the margin, and a single element (below min_width): neither is scored.
  const OpeningSearchResult r =
      search_whole_openings(d, c, {{{wall, 0, 3, 0, 3}}, {{wall, 4, 4, 4, 4}}}, score, 0);
  EXPECT_EQ(calls, 0);
  EXPECT_TRUE(r.rects.empty());
  EXPECT_TRUE(std::isinf(r.score));
  EXPECT_EQ(r.best_start, -1);
}

TEST(OpeningSearch, SameStartsAndScoreGiveTheSameAnswer) {
  const OpeningDomain d = wall_and_roof();
  const int wall = panel_of_rows(d, 10), roof = 1 - wall;
  const OpeningConstraints c = automatic_like();
  const SuperlinearLight model(d);
  const std::vector<double> goal = model.light({{wall, 3, 8, 4, 9}, {roof, 2, 5, 2, 7}});
  const OpeningScore score = [&](const std::vector<GridRectangle>& rects) {
    const std::vector<double> v = model.light(rects);
    double e = 0.0;
    for (size_t i = 0; i < v.size(); ++i) e += std::abs(v[i] - goal[i]);
    return e;
  };
  const std::vector<std::vector<GridRectangle>> starts = {{{wall, 2, 4, 12, 14}}, {{roof, 6, 9, 6, 9}}};
  const OpeningSearchResult a = search_whole_openings(d, c, starts, score, 0);
  const OpeningSearchResult b = search_whole_openings(d, c, starts, score, 0);
  EXPECT_EQ(a.rects, b.rects);
  EXPECT_EQ(a.score, b.score);
  EXPECT_EQ(a.evaluations, b.evaluations);
  EXPECT_LT(a.score, a.start_score);
}

// A bound below every score (here the score less a tenth) rules out moves that cannot gain before
// they are scored: the search takes the same steps to the same answer, considering the same sets,
// and scores fewer of them.
TEST(OpeningSearch, ABoundBelowTheScoreGivesTheSameAnswerFromFewerScores) {
  const OpeningDomain d = wall_and_roof();
  const int wall = panel_of_rows(d, 10), roof = 1 - wall;
  const OpeningConstraints c = automatic_like();
  const SuperlinearLight model(d);
  const std::vector<double> goal = model.light({{wall, 2, 7, 2, 6}, {wall, 3, 6, 12, 16}, {roof, 4, 8, 5, 8}});
  auto error = [&](const std::vector<GridRectangle>& rects) {
    const std::vector<double> v = model.light(rects);
    double e = 0.0;
    for (size_t i = 0; i < v.size(); ++i) e += (v[i] - goal[i]) * (v[i] - goal[i]);
    return e;
  };
  int calls = 0, bounds = 0;
  const OpeningScore score = [&](const std::vector<GridRectangle>& rects) { return ++calls, error(rects); };
  const OpeningBound bound = [&](const std::vector<GridRectangle>& rects) { return ++bounds, 0.9 * error(rects); };
  const std::vector<std::vector<GridRectangle>> starts = {{{wall, 3, 6, 3, 5}, {wall, 2, 5, 13, 16}},
                                                          {{roof, 2, 9, 6, 11}}};
  const OpeningSearchResult plain = search_whole_openings(d, c, starts, score, 0);
  const int plain_calls = std::exchange(calls, 0);
  EXPECT_EQ(plain.scored, plain_calls);
  EXPECT_EQ(plain.evaluations, plain_calls);
  const OpeningSearchResult bounded = search_whole_openings(d, c, starts, score, 0, nullptr, nullptr, bound);
  EXPECT_EQ(bounded.rects, plain.rects);
  EXPECT_EQ(bounded.score, plain.score);
  EXPECT_EQ(bounded.evaluations, plain.evaluations);
  EXPECT_EQ(bounded.moves, plain.moves);
  EXPECT_EQ(bounded.best_found_after, plain.best_found_after);
  EXPECT_EQ(bounded.scored, calls);
  EXPECT_LT(bounded.scored, plain.scored / 2);
  EXPECT_GT(bounds, 0);
  EXPECT_LE(bounds, bounded.evaluations);
}

// With a limit, the sets ruled out by the bound count against it as the scored ones do: the search
// stops where the search without a bound stops.
TEST(OpeningSearch, SetsRuledOutByTheBoundCountAgainstTheLimit) {
  const OpeningDomain d = wall_and_roof();
  const int wall = panel_of_rows(d, 10);
  const OpeningConstraints c = automatic_like();
  const SuperlinearLight model(d);
  const std::vector<double> goal = model.light({{wall, 2, 7, 2, 6}});
  auto error = [&](const std::vector<GridRectangle>& rects) {
    const std::vector<double> v = model.light(rects);
    double e = 0.0;
    for (size_t i = 0; i < v.size(); ++i) e += (v[i] - goal[i]) * (v[i] - goal[i]);
    return e;
  };
  const OpeningScore score = error;
  const OpeningBound bound = [&](const std::vector<GridRectangle>& rects) { return 0.9 * error(rects); };
  const std::vector<std::vector<GridRectangle>> starts = {{{wall, 3, 7, 3, 6}}};  // one step from the truth
  Progress progress;
  progress.start("searching", 40);
  const OpeningSearchResult bounded = search_whole_openings(d, c, starts, score, 40, &progress, nullptr, bound);
  const OpeningSearchResult plain = search_whole_openings(d, c, starts, score, 40);
  EXPECT_DOUBLE_EQ(progress.fraction(), 1.0);  // one step per set considered
  EXPECT_EQ(bounded.evaluations, 40);
  EXPECT_TRUE(bounded.out_of_evaluations);
  EXPECT_LT(bounded.scored, bounded.evaluations);
  EXPECT_EQ(bounded.rects, plain.rects);
  EXPECT_EQ(bounded.score, plain.score);
}

}  // namespace
}  // namespace fenestra
