#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include <tbb/global_control.h>

#include "scene/solver_settings.h"
#include "solve/genetic.h"
#include "util/progress.h"
#include "util/rng.h"

namespace fenestra {
namespace {

using State = std::vector<uint8_t>;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A 10 x 20 wall seen by sensors on a plane in front of it: each sensor receives from each
// element with a smooth (cos^4-like) falloff, so neighbouring columns of E are similar, as
// they are in a traced scene. The target is what a known mask of two rectangles gives.
struct Synthetic {
  ElementGrid grid = ElementGrid::rectangle(10, 20);
  LinearObjective objective;
  State truth;
};

State rectangles_mask(const ElementGrid& grid) {
  State mask(grid.size(), 0);
  for (int k = 0; k < grid.size(); ++k) {
    const auto& c = grid.cell(k);
    const bool first = c.row >= 2 && c.row <= 5 && c.col >= 3 && c.col <= 8;
    const bool second = c.row >= 4 && c.row <= 8 && c.col >= 12 && c.col <= 17;
    mask[k] = first || second;
  }
  return mask;
}

Eigen::VectorXd as_vector(const State& s) {
  Eigen::VectorXd v(s.size());
  for (size_t k = 0; k < s.size(); ++k) v[k] = s[k];
  return v;
}

Synthetic synthetic_problem() {
  Synthetic p;
  const int sensors = 60;
  Eigen::MatrixXd E(sensors, p.grid.size());
  for (int s = 0; s < sensors; ++s) {
    const double x = 1.0 + 18.0 * (s % 10) / 9.0, y = 1.0 + 8.0 * (s / 10) / 5.0, depth = 2.0 + (s % 3);
    for (int k = 0; k < p.grid.size(); ++k) {
      const double dx = p.grid.cell(k).col - x, dy = p.grid.cell(k).row - y;
      const double cosine2 = depth * depth / (depth * depth + dx * dx + dy * dy);
      E(s, k) = 0.01 * cosine2 * cosine2;
    }
  }
  p.truth = rectangles_mask(p.grid);
  p.objective.E = E;
  p.objective.target = E * as_vector(p.truth);
  // Relative mean squared error: 1e-4 is a 1% RMS error.
  p.objective.weight = (1.0 / (sensors * p.objective.target.array().square())).matrix();
  p.objective.lower = Eigen::VectorXd::Constant(sensors, -kInfinity);
  p.objective.upper = Eigen::VectorXd::Constant(sensors, kInfinity);
  return p;
}

// Relative RMS error of E o against the target.
double relative_rms(const LinearObjective& objective, const State& open) {
  const Eigen::VectorXd p = objective.E * as_vector(open);
  return std::sqrt(((p - objective.target).array() / objective.target.array()).square().mean());
}

State flip_fraction(const State& s, double fraction, uint64_t seed) {
  State out = s;
  Rng rng(seed, 7);
  for (auto& bit : out)
    if (rng.uniform() < fraction) bit ^= 1;
  return out;
}

// The default weights: small against a 1% RMS error (1e-4) yet decisive between equally good fits.
ShapeWeights recommended_shape() { return ShapeWeights{}; }

State mask_from(const ElementGrid& grid, const std::vector<std::pair<int, int>>& open_cells) {
  State mask(grid.size(), 0);
  for (const auto& [row, col] : open_cells) mask[grid.at(0, row, col)] = 1;
  return mask;
}

TEST(GeneticShape, CountsHandMadeMasks) {
  const ElementGrid grid = ElementGrid::rectangle(5, 6);
  {
    const ShapeCounts c = shape_counts(grid, State(grid.size(), 0));
    EXPECT_EQ(c.isolated, 0);
    EXPECT_EQ(c.boundary, 0);
    EXPECT_EQ(c.regions, 0);
  }
  {  // One element inside, one in a corner (missing neighbours count as closed).
    const ShapeCounts c = shape_counts(grid, mask_from(grid, {{2, 2}, {0, 5}}));
    EXPECT_EQ(c.isolated, 2);
    EXPECT_EQ(c.boundary, 8);
    EXPECT_EQ(c.regions, 2);
  }
  {  // Diagonal pair: N-8 neighbours, one region, not isolated, no shared edge.
    const ShapeCounts c = shape_counts(grid, mask_from(grid, {{1, 1}, {2, 2}}));
    EXPECT_EQ(c.isolated, 0);
    EXPECT_EQ(c.boundary, 8);
    EXPECT_EQ(c.regions, 1);
  }
  {  // A 2 x 3 block (perimeter 10) and a lone element.
    const ShapeCounts c = shape_counts(grid, mask_from(grid, {{0, 0}, {0, 1}, {0, 2}, {1, 0}, {1, 1}, {1, 2}, {4, 5}}));
    EXPECT_EQ(c.isolated, 1);
    EXPECT_EQ(c.boundary, 14);
    EXPECT_EQ(c.regions, 2);
  }
  {  // A ring: one region with a hole; the hole's edges count.
    const ShapeCounts c =
        shape_counts(grid, mask_from(grid, {{1, 1}, {1, 2}, {1, 3}, {2, 1}, {2, 3}, {3, 1}, {3, 2}, {3, 3}}));
    EXPECT_EQ(c.isolated, 0);
    EXPECT_EQ(c.boundary, 16);
    EXPECT_EQ(c.regions, 1);
  }
  {  // The whole wall: its outline only.
    const ShapeCounts c = shape_counts(grid, State(grid.size(), 1));
    EXPECT_EQ(c.boundary, 2 * (5 + 6));
    EXPECT_EQ(c.regions, 1);
  }
}

TEST(GeneticShape, PanelsDoNotTouch) {
  // Two panels whose cells share coordinates: adjacent cells of different panels are not neighbours.
  const ElementGrid grid({{0, 0, 0}, {0, 0, 1}, {1, 0, 2}, {1, 1, 2}});
  const ShapeCounts c = shape_counts(grid, {0, 1, 1, 0});
  EXPECT_EQ(c.isolated, 2);
  EXPECT_EQ(c.boundary, 8);
  EXPECT_EQ(c.regions, 2);
}

TEST(GeneticShape, FitnessAddsWeightedCounts) {
  const Synthetic p = synthetic_problem();
  const State state = flip_fraction(p.truth, 0.1, 3);
  const ShapeWeights shape{0.5, 0.25, 2.0};
  const ShapeCounts c = shape_counts(p.grid, state);
  EXPECT_NEAR(fitness(p.objective, p.grid, shape, state),
              objective_error(p.objective, state) + 0.5 * c.isolated + 0.25 * c.boundary + 2.0 * c.regions, 1e-12);
  EXPECT_EQ(objective_error(p.objective, p.truth), 0.0);
}

TEST(GeneticObjective, BoundPenalty) {
  Synthetic p = synthetic_problem();
  const State state = p.truth;  // exactly on target: only the bound can cost anything
  const Eigen::VectorXd predicted = p.objective.E * as_vector(state);
  ASSERT_EQ(objective_error(p.objective, state), 0.0);
  p.objective.upper[7] = 0.8 * predicted[7];
  p.objective.lower[11] = 1.1 * predicted[11];
  p.objective.bound_weight = 10.0;
  const double over = 0.2 * predicted[7], under = 0.1 * predicted[11];
  EXPECT_NEAR(objective_error(p.objective, state),
              10.0 * (p.objective.weight[7] * over * over + p.objective.weight[11] * under * under), 1e-15);
  p.objective.upper[7] = kInfinity;
  p.objective.lower[11] = 1.0 * predicted[11];  // touching a bound costs nothing
  EXPECT_EQ(objective_error(p.objective, state), 0.0);
}

TEST(GeneticObjective, TightUpperBoundsLowerTheSolution) {
  Synthetic p = synthetic_problem();
  GeneticSettings settings;
  settings.generations = 150;
  settings.shape = recommended_shape();
  const std::vector<State> seeds{p.truth};
  const GeneticResult free = run_genetic(p.objective, p.grid, seeds, settings);
  p.objective.upper = 0.8 * p.objective.target;
  const GeneticResult bounded = run_genetic(p.objective, p.grid, seeds, settings);
  EXPECT_GT(fitness(p.objective, p.grid, settings.shape, free.best), bounded.best_fitness);
  const double free_light = (p.objective.E * as_vector(free.best)).sum();
  const double bounded_light = (p.objective.E * as_vector(bounded.best)).sum();
  EXPECT_LT(bounded_light, 0.95 * free_light);
  EXPECT_NEAR(bounded.best_fitness, fitness(p.objective, p.grid, settings.shape, bounded.best),
              1e-9 * bounded.best_fitness);
}

TEST(GeneticSearch, IncrementalScoreMatchesReference) {
  const Synthetic p = synthetic_problem();
  for (bool polish : {false, true}) {
    GeneticSettings settings;
    settings.generations = 200;
    settings.polish = polish;
    settings.shape = {3e-4, 1e-4, 2e-4};  // large enough for the shape terms to matter
    const GeneticResult r = run_genetic(p.objective, p.grid, {flip_fraction(p.truth, 0.15, 1)}, settings);
    const double reference = fitness(p.objective, p.grid, settings.shape, r.best);
    EXPECT_NEAR(r.best_fitness, reference, 1e-9 * reference) << "polish " << polish;
    if (!polish) EXPECT_EQ(r.best_fitness, r.history.back().best);
  }
}

TEST(GeneticSearch, PanelsWithMissingElements) {
  // Two panels, the first with a hole and offset indices: crossover blocks and side moves meet
  // missing elements, and the incremental score must still match.
  std::vector<ElementGrid::Cell> cells;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 8; ++c)
      if (!(r >= 2 && r <= 3 && c >= 3 && c <= 5)) cells.push_back({3, r + 10, c - 4});
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 5; ++c) cells.push_back({0, r, c});
  const ElementGrid grid(cells);
  LinearObjective objective;
  const int sensors = 30;
  objective.E = (Eigen::MatrixXd::Random(sensors, grid.size()).array() + 1.0).matrix() * 0.01;
  State truth(grid.size(), 0);
  for (int k = 0; k < 12; ++k) truth[k] = 1;
  objective.target = objective.E * as_vector(truth);
  objective.weight = Eigen::VectorXd::Constant(sensors, 1.0);
  objective.upper = 1.05 * objective.target;
  GeneticSettings settings;
  settings.generations = 200;
  settings.shape = {1e-4, 3e-5, 2e-4};
  const GeneticResult r = run_genetic(objective, grid, {State(grid.size(), 1)}, settings);
  const double reference = fitness(objective, grid, settings.shape, r.best);
  EXPECT_NEAR(r.best_fitness, reference, 1e-9 * reference);
  EXPECT_LT(r.best_fitness, fitness(objective, grid, settings.shape, State(grid.size(), 1)));
}

TEST(GeneticSearch, ReproducibleWhateverTheThreadCount) {
  const Synthetic p = synthetic_problem();
  GeneticSettings settings;
  settings.generations = 100;
  settings.seed = 42;
  settings.shape = recommended_shape();
  const std::vector<State> seeds{flip_fraction(p.truth, 0.15, 2), State(p.grid.size(), 0)};
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return run_genetic(p.objective, p.grid, seeds, settings);
  };
  const GeneticResult one = run(1), two = run(2), again = run(2);
  for (const GeneticResult* other : {&two, &again}) {
    EXPECT_EQ(one.best, other->best);
    EXPECT_EQ(one.best_fitness, other->best_fitness);
    EXPECT_EQ(one.elite, other->elite);
    ASSERT_EQ(one.history.size(), other->history.size());
    for (size_t g = 0; g < one.history.size(); ++g) {
      EXPECT_EQ(one.history[g].best, other->history[g].best) << g;
      EXPECT_EQ(one.history[g].mean, other->history[g].mean) << g;
    }
  }
  settings.seed = 43;
  EXPECT_NE(run_genetic(p.objective, p.grid, seeds, settings).history.back().mean, one.history.back().mean);
}

TEST(GeneticSearch, HistoryAndElite) {
  const Synthetic p = synthetic_problem();
  GeneticSettings settings;
  settings.generations = 300;
  settings.shape = recommended_shape();
  const GeneticResult r = run_genetic(p.objective, p.grid, {flip_fraction(p.truth, 0.2, 5)}, settings);
  ASSERT_EQ(r.generations, 300);
  ASSERT_EQ(r.history.size(), 300u);
  for (size_t g = 0; g < r.history.size(); ++g) {
    EXPECT_EQ(r.history[g].generation, static_cast<int>(g));
    EXPECT_LE(r.history[g].best, r.history[g].mean);
    if (g > 0) {
      EXPECT_LE(r.history[g].best, r.history[g - 1].best) << g;
      EXPECT_GE(r.history[g].seconds, r.history[g - 1].seconds);
    }
  }
  EXPECT_LE(r.best_fitness, r.history.back().best);
  ASSERT_EQ(r.elite.size(), static_cast<size_t>(settings.elite));
  EXPECT_EQ(r.elite.front(), r.best);
  EXPECT_EQ(std::set<State>(r.elite.begin(), r.elite.end()).size(), r.elite.size());
  for (size_t i = 1; i < r.elite.size(); ++i)
    EXPECT_LE(fitness(p.objective, p.grid, settings.shape, r.elite[i - 1]),
              fitness(p.objective, p.grid, settings.shape, r.elite[i]) * (1 + 1e-12));
}

TEST(GeneticSearch, LongRunsKeepAThinnedHistory) {
  const Synthetic p = synthetic_problem();
  GeneticSettings settings;
  settings.generations = 5000;
  settings.population = 4;
  const GeneticResult r = run_genetic(p.objective, p.grid, {flip_fraction(p.truth, 0.2, 5)}, settings);
  ASSERT_EQ(r.generations, 5000);
  EXPECT_LE(r.history.size(), kMaxHistory);
  EXPECT_GE(r.history.size(), kMaxHistory / 2);
  EXPECT_EQ(r.history.front().generation, 0);
  EXPECT_EQ(r.history.back().generation, 4999);  // the last generation is always there
  // Evenly spread: one stride between all records but the last.
  const int stride = r.history[1].generation - r.history[0].generation;
  EXPECT_EQ(stride, 4);
  for (size_t g = 1; g + 1 < r.history.size(); ++g) {
    EXPECT_EQ(r.history[g].generation - r.history[g - 1].generation, stride) << g;
    EXPECT_LE(r.history[g].best, r.history[g - 1].best) << g;
  }
}

TEST(GeneticSearch, RecoversRectanglesFromNoisySeed) {
  const Synthetic p = synthetic_problem();
  const State seed = flip_fraction(p.truth, 0.15, 11);
  GeneticSettings settings;
  settings.shape = recommended_shape();
  const double seed_error = relative_rms(p.objective, seed);
  for (bool polish : {false, true}) {
    settings.polish = polish;
    const GeneticResult r = run_genetic(p.objective, p.grid, {seed}, settings);
    const double error = relative_rms(p.objective, r.best);
    int wrong = 0;
    for (size_t k = 0; k < seed.size(); ++k) wrong += r.best[k] != p.truth[k];
    RecordProperty(polish ? "polished" : "unpolished", std::to_string(error) + " " + std::to_string(wrong));
    EXPECT_LT(error, 0.02) << "seed error " << seed_error << ", wrong elements " << wrong;
    EXPECT_LT(error, 0.1 * seed_error);
  }
}

TEST(GeneticSearch, RecoversRectanglesFromClosedWall) {
  const Synthetic p = synthetic_problem();
  GeneticSettings settings;
  settings.shape = recommended_shape();
  const GeneticResult r = run_genetic(p.objective, p.grid, {State(p.grid.size(), 0)}, settings);
  EXPECT_LT(relative_rms(p.objective, r.best), 0.02);
  EXPECT_LE(shape_counts(p.grid, r.best).regions, 3);
}

TEST(GeneticSearch, ShapeDecidesBetweenEqualFits) {
  // One sensor that sees every element alike: any 24 open elements fit exactly, and the shape
  // terms alone should pick one compact opening (a 4 x 6 or 5 x 5 less one has perimeter 20).
  const ElementGrid grid = ElementGrid::rectangle(10, 20);
  LinearObjective objective;
  objective.E = Eigen::MatrixXd::Constant(1, grid.size(), 0.01);
  objective.target = Eigen::VectorXd::Constant(1, 0.24);
  objective.weight = Eigen::VectorXd::Constant(1, 1.0 / (0.24 * 0.24));
  GeneticSettings settings;
  settings.shape = recommended_shape();
  const GeneticResult r = run_genetic(objective, grid, {flip_fraction(State(grid.size(), 0), 0.12, 4)}, settings);
  const ShapeCounts c = shape_counts(grid, r.best);
  EXPECT_LT(objective_error(objective, r.best), 1e-20);
  EXPECT_EQ(c.regions, 1);
  EXPECT_EQ(c.isolated, 0);
  EXPECT_LE(c.boundary, 22);
}

TEST(GeneticSearch, StopsOnTimeBudgetBetweenGenerations) {
  const Synthetic p = synthetic_problem();
  GeneticSettings settings;
  settings.generations = 1000000;
  settings.time_budget_s = 0.05;
  const GeneticResult r = run_genetic(p.objective, p.grid, {p.truth}, settings);
  EXPECT_GT(r.generations, 0);
  EXPECT_LT(r.generations, settings.generations);
  EXPECT_EQ(r.history.size(), static_cast<size_t>(r.generations));
  EXPECT_TRUE(r.out_of_time);  // the solve's stages say "time budget"
}

TEST(GeneticSearch, RunsOutOfGenerationsNotTimeWithinItsBudget) {
  const Synthetic p = synthetic_problem();
  GeneticSettings settings;
  settings.generations = 20;
  for (double budget : {0.0, 1e6}) {
    settings.time_budget_s = budget;
    const GeneticResult r = run_genetic(p.objective, p.grid, {p.truth}, settings);
    EXPECT_EQ(r.generations, 20);
    EXPECT_FALSE(r.out_of_time) << budget;
  }
}

TEST(GeneticSettingsFrom, TakesEachSolverSetting) {
  SolverSettings s;
  s.population = 17;
  s.generations = 23;
  s.seed = 29;
  s.time_budget_s = 3.5;
  s.elite = 5;
  s.isolated_weight = 0.25;
  s.boundary_weight = 0.125;
  s.regions_weight = 0.0625;
  const GeneticSettings ga = genetic_settings_from(s);
  EXPECT_EQ(ga.population, 17);
  EXPECT_EQ(ga.generations, 23);
  EXPECT_EQ(ga.seed, 29u);
  EXPECT_EQ(ga.time_budget_s, 3.5);
  EXPECT_EQ(ga.elite, 5);
  EXPECT_EQ(ga.shape.isolated, 0.25);
  EXPECT_EQ(ga.shape.boundary, 0.125);
  EXPECT_EQ(ga.shape.regions, 0.0625);
  EXPECT_TRUE(ga.polish);  // not a scene setting
}

TEST(GeneticSearch, Cancels) {
  const Synthetic p = synthetic_problem();
  Progress progress;
  progress.cancel();
  EXPECT_THROW(run_genetic(p.objective, p.grid, {p.truth}, GeneticSettings{}, &progress), Cancelled);
}

TEST(GeneticSearch, RejectsBadInput) {
  const Synthetic p = synthetic_problem();
  GeneticSettings settings;
  EXPECT_THROW(run_genetic(p.objective, p.grid, {}, settings), std::invalid_argument);
  EXPECT_THROW(run_genetic(p.objective, p.grid, {State(3, 0)}, settings), std::invalid_argument);
  LinearObjective wrong = p.objective;
  wrong.weight[0] = -1.0;
  EXPECT_THROW(run_genetic(wrong, p.grid, {p.truth}, settings), std::invalid_argument);
  settings.population = 1;
  EXPECT_THROW(run_genetic(p.objective, p.grid, {p.truth}, settings), std::invalid_argument);
}

}  // namespace
}  // namespace fenestra
