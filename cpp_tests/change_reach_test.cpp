// A cut need trace only the sensors a change of openings can reach (those whose records met an
// element near it); the others keep the values cut before it. Their paths never come near the
// change, so it leaves their light as it was, within the noise (their sky samples, aimed at every
// opening, are drawn anew). Two rooms with 0.3 m walls, each with one panel of the opening domain:
// the sensors of one room are not traced again for the other's change.
#include <gtest/gtest.h>

#include <sstream>
#include <vector>

#include "annual/annual_contributions.h"
#include "solve/cut_region_search.h"
#include "solve/change_reach.h"
#include "solve/record_queries.h"
#include "solve/thick_wall_edges.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"

namespace fenestra {
namespace {

using test::ObjBuilder;
using test::TempDir;

// Room A (0..3 x 0..3) opens south, room B (0..3 x 6..9) north; sensors 0, 1 in A and 2, 3 in B.
// With `ground`, light leaving one room may reach the other's facade off the ground.
Scene two_rooms(const TempDir& dir, bool ground, int paths) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {3, 3, 2.5f}, [](const std::string& f) { return f == "south" ? "facade" : "plaster"; });
  obj.box({0, 6, 0}, {3, 9, 2.5f}, [](const std::string& f) { return f == "north" ? "facade" : "plaster"; });
  if (ground) obj.quad("ground", "ground", {-20, -20, -0.01f}, {20, -20, -0.01f}, {20, 20, -0.01f}, {-20, 20, -0.01f});
  dir.write("scene.obj", obj.str());
  std::ostringstream s;
  s << R"({"fenestra": 1, "geometry": "scene.obj",
      "materials": {"plaster": {"reflectance": 0.6}, "facade": {"reflectance": 0.5}, "ground": {"reflectance": 0.3}},
      "opening_domain": {"materials": ["facade"], "element_size": 0.25, "thickness": 0.3},
      "sensors": {"points": [[1.5, 1.5, 0.8], [1, 2.2, 0.8], [1.5, 7.5, 0.8], [2, 6.8, 0.8]], "normals": [0, 0, 1]},
      "sky": {"type": "cie_overcast", "resolution": [64, 32]},
      "render": {"paths_per_sensor": )"
    << paths << R"(, "max_bounces": 6, "seed": 7}})";
  dir.write("scene.json", s.str());
  return load_scene(dir.file("scene.json"));
}

// The panel of the domain facing `sign` along y (-1: room A's south wall).
int panel_facing(const Scene& scene, float sign) {
  for (size_t p = 0; p < scene.domain.panels().size(); ++p)
    if (scene.domain.panels()[p].normal.y() * sign > 0.5f) return static_cast<int>(p);
  return -1;
}

std::vector<OpeningInput> inputs(const std::vector<PanelRectangle>& rects) { return {rects.begin(), rects.end()}; }

// The two rooms traced, with their records' queries; `a` and `b` their panels.
struct TwoRooms {
  TempDir dir;
  Scene scene;
  Contributions c;
  LocalRecordQueries records;
  int a, b;
  explicit TwoRooms(bool ground)
      : scene(two_rooms(dir, ground, 256)), c(compute_contributions(scene)), records(scene, c, nullptr),
        a(panel_facing(scene, -1.0f)), b(panel_facing(scene, 1.0f)) {}
};

TEST(ChangeReach, TheElementsNearAChangeAreThoseCoveredDifferentlyAndTheirNeighbours) {
  TwoRooms rooms(false);
  const OpeningDomain& domain = rooms.scene.domain;
  const PanelRectangle window{rooms.a, 1.0, 2.0, 0.75, 1.75};
  PanelRectangle wider = window;
  wider.u1 = 2.1;  // its right side into the next column, off the grid
  const std::vector<int32_t> near = elements_near_change(domain, {window}, {wider});
  ASSERT_FALSE(near.empty());
  for (int32_t k : near) {
    const Element& e = domain.elements()[static_cast<size_t>(k)];
    EXPECT_EQ(e.panel, rooms.a);
    EXPECT_GE(e.u1, 2.0 - 0.25 - 1e-6) << k;  // the column it covers, and one on either side
    EXPECT_LE(e.u0, 2.1 + 0.25 + 1e-6) << k;
    EXPECT_GE(e.v1, 0.75 - 0.25 - 1e-6) << k;  // its rows, and one above and below
    EXPECT_LE(e.v0, 1.75 + 0.25 + 1e-6) << k;
  }
  // The column the side moved into (four rows), the columns on either side, a row above and below.
  EXPECT_EQ(near.size(), 3u * 6u);
  EXPECT_TRUE(elements_near_change(domain, {window}, {window}).empty());
  EXPECT_TRUE(elements_near_change(domain, {window}, {PanelRectangle{rooms.a, 1.0, 2.0, 0.75, 1.75}}).empty());
}

TEST(ChangeReach, ARoomsSensorsAreNotReachedByTheOtherRoomsChange) {
  TwoRooms rooms(false);
  LocalRecordQueries& records = rooms.records;
  ASSERT_GE(rooms.a, 0);
  ASSERT_GE(rooms.b, 0);
  const std::vector<PanelRectangle> before = {{rooms.a, 1.0, 2.0, 0.75, 1.75}, {rooms.b, 1.0, 2.0, 0.75, 1.75}};
  std::vector<PanelRectangle> a_moved = before, b_moved = before, both = before;
  a_moved[0].v1 = both[0].v1 = 1.9;
  b_moved[1].u0 = both[1].u0 = 0.9;
  EXPECT_EQ(records.sensors_reached(before, a_moved), (std::vector<size_t>{0, 1}));
  EXPECT_EQ(records.sensors_reached(before, b_moved), (std::vector<size_t>{2, 3}));
  EXPECT_EQ(records.sensors_reached(before, both), (std::vector<size_t>{0, 1, 2, 3}));
  EXPECT_TRUE(records.sensors_reached(before, before).empty());
  // Not known (records elsewhere): every sensor.
  EXPECT_EQ(ChangeReach().sensors({0}, 4), (std::vector<size_t>{0, 1, 2, 3}));
}

// Whether two cuts of one sensor differ by more than their noise (four standard errors of the
// difference of independent cuts; theirs share every random number but those of the sky samples).
bool beyond_noise(const SensorValues& one, const SensorValues& two, Eigen::Index i) {
  return !test::within_sigma(one.value[i], one.standard_error[i], two.value[i], two.standard_error[i]);
}

// A cluster's worker keeps a shard's records only (its E, E_stderr and A go to the client): its
// records name the same sensors, or its cuts would trace others than one process's.
TEST(ChangeReach, RecordsWithoutTheirMatricesNameTheSameSensors) {
  TwoRooms rooms(true);
  const std::vector<PanelRectangle> before = {{rooms.a, 1.0, 2.0, 0.75, 1.75}, {rooms.b, 1.0, 2.0, 0.75, 1.75}};
  std::vector<PanelRectangle> after = before;
  after[1].u1 = 2.1;  // room B's window only
  const std::vector<size_t> whole = rooms.records.sensors_reached(before, after);
  ASSERT_FALSE(whole.empty());
  ASSERT_LT(whole.size(), 4u);
  Contributions records_only = rooms.c;
  for (Eigen::MatrixXd* m : {&records_only.E, &records_only.E_stderr, &records_only.A})
    *m = Eigen::MatrixXd(0, m->cols());
  LocalRecordQueries queries(rooms.scene, records_only, nullptr);
  EXPECT_EQ(queries.sensors_reached(before, after), whole);
}

TEST(ChangeReach, SensorsAChangeDoesNotReachKeepTheirLightWithinTheNoise) {
  for (bool ground : {false, true}) {
    TwoRooms rooms(ground);
    LocalRecordQueries& records = rooms.records;
    const int a = rooms.a, b = rooms.b;
    const std::vector<PanelRectangle> before = {{a, 1.0, 2.0, 0.75, 1.75}, {b, 1.0, 2.0, 0.75, 1.75}};
    std::vector<PanelRectangle> after = before;
    after[0] = {a, 0.9, 2.1, 0.6, 1.9};  // room A's window changed, off the element grid
    const SensorValues one = records.cut(inputs(before), kThickWallEdgeCutPaths, kThickWallEdgeCutStream);
    const SensorValues two = records.cut(inputs(after), kThickWallEdgeCutPaths, kThickWallEdgeCutStream);
    const std::vector<size_t> reached = records.sensors_reached(before, after);
    size_t changed = 0;
    for (Eigen::Index i = 0; i < one.value.size(); ++i) {
      const bool in_reach = std::find(reached.begin(), reached.end(), static_cast<size_t>(i)) != reached.end();
      if (!in_reach) EXPECT_FALSE(beyond_noise(one, two, i)) << "sensor " << i << (ground ? ", ground" : "");
      changed += beyond_noise(one, two, i);
    }
    EXPECT_GE(changed, 1u);  // the change is seen where it can be, beyond the noise
  }
}

TEST(ChangeReach, CutAtGivesTheWholeCutsValuesAtTheListedSensors) {
  TwoRooms rooms(true);
  LocalRecordQueries& records = rooms.records;
  const std::vector<PanelRectangle> rects = {{rooms.a, 1.0, 2.0, 0.75, 1.75}};
  const SensorValues all = records.cut(inputs(rects), 384, 3);
  const std::vector<size_t> listed = {3, 1};
  const SensorValues at = records.cut_at(inputs(rects), 384, 3, listed);
  ASSERT_EQ(at.value.size(), 2);
  for (size_t i = 0; i < listed.size(); ++i) {
    EXPECT_EQ(at.value[static_cast<Eigen::Index>(i)], all.value[static_cast<Eigen::Index>(listed[i])]);
    EXPECT_EQ(at.standard_error[static_cast<Eigen::Index>(i)], all.standard_error[static_cast<Eigen::Index>(listed[i])]);
  }
  // The interface's own (a whole cut, picked), as queries whose records are elsewhere answer.
  const SensorValues picked = records.RecordQueries::cut_at(inputs(rects), 384, 3, listed);
  for (size_t i = 0; i < listed.size(); ++i)
    EXPECT_EQ(picked.value[static_cast<Eigen::Index>(i)], all.value[static_cast<Eigen::Index>(listed[i])]);
  EXPECT_THROW(records.cut_at(inputs(rects), 384, 3, {4}), std::invalid_argument);
}

// Whether `values` are `whole`'s at the sensors `reached` and `kept`'s elsewhere, bit for bit.
bool cut_where_reached(const Eigen::VectorXd& values, const SensorValues& whole, const SensorValues& kept,
                       const std::vector<size_t>& reached) {
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    const bool in_reach = std::find(reached.begin(), reached.end(), static_cast<size_t>(i)) != reached.end();
    if (values[i] != (in_reach ? whole.value[i] : kept.value[i])) return false;
  }
  return true;
}

TEST(ChangeReach, ARegionSearchTracesOnlyTheSensorsAChangeReachesAndKeepsTheOthers) {
  TwoRooms rooms(true);
  LocalRecordQueries& records = rooms.records;
  const int a = rooms.a, b = rooms.b;
  const std::vector<PanelRectangle> start = {{a, 1.0, 2.0, 0.75, 1.75}, {b, 1.0, 2.0, 0.75, 1.75}};
  CutRegionSearch search(records, start, 256, kThickWallEdgeCutStream);
  const SensorValues at_start = search.current();
  std::vector<PanelRectangle> moved = start;
  moved[1].u1 = 2.1;  // room B's window only
  const std::vector<size_t> b_sensors = records.sensors_reached(start, moved);
  const Eigen::VectorXd tried = search.try_region(moved);
  const SensorValues whole = records.cut(inputs(moved), 256, kThickWallEdgeCutStream);
  EXPECT_TRUE(cut_where_reached(tried, whole, at_start, b_sensors));
  search.accept();
  const Eigen::VectorXd rough = search.rough_values(start);
  const SensorValues rough_moved = records.cut(inputs(moved), 128, kThickWallEdgeCutStream);
  const SensorValues rough_start = records.cut(inputs(start), 128, kThickWallEdgeCutStream);
  EXPECT_TRUE(cut_where_reached(rough, rough_start, rough_moved, b_sensors));
  // The start traced every sensor; the try and the rough cut only those B's change reaches (room
  // B's, unless the ground carried room A's paths to B's facade in the records), the current
  // rough cut every sensor.
  EXPECT_EQ(search.sensors_cut(), 4u * 4u);
  EXPECT_EQ(search.sensors_traced(), 4u + b_sensors.size() + 4u + b_sensors.size());
  EXPECT_LT(b_sensors.size(), 4u);
  // Handed on, the values of a cut of every sensor: the kept ones within the noise.
  const SensorValues kept = search.current();
  const SensorValues& handed = search.whole();
  EXPECT_TRUE((handed.value.array() == whole.value.array()).all());
  for (Eigen::Index i = 0; i < kept.value.size(); ++i) EXPECT_FALSE(beyond_noise(kept, handed, i)) << i;
  EXPECT_EQ(search.cuts(), 3);
  search.whole();  // already whole
  EXPECT_EQ(search.cuts(), 3);
}

}  // namespace
}  // namespace fenestra
