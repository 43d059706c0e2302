// The solver reads the path records only through RecordQueries, and every answer is per sensor:
// a study whose records are split into shards of sensors (as fenestra.distributed keeps them on
// its workers) gives the solver the same answers, and the solve the same result, bit for bit.
#include <gtest/gtest.h>

#include <deque>
#include <memory>
#include <vector>

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
    for (const SensorRange& b : blocks) shards_.push_back(compute_contributions(scene, nullptr, false, b));
    for (const Contributions& c : shards_)
      local_.push_back(std::make_unique<LocalRecordQueries>(scene, c, scene.domain, nullptr));
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
  SensorValues cut(const std::vector<OpeningInput>& openings, int paths) override {
    ++cuts;
    std::vector<SensorValues> parts;
    for (const SensorRange& b : blocks_) parts.push_back(evaluate_openings(scene_, openings, nullptr, paths, b));
    return join(parts);
  }
  double record_bytes() const override {
    double bytes = 0.0;
    for (auto& q : local_) bytes += q->record_bytes();
    return bytes;
  }

  int exact_calls = 0, region_searches = 0, cuts = 0;

 private:
  template <typename F>
  SensorValues pair(F f) {
    std::vector<SensorValues> parts;
    for (auto& q : local_) parts.push_back(f(*q));
    return join(parts);
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
};

bool same(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && (a.array() == b.array()).all();
}

// A 4 x 3 x 2.5 m room, its south wall the opening domain (0.4 m elements), six sensors, goals
// that want about a third of the unobstructed light, and opening limits: every stage runs.
Scene solve_room(const TempDir& dir) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {4, 3, 2.5f}, [](const std::string& f) { return f == "south" ? "domain" : "grey"; });
  dir.write("scene.obj", obj.str());
  dir.write("scene.json", R"({"fenestra": 1, "geometry": "scene.obj",
    "materials": {"grey": {"reflectance": 0.6}, "domain": {"reflectance": 0.5}},
    "opening_domain": {"materials": ["domain"], "element_size": 0.4},
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

}  // namespace
}  // namespace fenestra
