// The solver reads the path records only through RecordQueries, and every answer is per sensor:
// a study whose records are split into shards of sensors (as fenestra.distributed keeps them on
// its workers) gives the solver the same answers, and the solve the same result, bit for bit:
// with per-sensor goals, and with climate goals (hourly models and annual studies stacked from
// the shards').
#include <gtest/gtest.h>

#include <deque>
#include <memory>
#include <numeric>
#include <vector>

#include "annual/annual_contributions.h"
#include "annual/annual_cut_study.h"
#include "annual/annual_records.h"
#include "solve/climate_design.h"
#include "solve/goals.h"
#include "solve/record_queries.h"
#include "solve/solver.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"

namespace fenestra {
namespace {

using test::ObjBuilder;
using test::TempDir;

template <typename Part>
Eigen::VectorXd concatenated(const std::vector<Part>& parts, Eigen::Index size) {
  Eigen::VectorXd out(size);
  Eigen::Index at = 0;
  for (const Part& p : parts) {
    out.segment(at, p.size()) = p;
    at += p.size();
  }
  return out;
}

class ShardedRegions : public RegionQueries {
 public:
  explicit ShardedRegions(std::vector<std::unique_ptr<RegionQueries>> shards) : shards_(std::move(shards)) {
    values_ = gather([](RegionQueries& s) { return s.values(); });
  }
  const Eigen::VectorXd& values() const override { return values_; }
  const std::vector<PanelRectangle>& rectangles() const override { return shards_.front()->rectangles(); }
  const Eigen::VectorXd& try_region(const std::vector<PanelRectangle>& candidate) override {
    tried_ = gather([&](RegionQueries& s) { return s.try_region(candidate); });
    return tried_;
  }
  void accept() override {
    for (auto& s : shards_) s->accept();
    values_ = tried_;
  }

 private:
  template <typename F>
  Eigen::VectorXd gather(F f) {
    std::vector<Eigen::VectorXd> parts;
    Eigen::Index n = 0;
    for (auto& s : shards_) n += parts.emplace_back(f(*s)).size();
    return concatenated(parts, n);
  }
  std::vector<std::unique_ptr<RegionQueries>> shards_;
  Eigen::VectorXd values_, tried_;
};

// The records of blocks of sensors, each asked by its own LocalRecordQueries; the dense arrays
// (E, closed, ...) of the whole study without its records, as the client of a cluster holds them.
class ShardedRecords : public RecordQueries {
 public:
  ShardedRecords(const Scene& scene, const Contributions& whole, const std::vector<SensorRange>& blocks)
      : scene_(scene), blocks_(blocks) {
    summary_ = whole;
    summary_.records.assign(whole.records.size(), SensorRecord{});
    summary_.annual = nullptr;  // the client holds no sensor's records
    for (const SensorRange& b : blocks) shards_.push_back(compute_contributions(scene, nullptr, false, b));
    for (size_t i = 0; i < shards_.size(); ++i)
      local_.push_back(std::make_unique<LocalRecordQueries>(scene, shards_[i], nullptr, blocks[i]));
    if (scene.climate) annual_ = prepare_annual(scene);  // sources and hours: no sensor's records
  }
  const Contributions& contributions() const override { return summary_; }
  const SensorValues& exact(const std::vector<uint8_t>& open) override {
    ++exact_calls;
    return known_.emplace_back(pair([&](LocalRecordQueries& q) { return q.exact(open); }));
  }
  SensorValues evaluate(const std::vector<PanelRectangle>& region) override {
    return pair([&](LocalRecordQueries& q) { return q.evaluate(region); });
  }
  Eigen::MatrixXd flip_effects(const std::vector<uint8_t>& about) override {
    Eigen::MatrixXd D(summary_.E.rows(), summary_.E.cols());
    Eigen::Index at = 0;
    for (auto& q : local_) {
      const Eigen::MatrixXd part = q->flip_effects(about);
      D.middleRows(at, part.rows()) = part;
      at += part.rows();
    }
    return D;
  }
  std::unique_ptr<RegionQueries> region_search(const std::vector<PanelRectangle>& start) override {
    ++region_searches;
    std::vector<std::unique_ptr<RegionQueries>> parts;
    for (auto& q : local_) parts.push_back(q->region_search(start));
    return std::make_unique<ShardedRegions>(std::move(parts));
  }
  SensorValues cut(const std::vector<OpeningInput>& openings, int paths, uint64_t stream) override {
    ++cuts;
    std::vector<SensorValues> parts;
    for (const SensorRange& b : blocks_) parts.push_back(evaluate_openings(scene_, openings, nullptr, paths, b, stream));
    return join(parts);
  }
  double record_bytes() const override {
    double bytes = 0.0;
    for (auto& q : local_) bytes += q->record_bytes();
    return bytes;
  }
  std::shared_ptr<const AnnualRecords> annual() const override { return annual_; }
  // One shard of the model per block, each built from its own records, as a cluster's workers do.
  std::unique_ptr<ClimateModel> climate_model(const ClimateProblem& problem, const std::vector<uint8_t>& about,
                                              const std::vector<uint8_t>& excluded) override {
    ++climate_models;
    std::vector<std::unique_ptr<ClimateShard>> parts;
    for (auto& q : local_) parts.push_back(q->climate_shard(problem, about, excluded));
    return std::make_unique<LocalClimateModel>(*problem.objective, std::move(parts));
  }
  ClimateTally climate_tally(const ClimateProblem& problem, const std::vector<uint8_t>& open) override {
    ClimateTally sum = problem.objective->empty_tally();
    for (auto it = local_.rbegin(); it != local_.rend(); ++it) sum.add((*it)->climate_tally(problem, open));
    return sum;
  }
  AnnualStudy annual_study(const std::vector<PanelRectangle>& region) override {
    ++annual_studies;
    std::vector<AnnualRegionParts> parts;
    for (const Contributions& c : shards_) parts.push_back(annual_region_parts(c, OpenRegion(scene_.domain, region)));
    AnnualRegionParts whole = stack(parts);
    AnnualStudy study = annual_study_of(whole.coefficients, annual_, whole.occupied_mean);
    study.paths_per_sensor = summary_.paths_per_sensor;
    return study;
  }
  AnnualStudy annual_cut(const std::vector<OpeningInput>& openings, int paths) override {
    ++annual_cuts;
    std::vector<AnnualRegionParts> parts;
    AnnualCutCoefficients whole;
    for (const SensorRange& b : blocks_) {
      AnnualCutCoefficients part = annual_cut_coefficients(scene_, openings, nullptr, paths, b);
      parts.push_back({part.coefficients, part.occupied_mean});
      whole.paths_per_sensor = part.paths_per_sensor;
    }
    AnnualRegionParts stacked = stack(parts);
    whole.coefficients = stacked.coefficients;
    whole.occupied_mean = stacked.occupied_mean;
    return annual_cut_study_of(scene_, whole);
  }

  int exact_calls = 0, region_searches = 0, cuts = 0, climate_models = 0, annual_studies = 0, annual_cuts = 0;

 private:
  template <typename F>
  SensorValues pair(F f) {
    std::vector<SensorValues> parts;
    for (auto& q : local_) parts.push_back(f(*q));
    return join(parts);
  }
  AnnualRegionParts stack(const std::vector<AnnualRegionParts>& parts) const {
    AnnualRegionParts out;
    const Eigen::Index n = summary_.E.rows();
    out.coefficients.sources.resize(n, parts.front().coefficients.sources.cols());
    out.coefficients.direct.resize(n, parts.front().coefficients.direct.cols());
    std::vector<SensorValues> means;
    Eigen::Index at = 0;
    for (const AnnualRegionParts& p : parts) {
      const Eigen::Index rows = p.coefficients.sources.rows();
      out.coefficients.sources.middleRows(at, rows) = p.coefficients.sources;
      out.coefficients.direct.middleRows(at, rows) = p.coefficients.direct;
      means.push_back(p.occupied_mean);
      at += rows;
    }
    out.occupied_mean = join(means);
    return out;
  }
  SensorValues join(const std::vector<SensorValues>& parts) const {
    std::vector<Eigen::VectorXd> v, e;
    for (const SensorValues& p : parts) v.push_back(p.value), e.push_back(p.standard_error);
    const Eigen::Index n = summary_.E.rows();
    return {concatenated(v, n), concatenated(e, n)};
  }

  const Scene& scene_;
  std::vector<SensorRange> blocks_;
  Contributions summary_;
  std::vector<Contributions> shards_;
  std::vector<std::unique_ptr<LocalRecordQueries>> local_;
  std::deque<SensorValues> known_;  // references handed out stay valid
  std::shared_ptr<const AnnualRecords> annual_;
};

bool same(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && (a.array() == b.array()).all();
}

// A 4 x 3 x 2.5 m room, its south wall the opening domain (0.4 m elements), six sensors, goals
// that want about a third of the unobstructed light, and opening limits: every stage runs.
Scene solve_room(const TempDir& dir, const std::string& thickness = "") {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {4, 3, 2.5f}, [](const std::string& f) { return f == "south" ? "domain" : "grey"; });
  dir.write("scene.obj", obj.str());
  dir.write("scene.json", R"({"fenestra": 1, "geometry": "scene.obj",
    "materials": {"grey": {"reflectance": 0.6}, "domain": {"reflectance": 0.5}},
    "opening_domain": {"materials": ["domain"], "element_size": 0.4)" + thickness + R"(},
    "sensors": {"points": [[0.5, 0.6, 0.8], [2.0, 0.6, 0.8], [3.5, 0.6, 0.8], [0.5, 2.4, 0.8], [2.0, 2.4, 0.8],
                           [3.5, 2.4, 0.8]], "normals": [0, 0, 1]},
    "sky": {"type": "uniform", "radiance": 318.3},
    "render": {"paths_per_sensor": 256, "seed": 5},
    "goals": {"units": "normalized", "uniform": [{"sensors": "all", "level": 0.3}]},
    "solver": {"generations": 20, "population": 12, "seed": 2, "verify_paths": 64,
               "constraints": {"min_width": 0.6, "min_height": 0.8, "sill_min": 0.6}}})");
  return load_scene(dir.file("scene.json"));
}

TEST(RecordQueries, ASolveOnShardedRecordsEqualsTheWholeStudysBitForBit) {
  TempDir dir;
  const Scene scene = solve_room(dir);
  const Contributions whole = compute_contributions(scene);
  const SolveResult one = solve_openings(scene, whole);
  ShardedRecords sharded(scene, whole, {{0, 1}, {1, 4}, {4, 6}});
  const SolveResult many = solve_openings(scene, sharded);
  // The queries were used: exact values, edge searches, the check with real cutters.
  EXPECT_GT(sharded.exact_calls, 10);
  EXPECT_GT(sharded.region_searches, 0);
  EXPECT_GT(sharded.cuts, 0);
  ASSERT_FALSE(one.openings.empty());
  ASSERT_EQ(one.openings.size(), many.openings.size());
  for (size_t i = 0; i < one.openings.size(); ++i) EXPECT_TRUE(one.openings[i].parameter == many.openings[i].parameter);
  EXPECT_EQ(one.open, many.open);
  EXPECT_EQ(one.unconstrained_open, many.unconstrained_open);
  EXPECT_TRUE(same(one.predicted, many.predicted));
  EXPECT_TRUE(same(one.predicted_stderr, many.predicted_stderr));
  EXPECT_TRUE(same(one.verified_value, many.verified_value));
  EXPECT_EQ(one.fitness, many.fitness);
  EXPECT_EQ(one.edge_moves, many.edge_moves);
  ASSERT_EQ(one.tradeoffs.size(), many.tradeoffs.size());
  for (size_t i = 0; i < one.tradeoffs.size(); ++i) EXPECT_TRUE(same(one.tradeoffs[i].predicted, many.tradeoffs[i].predicted));
  EXPECT_EQ(one.warnings, many.warnings);
}

// In a 0.3 m wall the edges below the element size are searched with real cutters: on a cluster
// those are traced shard by shard too.
TEST(RecordQueries, AThickWallSolveOnShardedRecordsEqualsTheWholeStudysBitForBit) {
  TempDir dir;
  const Scene scene = solve_room(dir, R"(, "thickness": 0.3)");
  const Contributions whole = compute_contributions(scene);
  const SolveResult one = solve_openings(scene, whole);
  ShardedRecords sharded(scene, whole, {{0, 2}, {2, 5}, {5, 6}});
  const SolveResult many = solve_openings(scene, sharded);
  bool searched = false;
  for (const SolveStage& stage : one.stages)
    searched = searched || (stage.name == "thick-wall edges" && stage.stopped_because == stop_reason::kDone);
  EXPECT_TRUE(searched);
  EXPECT_GT(sharded.cuts, 1);  // the search's and the check's
  ASSERT_FALSE(one.openings.empty());
  ASSERT_EQ(one.openings.size(), many.openings.size());
  for (size_t i = 0; i < one.openings.size(); ++i) EXPECT_TRUE(one.openings[i].parameter == many.openings[i].parameter);
  EXPECT_TRUE(same(one.predicted, many.predicted));
  EXPECT_TRUE(same(one.verified_value, many.verified_value));
  EXPECT_EQ(one.fitness, many.fitness);
  EXPECT_EQ(one.edge_moves, many.edge_moves);
  EXPECT_EQ(one.warnings, many.warnings);
}

const std::string kChicago =
    std::string(FENESTRA_EXAMPLES) + "/weather/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw";

// A 3 x 4 x 2.5 m room lit by its south wall (0.5 m elements), six sensors, the Chicago year,
// climate goals that need part of the wall, verified with real cutters, with trade-offs.
Scene climate_room(const TempDir& dir) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {3, 4, 2.5f}, [](const std::string& f) { return f == "south" ? "glazing" : "wall"; });
  dir.write("scene.obj", obj.str());
  dir.write("scene.json", R"({"fenestra": 1, "geometry": "scene.obj",
    "materials": {"glazing": {"reflectance": 0.5}, "wall": {"reflectance": 0.5}},
    "opening_domain": {"materials": ["glazing"], "element_size": 0.5},
    "sensors": {"points": [[0.75, 0.75, 0.8], [2.25, 0.75, 0.8], [0.75, 2, 0.8], [2.25, 2, 0.8], [0.75, 3.25, 0.8],
                           [2.25, 3.25, 0.8]], "normals": [0, 0, 1]},
    "sky": {"type": "climate", "weather": ")" + kChicago + R"("},
    "goals": {"climate": [{"metric": "sda", "min_area_fraction": 0.5}, {"metric": "ase", "max_area_fraction": 0.2}],
              "least_glazing": true},
    "render": {"paths_per_sensor": 128, "max_bounces": 4, "seed": 5},
    "solver": {"generations": 12, "population": 10, "seed": 3, "verify": true, "verify_paths": 32,
               "tradeoffs": true}})");
  return load_scene(dir.file("scene.json"));
}

bool same_figures(const std::vector<ClimateFigure>& a, const std::vector<ClimateFigure>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (!(a[i].achieved == b[i].achieved)) return false;
  return true;
}

TEST(RecordQueries, ClimateModelsInShardsAnswerAsTheWholeStudysBitForBit) {
  TempDir dir;
  const Scene scene = climate_room(dir);
  const Contributions whole = compute_contributions(scene, nullptr, false);
  ShardedRecords sharded(scene, whole, {{0, 2}, {2, 3}, {3, 6}});
  LocalRecordQueries local(scene, whole, nullptr);
  const ClimateProblem problem = climate_problem(scene, whole, resolve_goals(scene, whole));
  ASSERT_GE(problem.rows.size(), 4u);
  std::vector<uint8_t> about(whole.element_count(), 0), excluded(whole.element_count(), 0);
  for (size_t k = 0; k < about.size(); k += 3) about[k] = 1;
  excluded[1] = 1;
  const auto a = local.climate_model(problem, about, excluded);
  const auto b = sharded.climate_model(problem, about, excluded);
  EXPECT_EQ(a->model_bytes() > 0.0, true);
  // A batch as the search sends it: states from the model's state, from a slot settled before them
  // in the batch, and in place.
  std::vector<ClimateRecipe> batch;
  for (int i = 0; i < 4; ++i) {
    ClimateRecipe r{i, i < 2 ? ClimateRecipe::kModelState : i - 2, about};
    for (size_t k = static_cast<size_t>(i); k < about.size(); k += 5) r.open[k] ^= 1;
    batch.push_back(r);
  }
  auto same = [&](const std::vector<ClimateTally>& x, const std::vector<ClimateTally>& y, const std::string& what) {
    ASSERT_EQ(x.size(), y.size()) << what;
    for (size_t i = 0; i < x.size(); ++i) {
      EXPECT_EQ(x[i].hours, y[i].hours) << what << " " << i;
      EXPECT_EQ(x[i].occupied_sum, y[i].occupied_sum) << what << " " << i;
      EXPECT_EQ(x[i].above_target, y[i].above_target) << what << " " << i;
      EXPECT_EQ(x[i].above_minimum, y[i].above_minimum) << what << " " << i;
      EXPECT_EQ(problem.objective->error(x[i], 1.0), problem.objective->error(y[i], 1.0)) << what << " " << i;
    }
  };
  same(a->settle(batch), b->settle(batch), "settled");
  std::vector<int> elements(whole.element_count());
  std::iota(elements.begin(), elements.end(), 0);
  same(a->flip_tallies(3, elements), b->flip_tallies(3, elements), "single flips");
  // A flip's tally is the tally of the state with that element flipped, settled anew.
  ClimateRecipe flipped{5, 3, batch[3].open};
  flipped.open[7] ^= 1;
  const std::vector<ClimateTally> direct = a->settle({flipped});
  same({a->flip_tallies(3, {7})[0]}, direct, "a flip against its state");
  // The exact years of a state.
  same({local.climate_tally(problem, batch[2].open)}, {sharded.climate_tally(problem, batch[2].open)}, "exact year");
  // A slot never settled, or two writes of one slot in a batch, are refused.
  EXPECT_THROW(a->flip_tallies(40, {0}), std::invalid_argument);
  EXPECT_THROW(a->settle({{9, 8, about}}), std::invalid_argument);
  EXPECT_THROW(a->settle({{1, ClimateRecipe::kModelState, about}, {1, 0, about}}), std::invalid_argument);
}

TEST(RecordQueries, AClimateSolveOnShardedRecordsEqualsTheWholeStudysBitForBit) {
  TempDir dir;
  const Scene scene = climate_room(dir);
  const Contributions whole = compute_contributions(scene);
  const SolveResult one = solve_openings(scene, whole);
  ShardedRecords sharded(scene, whole, {{0, 1}, {1, 4}, {4, 6}});
  const SolveResult many = solve_openings(scene, sharded);
  ASSERT_TRUE(one.climate.active);
  EXPECT_GE(sharded.climate_models, 2);  // about all closed, then about the best state
  EXPECT_GT(sharded.annual_studies, 0);
  EXPECT_EQ(sharded.annual_cuts, 1);
  ASSERT_FALSE(one.climate.achieved.empty());
  ASSERT_FALSE(one.climate.verified.empty());
  EXPECT_EQ(one.open, many.open);
  ASSERT_EQ(one.openings.size(), many.openings.size());
  for (size_t i = 0; i < one.openings.size(); ++i) EXPECT_TRUE(one.openings[i].parameter == many.openings[i].parameter);
  EXPECT_TRUE(same_figures(one.climate.element_figures, many.climate.element_figures));
  EXPECT_TRUE(same_figures(one.climate.all_open_figures, many.climate.all_open_figures));
  EXPECT_TRUE(same_figures(one.climate.achieved, many.climate.achieved));
  EXPECT_TRUE(same_figures(one.climate.verified, many.climate.verified));
  EXPECT_TRUE((one.climate.study->illuminance.total.array() == many.climate.study->illuminance.total.array()).all());
  EXPECT_TRUE(same(one.climate.study->occupied_mean.value, many.climate.study->occupied_mean.value));
  EXPECT_TRUE(
      (one.climate.verified_study->illuminance.total.array() == many.climate.verified_study->illuminance.total.array()).all());
  EXPECT_TRUE(same(one.climate.verified_study->occupied_mean.standard_error,
                   many.climate.verified_study->occupied_mean.standard_error));
  // The model's bytes over its shards: each shard stores an element's changes at its own sensors only.
  EXPECT_GT(many.climate.model_bytes, 0.0);
  EXPECT_LE(many.climate.model_bytes, 1.05 * one.climate.model_bytes);
  EXPECT_EQ(one.climate.linearisations, many.climate.linearisations);
  ASSERT_EQ(one.tradeoffs.size(), many.tradeoffs.size());
  for (size_t i = 0; i < one.tradeoffs.size(); ++i)
    EXPECT_TRUE(same_figures(one.tradeoffs[i].climate, many.tradeoffs[i].climate));
  EXPECT_EQ(one.fitness, many.fitness);
  EXPECT_EQ(one.warnings, many.warnings);
}

TEST(RecordQueries, AnAnnualStudyWithCuttersStackedFromRangesEqualsTheWholeOne) {
  TempDir dir;
  const Scene scene = climate_room(dir);
  const std::vector<OpeningInput> openings = {PanelRectangle{0, 0.5, 2.0, 0.5, 2.0}};
  const AnnualStudy whole = annual_study_with_cutters(scene, openings, nullptr, 16);
  AnnualCutCoefficients a = annual_cut_coefficients(scene, openings, nullptr, 16, {0, 4});
  const AnnualCutCoefficients b = annual_cut_coefficients(scene, openings, nullptr, 16, {4, 6});
  AnnualCutCoefficients stacked;
  stacked.paths_per_sensor = a.paths_per_sensor;
  stacked.coefficients.sources.resize(6, a.coefficients.sources.cols());
  stacked.coefficients.sources << a.coefficients.sources, b.coefficients.sources;
  stacked.coefficients.direct.resize(6, a.coefficients.direct.cols());
  stacked.coefficients.direct << a.coefficients.direct, b.coefficients.direct;
  stacked.occupied_mean.value.resize(6);
  stacked.occupied_mean.value << a.occupied_mean.value, b.occupied_mean.value;
  stacked.occupied_mean.standard_error.resize(6);
  stacked.occupied_mean.standard_error << a.occupied_mean.standard_error, b.occupied_mean.standard_error;
  const AnnualStudy parts = annual_cut_study_of(scene, stacked);
  EXPECT_GT(whole.illuminance.total.maxCoeff(), 0.0f);
  EXPECT_TRUE((whole.illuminance.total.array() == parts.illuminance.total.array()).all());
  EXPECT_TRUE((whole.illuminance.direct.array() == parts.illuminance.direct.array()).all());
  EXPECT_TRUE(same(whole.occupied_mean.value, parts.occupied_mean.value));
  EXPECT_TRUE(same(whole.occupied_mean.standard_error, parts.occupied_mean.standard_error));
  EXPECT_EQ(whole.paths_per_sensor, parts.paths_per_sensor);
  EXPECT_TRUE(parts.cutters);
  // Not every sensor: refused by name.
  EXPECT_THROW(annual_cut_study_of(scene, a), std::invalid_argument);
}

}  // namespace
}  // namespace fenestra
