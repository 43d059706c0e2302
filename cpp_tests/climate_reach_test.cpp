// The climate goals' hourly model's size, estimated before tracing (study/climate_reach.h),
// against the model the records then build.
#include <gtest/gtest.h>

#include <numeric>

#include "annual/annual_contributions.h"
#include "annual/annual_records.h"
#include "annual/hourly_flip_model.h"
#include "scene/scene.h"
#include "study/climate_reach.h"
#include "study/cost_model.h"
#include "trace/contributions.h"
#include "test_scenes.h"

namespace fenestra {
namespace {

using test::ObjBuilder;
using test::TempDir;

using test::kChicago;

// Two 3 x 4 x 2.5 m rooms side by side, 0.2 m apart, each lit by its south wall (the opening
// domain, 0.5 m elements), joined by a lined 1 x 2.1 m door or not; three sensors per room.
Scene two_rooms(const TempDir& dir, int paths, bool door) {
  ObjBuilder obj;
  const auto walls = [](const std::string& f) { return f == "south" ? "facade" : "wall"; };
  for (const float x0 : {0.0f, 3.2f}) {
    const float x1 = x0 + 3.0f;
    obj.quad("floor", "wall", {x0, 0, 0}, {x0, 4, 0}, {x1, 4, 0}, {x1, 0, 0});
    obj.quad("ceiling", "wall", {x0, 0, 2.5f}, {x1, 0, 2.5f}, {x1, 4, 2.5f}, {x0, 4, 2.5f});
    obj.quad("south", walls("south"), {x0, 0, 0}, {x1, 0, 0}, {x1, 0, 2.5f}, {x0, 0, 2.5f});
    obj.quad("north", "wall", {x0, 4, 0}, {x0, 4, 2.5f}, {x1, 4, 2.5f}, {x1, 4, 0});
    // The walls at x = 3 and x = 3.2 have the door at y in [1.5, 2.5], up to 2.1 m.
    for (const float x : {x0, x1}) {
      if (x == 0.0f || x == 6.2f || !door) {
        obj.quad("side", "wall", {x, 0, 0}, {x, 0, 2.5f}, {x, 4, 2.5f}, {x, 4, 0});
        continue;
      }
      obj.quad("side", "wall", {x, 0, 0}, {x, 0, 2.5f}, {x, 1.5f, 2.5f}, {x, 1.5f, 0});
      obj.quad("side", "wall", {x, 2.5f, 0}, {x, 2.5f, 2.5f}, {x, 4, 2.5f}, {x, 4, 0});
      obj.quad("side", "wall", {x, 1.5f, 2.1f}, {x, 1.5f, 2.5f}, {x, 2.5f, 2.5f}, {x, 2.5f, 2.1f});
    }
  }
  if (door) {
    obj.quad("jamb", "wall", {3, 1.5f, 0}, {3.2f, 1.5f, 0}, {3.2f, 1.5f, 2.1f}, {3, 1.5f, 2.1f});
    obj.quad("jamb", "wall", {3, 2.5f, 0}, {3, 2.5f, 2.1f}, {3.2f, 2.5f, 2.1f}, {3.2f, 2.5f, 0});
    obj.quad("head", "wall", {3, 1.5f, 2.1f}, {3.2f, 1.5f, 2.1f}, {3.2f, 2.5f, 2.1f}, {3, 2.5f, 2.1f});
    obj.quad("threshold", "wall", {3, 1.5f, 0}, {3, 2.5f, 0}, {3.2f, 2.5f, 0}, {3.2f, 1.5f, 0});
  }
  dir.write("scene.obj", obj.str());
  dir.write("scene.json", R"({"fenestra": 1, "geometry": "scene.obj",
    "materials": {"facade": {"reflectance": 0.5}, "wall": {"reflectance": 0.6}},
    "opening_domain": {"materials": ["facade"], "element_size": 0.5},
    "sensors": {"points": [[1, 1, 0.8], [2, 2, 0.8], [1, 3, 0.8], [4.2, 1, 0.8], [5.2, 2, 0.8], [4.2, 3, 0.8]],
                "normals": [0, 0, 1], "groups": {"west": [0, 1, 2], "east": [3, 4, 5]}},
    "sky": {"type": "climate", "weather": ")" + kChicago + R"("},
    "goals": {"climate": [{"metric": "sda", "sensors": "west", "min_area_fraction": 0.5},
                          {"metric": "ase", "sensors": "east", "max_area_fraction": 0.1}]},
    "render": {"paths_per_sensor": )" + std::to_string(paths) + R"(, "max_bounces": 6, "seed": 3}})");
  return load_scene(dir.file("scene.json"));
}

// Per row of the model, the elements whose flips it keeps.
std::vector<double> pairs_per_row(const HourlyFlipModel& m) {
  std::vector<double> out(m.rows.size(), 0.0);
  for (const FlipChange& f : m.flip_total)
    for (int32_t r : f.rows) out[r] += 1.0;
  return out;
}

struct Built {
  std::vector<double> estimate, pairs;
  double counted_bytes = 0.0, model_bytes = 0.0, direct_bytes = 0.0;
};

// The estimate, the model of every sensor's rows, and the bytes counted from the records before it.
Built build(const Scene& scene) {
  Built out;
  out.estimate = climate_reach(scene);
  const Contributions c = compute_contributions(scene);
  std::vector<int> rows(scene.sensors.size());
  std::iota(rows.begin(), rows.end(), 0);
  const HourlyColumns columns = hourly_columns(*c.annual, false);
  const HourlyFlipModel model = hourly_flip_model(c, std::vector<uint8_t>(c.element_count(), 0), rows, columns);
  out.pairs = pairs_per_row(model);
  double pairs = 0.0;
  for (size_t n : hourly_flip_model_reach(c, rows)) pairs += static_cast<double>(n);
  out.counted_bytes = hourly_flip_model_bytes(static_cast<double>(rows.size()), static_cast<double>(columns.hour.size()), pairs);
  out.model_bytes = static_cast<double>(model.memory_bytes());
  for (const auto& d : model.flip_direct) out.direct_bytes += static_cast<double>(sizeof(DirectChange) * d.capacity());
  return out;
}

TEST(ClimateReach, CoversClosedRoomsAndKnowsThemApart) {
  TempDir dir;
  const Built b = build(two_rooms(dir, 1024, false));
  for (size_t s = 0; s < b.pairs.size(); ++s) {
    // Each room's facade, 30 elements, is all in view and met; the other's is not.
    EXPECT_EQ(b.pairs[s], 30.0) << "sensor " << s;
    EXPECT_GE(b.estimate[s], b.pairs[s]) << "sensor " << s;
    EXPECT_LE(b.estimate[s], std::ceil(kClimateReachMargin * 30.0)) << "sensor " << s;
  }
}

TEST(ClimateReach, TheRecordsCountTheModelExactlyWhereLightPassesADoor) {
  TempDir dir;
  const Built b = build(two_rooms(dir, 1024, true));
  double met_beyond = 0.0;
  double estimated_beyond = 0.0;
  for (size_t s = 0; s < b.pairs.size(); ++s) {
    met_beyond += b.pairs[s] - 30.0;
    estimated_beyond += std::max(0.0, b.estimate[s] - std::ceil(kClimateReachMargin * 30.0));
  }
  // Light through the door meets the other room's facade more than the sensors see of it through
  // the door: the estimate is short here, and the records' count is what the model is checked by.
  EXPECT_GT(met_beyond, estimated_beyond);
  // What the records count before the model is built is what it holds, but the sun's own changes.
  EXPECT_EQ(b.counted_bytes, b.model_bytes - b.direct_bytes);
}

TEST(ClimateReach, ExcludedElementsAreLeftOutOfTheModelAndItsCount) {
  TempDir dir;
  const Scene scene = two_rooms(dir, 256, true);
  const Contributions c = compute_contributions(scene);
  std::vector<int> rows(scene.sensors.size());
  std::iota(rows.begin(), rows.end(), 0);
  const HourlyColumns columns = hourly_columns(*c.annual, false);
  std::vector<uint8_t> about(c.element_count(), 0), excluded(c.element_count(), 0);
  for (size_t k = 0; k < excluded.size(); k += 3) excluded[k] = 1;
  for (size_t k = 1; k < about.size(); k += 4) about[k] = !excluded[k];
  const HourlyFlipModel whole = hourly_flip_model(c, about, rows, columns);
  const HourlyFlipModel part = hourly_flip_model(c, about, rows, columns, nullptr, excluded);
  // The state is the same, bit for bit; the excluded elements' flips are gone, the others' the same
  // but for float rounding (the sky's product is blocked by the count of each row's flips).
  EXPECT_TRUE(part.total == whole.total);
  EXPECT_TRUE(part.direct == whole.direct);
  size_t pairs = 0;
  for (size_t k = 0; k < excluded.size(); ++k) {
    if (excluded[k]) {
      EXPECT_TRUE(part.flip_total[k].empty() && part.flip_direct[k].empty()) << "element " << k;
      continue;
    }
    EXPECT_EQ(part.flip_total[k].rows, whole.flip_total[k].rows) << "element " << k;
    const HourlyMatrix& a = part.flip_total[k].values;
    const HourlyMatrix& b = whole.flip_total[k].values;
    ASSERT_EQ(a.rows(), b.rows());
    const float scale = std::max(1e-3f, b.cwiseAbs().maxCoeff());
    EXPECT_LE((a - b).cwiseAbs().maxCoeff(), 1e-5f * scale) << "element " << k;
    pairs += part.flip_total[k].rows.size();
  }
  size_t counted = 0;
  for (size_t n : hourly_flip_model_reach(c, rows, excluded)) counted += n;
  EXPECT_EQ(counted, pairs);
}

TEST(ClimateReach, OnlyGoalSensorsAndNoClimateGoalsGiveNoRows) {
  TempDir dir;
  Scene scene = two_rooms(dir, 16, true);
  scene.sensors.climate_goals.goals.pop_back();  // the east room's goal
  const std::vector<double> estimate = climate_reach(scene);
  EXPECT_GT(estimate[0], 0.0);
  for (size_t s = 3; s < 6; ++s) EXPECT_EQ(estimate[s], 0.0) << "sensor " << s;
  scene.sensors.climate_goals.goals.clear();
  for (double e : climate_reach(scene)) EXPECT_EQ(e, 0.0);
}

}  // namespace
}  // namespace fenestra
