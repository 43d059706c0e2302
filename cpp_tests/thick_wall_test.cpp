// Thick walls: the exact evaluation from path records (elements as tubes through the wall, reveals
// where a closed neighbour lines an open one) against `evaluate` with the openings really cut.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>

#include "annual/annual_contributions.h"
#include "solve/catalogue_snap.h"
#include "solve/record_queries.h"
#include "solve/thick_wall_edges.h"
#include "solve/thick_wall_joint_edges.h"
#include "solve/thick_wall_merges.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"

namespace fenestra {
namespace {

using test::ObjBuilder;
using test::TempDir;
using test::within_sigma;

struct Wall {
  float thickness;     // meters
  float element_size;  // meters
  bool modelled;       // outer face and edge strips in the OBJ (else: thickness given, wall added)
  bool sun;            // Preetham sky with the sun at about 50 degrees to the wall's normal; else overcast
};

std::string describe(const Wall& w) {
  std::ostringstream s;
  s << w.thickness << " m wall, " << w.element_size << " m elements, " << (w.modelled ? "modelled solid" : "given")
    << ", " << (w.sun ? "sun" : "overcast");
  return s.str();
}

constexpr const char* kFourSensors = "[[1.5, 1, 0.8], [0.6, 2.4, 0.8], [2.4, 0.6, 0.8], [1.5, 2.5, 1.6]]";

// A 3 m x 3 m x 2.5 m room; its south wall (y = 0) is the domain, the wall's body lies at y < 0.
// `sensors`: their points (JSON), facing up.
Scene room(const TempDir& dir, const Wall& w, int paths, const std::string& sensors = kFourSensors) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {3, 3, 2.5f}, [](const std::string& f) { return f == "south" ? "facade" : "plaster"; });
  obj.quad("ground", "ground", {-20, -20, -0.01f}, {20, -20, -0.01f}, {20, 20, -0.01f}, {-20, 20, -0.01f});
  if (w.modelled) {
    const float t = -w.thickness;
    obj.quad("outer", "outside", {0, t, 0}, {0, t, 2.5f}, {3, t, 2.5f}, {3, t, 0});
    obj.quad("edge_bottom", "outside", {0, t, 0}, {3, t, 0}, {3, 0, 0}, {0, 0, 0});
    obj.quad("edge_top", "outside", {0, t, 2.5f}, {0, 0, 2.5f}, {3, 0, 2.5f}, {3, t, 2.5f});
    obj.quad("edge_west", "outside", {0, t, 0}, {0, 0, 0}, {0, 0, 2.5f}, {0, t, 2.5f});
    obj.quad("edge_east", "outside", {3, t, 0}, {3, t, 2.5f}, {3, 0, 2.5f}, {3, 0, 0});
  }
  dir.write("scene.obj", obj.str());
  std::ostringstream s;
  s << R"({"fenestra": 1, "geometry": "scene.obj",
      "materials": {"plaster": {"reflectance": 0.6}, "facade": {"reflectance": 0.5},
                    "outside": {"reflectance": 0.5}, "ground": {"reflectance": 0.2}},
      "opening_domain": {"materials": ["facade"], "element_size": )"
    << w.element_size;
  if (!w.modelled) s << R"(, "thickness": )" << w.thickness;
  s << R"(},
      "sensors": {"points": )"
    << sensors << R"(, "normals": [0, 0, 1]},
      "sky": )"
    << (w.sun ? R"({"type": "preetham", "latitude": 48.85, "longitude": 2.35, "utc_offset": 1, "date": "2026-03-21",
                  "time": "10:00", "resolution": [128, 64]})"
              : R"({"type": "cie_overcast", "resolution": [128, 64]})")
    << R"(, "render": {"paths_per_sensor": )" << paths << R"(, "max_bounces": 6, "seed": 3}})";
  dir.write("scene.json", s.str());
  return load_scene(dir.file("scene.json"));
}

// Element k's square as an opening rectangle.
Rectangle square(const Scene& scene, int k) { return scene.domain.elements()[k].corners; }

// Elements whose centre lies in the box [x0, x1] x [z0, z1] of the wall.
std::vector<int> elements_in(const Scene& scene, float x0, float x1, float z0, float z1) {
  std::vector<int> out;
  for (size_t k = 0; k < scene.domain.element_count(); ++k) {
    const Vec3 c = scene.domain.elements()[k].center;
    if (c.x() > x0 && c.x() < x1 && c.z() > z0 && c.z() < z1) out.push_back(static_cast<int>(k));
  }
  return out;
}

class ThickWall : public ::testing::TestWithParam<Wall> {};

TEST_P(ThickWall, ExactRecordsEqualEvaluateWithRealCuts) {
  const Wall w = GetParam();
  TempDir dir;
  const Scene scene = room(dir, w, 1 << 13);
  for (const Panel& p : scene.domain.panels()) ASSERT_NEAR(p.thickness, w.thickness, 1e-5) << describe(w);
  const Contributions c = compute_contributions(scene);
  const size_t n = scene.domain.element_count();

  // Open sets as the solver makes them: a window, a ragged cluster of single elements (neighbours
  // open and closed on every side), the whole wall. Each element is cut as its own rectangle:
  // adjacent cuts share no reveal.
  const std::vector<std::vector<int>> sets = {
      elements_in(scene, 0.9f, 2.1f, 0.9f, 2.1f),
      [&] {
        std::vector<int> ragged;
        for (int k : elements_in(scene, 0.3f, 2.7f, 0.3f, 2.3f))
          if ((k * 7) % 3 != 0) ragged.push_back(k);
        return ragged;
      }(),
      elements_in(scene, -1, 4, -1, 3)};
  double max_z = 0.0;
  for (size_t set = 0; set < sets.size(); ++set) {
    std::vector<uint8_t> mask(n, 0);
    std::vector<OpeningInput> cuts;
    for (int k : sets[set]) mask[k] = 1, cuts.push_back(square(scene, k));
    ASSERT_GT(cuts.size(), 3u);
    const SensorValues exact = c.evaluate(mask);
    const SensorValues truth = evaluate_openings(scene, cuts);
    // The same set as rectangles on the panel (what the solver's edge search evaluates): equal to
    // the mask's evaluation, although tube crossings lie on the grid lines between cells.
    std::vector<PanelRectangle> squares;
    for (int k : sets[set]) squares.push_back(to_panel_rectangle(scene.domain, square(scene, k)));
    const SensorValues as_region = c.evaluate(OpenRegion(scene.domain, squares));
    for (size_t i = 0; i < scene.sensors.size(); ++i)
      EXPECT_NEAR(as_region.value[i], exact.value[i], 1e-9 * (1.0 + exact.value[i])) << describe(w) << ", set " << set;
    for (size_t i = 0; i < scene.sensors.size(); ++i) {
      EXPECT_GT(truth.value[i], 0.0);
      max_z = std::max(max_z, std::abs(exact.value[i] - truth.value[i]) /
                                  std::hypot(exact.standard_error[i], truth.standard_error[i]));
      EXPECT_TRUE(within_sigma(exact.value[i], exact.standard_error[i], truth.value[i], truth.standard_error[i]))
          << describe(w) << ", set " << set << ", sensor " << i;
    }
  }
  std::printf("[ thick    ] %s: records against real cuts, max |z| %.2f over %zu values\n", describe(w).c_str(), max_z,
              sets.size() * scene.sensors.size());
}

INSTANTIATE_TEST_SUITE_P(Walls, ThickWall,
                         ::testing::Values(Wall{0.3f, 0.25f, true, false}, Wall{0.3f, 0.25f, false, true},
                                           Wall{0.5f, 0.2f, true, true}, Wall{0.1f, 0.5f, false, false},
                                           Wall{0.2f, 0.25f, true, true}));

// A 6 x 6 grid of sensors over the room's work plane, 0.8 m up (JSON points).
std::string work_plane_sensors() {
  std::ostringstream points;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      points << (i + j ? ", " : "[") << "[" << 0.3 + 0.48 * i << ", " << 0.3 + 0.48 * j << ", 0.8]";
  points << "]";
  return points.str();
}

// The objective of lux goals `goals`, relative RMS (net of the all-closed light, as the solver's).
LinearObjective goals_objective(const SensorValues& goals, const Contributions& c) {
  LinearObjective objective;
  objective.target = goals.value - c.closed.value;
  objective.weight = Eigen::VectorXd::Constant(objective.target.size(), 1.0 / goals.value.squaredNorm());
  return objective;
}

// Edges between the element grid's lines are searched with real cutters. The goals are a truth's
// own cut on the search's random numbers, so its error there is exactly 0: from the grid window
// beside it (edges 1 to 3 of the finest steps away), the search ends on the truth's edges, and
// its result's values are that cut's. Sensors over the whole work plane tell shapes of nearly the
// same area apart.
TEST(ThickWall, EdgeSearchWithRealCuttersEndsOnEdgesBetweenGridLines) {
  TempDir dir;
  const Scene scene = room(dir, {0.3f, 0.25f, false, false}, 256, work_plane_sensors());
  const Contributions c = compute_contributions(scene);
  LocalRecordQueries records(scene, c, nullptr);
  const double step = edge_steps(scene.domain.element_size(), 0.0, true).back();
  ASSERT_DOUBLE_EQ(step, 0.0625);
  const PanelRectangle grid{0, 1.0, 2.0, 0.75, 1.75};
  const PanelRectangle truth{0, 1.0 + 2 * step, 2.0 + step, 0.75 - step, 1.75 + 3 * step};
  const int paths = 256;
  const SensorValues goals = records.cut({OpeningInput(truth)}, paths, kThickWallEdgeCutStream);
  const LinearObjective objective = goals_objective(goals, c);
  const OpeningConstraints constraints;
  const ThickWallEdges found =
      search_thick_wall_edges(scene.domain, records, objective, constraints, {grid}, paths, nullptr);
  ASSERT_EQ(found.edges.openings.size(), 1u);
  const PanelRectangle& r = found.edges.openings[0];
  EXPECT_NEAR(r.u0, truth.u0, 1e-6);
  EXPECT_NEAR(r.u1, truth.u1, 1e-6);
  EXPECT_NEAR(r.v0, truth.v0, 1e-6);
  EXPECT_NEAR(r.v1, truth.v1, 1e-6);
  EXPECT_GT(found.edges.moves, 0);
  EXPECT_TRUE((found.values.value.array() == goals.value.array()).all());
  EXPECT_GT(prediction_error(objective, found.start_values.value - c.closed.value), 0.0);
}

// In a thick wall the catalogue's sizes are scored by real cuts: with goals that are a catalogue
// size's own cut, that size, at that place, is chosen and its values are that cut's.
TEST(ThickWall, CatalogueSizesAreChosenByRealCuts) {
  TempDir dir;
  const Scene scene = room(dir, {0.3f, 0.25f, false, false}, 256, work_plane_sensors());
  const Contributions c = compute_contributions(scene);
  LocalRecordQueries records(scene, c, nullptr);
  OpeningConstraints constraints;
  constraints.catalogue.walls = {{1.0, 1.0}, {1.5, 1.0}, {1.0, 0.5}};
  const PanelRectangle start{0, 1.0, 2.0, 0.75, 1.75};  // a catalogue size, kept unless one does better
  const PanelRectangle truth{0, 0.75, 2.25, 0.75, 1.75};  // 1.5 x 1.0, centred where the start is
  const int paths = 256;
  const SensorValues goals = records.cut({OpeningInput(truth)}, paths, kThickWallEdgeCutStream);
  const LinearObjective objective = goals_objective(goals, c);
  const CatalogueSnap snap = snap_to_catalogue(scene.domain, records, objective, constraints, c.E, {start}, nullptr, paths);
  ASSERT_EQ(snap.openings.size(), 1u);
  const PanelRectangle& r = snap.openings[0];
  EXPECT_NEAR(r.u0, truth.u0, 1e-6);
  EXPECT_NEAR(r.u1, truth.u1, 1e-6);
  EXPECT_NEAR(r.v0, truth.v0, 1e-6);
  EXPECT_NEAR(r.v1, truth.v1, 1e-6);
  EXPECT_TRUE(snap.exact);
  EXPECT_TRUE((snap.values.array() == goals.value.array()).all());
  EXPECT_TRUE((snap.standard_error.array() == goals.standard_error.array()).all());
}

// The error (prediction_error: squared, relative to the goals) that independent cuts' noise alone
// stays below: its mean, from the standard errors of both, and three standard deviations of the
// chi-square of as many terms as sensors.
double noise_error(const SensorValues& values, const SensorValues& goals) {
  const double mean = (values.standard_error.squaredNorm() + goals.standard_error.squaredNorm()) /
                      goals.value.squaredNorm();
  return mean * (1.0 + 3.0 * std::sqrt(2.0 / static_cast<double>(goals.value.size())));
}

// An opening split in two, and one the goals do not need, as the records can leave them in a thick
// wall: the goals are one window's own cut on the search's random numbers, at the solver's paths.
// The extra opening is removed and the two halves merged, its edges then searched. The joint edge
// steps that follow in the solver then bring every side within half the finest edge step of the
// window's, and the error within the noise of the cuts.
TEST(ThickWall, SplitOpeningsAreMergedAndNeedlessOnesRemovedByRealCuts) {
  TempDir dir;
  const Scene scene = room(dir, {0.3f, 0.25f, false, false}, 256, work_plane_sensors());
  const Contributions c = compute_contributions(scene);
  LocalRecordQueries records(scene, c, nullptr);
  const double step = edge_steps(scene.domain.element_size(), 0.0, true).back();
  const PanelRectangle truth{0, 0.75 + step, 2.0 + step, 0.75, 1.75 + step};
  const std::vector<PanelRectangle> start = {{0, 0.75, 1.375, 0.75, 1.75 + 2 * step},  // the left half, taller
                                             {0, 1.5, 2.0, 1.0, 1.5},                   // the right, smaller
                                             {0, 2.375, 2.75, 0.25, 0.625}};            // not needed
  const int paths = kThickWallEdgeCutPaths, judge_paths = kJointEdgeJudgeFactor * paths;
  const SensorValues goals = records.cut({OpeningInput(truth)}, paths, kThickWallEdgeCutStream);
  const LinearObjective objective = goals_objective(goals, c);
  const ThickWallMerges found = merge_thick_wall_openings(scene.domain, records, objective, OpeningConstraints(),
                                                          start, paths, kThickWallEdgeCutStream, nullptr);
  ASSERT_EQ(found.openings.size(), 1u);
  EXPECT_EQ(found.removed, 1);
  EXPECT_EQ(found.merged, 1);
  EXPECT_GE(found.merges_searched, 1);
  const SensorValues again = records.cut({OpeningInput(found.openings[0])}, paths, kThickWallEdgeCutStream);
  EXPECT_TRUE((found.values.value.array() == again.value.array()).all());

  const ThickWallJointEdges joint = joint_thick_wall_edges(scene.domain, records, objective, OpeningConstraints(),
                                                           found.openings, paths, judge_paths,
                                                           kThickWallJointEdgeStream, nullptr);
  ASSERT_EQ(joint.openings.size(), 1u);
  const PanelRectangle& r = joint.openings[0];
  EXPECT_NEAR(r.u0, truth.u0, 0.5 * step);
  EXPECT_NEAR(r.u1, truth.u1, 0.5 * step);
  EXPECT_NEAR(r.v0, truth.v0, 0.5 * step);
  EXPECT_NEAR(r.v1, truth.v1, 0.5 * step);
  const SensorValues from_start = records.cut(std::vector<OpeningInput>(start.begin(), start.end()), paths,
                                              kThickWallEdgeCutStream);
  const double error = prediction_error(objective, joint.values.value - c.closed.value);
  EXPECT_LT(error, noise_error(joint.values, goals));
  EXPECT_LT(noise_error(joint.values, goals), 0.1 * prediction_error(objective, from_start.value - c.closed.value));
}

// A window with a small opening below it on its panel, where the goals are the window's own cut
// with other edges: the small one is taken out and the window's edges searched, by single moves
// and slides (free sizes: the joint steps then move every side at once). It ends closer to the
// goals than the window left as it was, with the cut of its own openings.
TEST(ThickWall, ANeedlessOpeningBelowAWindowIsTakenOutAndTheWindowsEdgesSearched) {
  TempDir dir;
  const Scene scene = room(dir, {0.3f, 0.25f, false, false}, 256, work_plane_sensors());
  const Contributions c = compute_contributions(scene);
  LocalRecordQueries records(scene, c, nullptr);
  const double step = edge_steps(scene.domain.element_size(), 0.0, true).back();
  const PanelRectangle truth{0, 1.0 - step, 2.0 - 2 * step, 1.0 - 2 * step, 2.0};
  const std::vector<PanelRectangle> start = {{0, 1.0, 2.0, 1.25, 2.0}, {0, 1.25, 1.75, 0.25, 0.75}};
  const int paths = 256;
  const SensorValues goals = records.cut({OpeningInput(truth)}, paths, kThickWallEdgeCutStream);
  const LinearObjective objective = goals_objective(goals, c);
  const ThickWallMerges found = merge_thick_wall_openings(scene.domain, records, objective, OpeningConstraints(),
                                                          start, paths, kThickWallEdgeCutStream, nullptr);
  ASSERT_EQ(found.openings.size(), 1u);
  EXPECT_EQ(found.removed + found.merged, 1);  // left alone, or merged into it: one opening fewer
  EXPECT_EQ(found.merges_searched, 1);
  EXPECT_EQ(found.rough_cuts, 0);  // no pair scans for free sizes
  EXPECT_NE(found.openings[0], start[0]);
  const SensorValues alone = records.cut({OpeningInput(start[0])}, paths, kThickWallEdgeCutStream);
  EXPECT_LT(prediction_error(objective, found.values.value - c.closed.value),
            prediction_error(objective, alone.value - c.closed.value));
  const SensorValues again = records.cut({OpeningInput(found.openings[0])}, paths, kThickWallEdgeCutStream);
  EXPECT_TRUE((found.values.value.array() == again.value.array()).all());
}

// Two openings' merged candidates: their bounding box, and their joint area about their joint
// centroid with the box's aspect, on the step's positions.
TEST(ThickWall, MergedOpeningsAreTheBoxAndTheJointAreaAboutTheCentroid) {
  const PanelRectangle a{2, 0.0, 1.0, 0.0, 2.0}, b{2, 1.5, 2.0, 0.0, 0.5};  // 2 m^2 and 0.25 m^2
  const std::vector<PanelRectangle> m = merged_openings(a, b, 0.0625);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0], (PanelRectangle{2, 0.0, 2.0, 0.0, 2.0}));
  const PanelRectangle& joint = m[1];
  EXPECT_EQ(joint.panel, 2);
  EXPECT_NEAR(joint.width() * joint.height(), 2.25, 2 * 0.0625 * 1.5 + 0.0625 * 0.0625);
  EXPECT_NEAR(0.5 * (joint.u0 + joint.u1), (2.0 * 0.5 + 0.25 * 1.75) / 2.25, 0.0625);
  EXPECT_NEAR(0.5 * (joint.v0 + joint.v1), (2.0 * 1.0 + 0.25 * 0.25) / 2.25, 0.0625);
  EXPECT_NEAR(joint.width() / joint.height(), 1.0, 0.1);
  for (const double x : {joint.u0, joint.u1, joint.v0, joint.v1})
    EXPECT_NEAR(x / 0.0625, std::round(x / 0.0625), 1e-9) << x;
}

constexpr int kJointEdgeRunPaths = 256, kJointEdgeRunJudgePaths = 1024;

// The joint edge steps from `start` towards goals that are `goals_openings`' own judged cut, in the
// 3 m room with a 0.3 m wall and work-plane sensors (256 paths per difference, 1024 judged).
struct JointEdgeRun {
  Scene scene;
  Contributions c;
  LinearObjective objective;
  ThickWallJointEdges found;
};

JointEdgeRun joint_edge_steps(const TempDir& dir, const std::vector<PanelRectangle>& goals_openings,
                              const std::vector<PanelRectangle>& start, const OpeningConstraints& constraints) {
  JointEdgeRun run;
  run.scene = room(dir, {0.3f, 0.25f, false, false}, 256, work_plane_sensors());
  run.c = compute_contributions(run.scene);
  LocalRecordQueries records(run.scene, run.c, nullptr);
  const SensorValues goals = records.cut(std::vector<OpeningInput>(goals_openings.begin(), goals_openings.end()),
                                         kJointEdgeRunJudgePaths, kThickWallJointEdgeStream);
  run.objective = goals_objective(goals, run.c);
  run.found = joint_thick_wall_edges(run.scene.domain, records, run.objective, constraints, start,
                                     kJointEdgeRunPaths, kJointEdgeRunJudgePaths, kThickWallJointEdgeStream, nullptr);
  return run;
}

// Two windows whose sides are all off: one too far left and short, the other too wide. The goals
// are the truth's own cut on the judging random numbers, so the truth's judged error is exactly 0.
// Moving every side at once by the differences of real cuts brings each side within half the
// finest edge step of the truth's (nearer than the edge search's positions could), and the error
// down twentyfold. The second window is at the smallest width the constraints allow, so
// its jambs are measured one way only; no step breaks the constraints. The values are the judged
// cut of the openings returned.
TEST(ThickWall, JointEdgeStepsMoveEverySideTowardsATruthsCut) {
  TempDir dir;
  const std::vector<PanelRectangle> truth = {{0, 0.43, 1.37, 0.81, 1.93}, {0, 1.9, 2.5, 1.05, 1.71}};
  const std::vector<PanelRectangle> start = {{0, 0.33, 1.29, 0.87, 1.79}, {0, 1.84, 2.58, 1.0, 1.78}};
  OpeningConstraints constraints;
  constraints.min_width = 0.6;
  const JointEdgeRun run = joint_edge_steps(dir, truth, start, constraints);
  const Scene& scene = run.scene;
  const Contributions& c = run.c;
  const LinearObjective& objective = run.objective;
  const ThickWallJointEdges& found = run.found;
  LocalRecordQueries records(scene, c, nullptr);
  EXPECT_EQ(found.sides, 8);
  EXPECT_GE(found.steps, 1);
  EXPECT_GE(found.cuts, found.steps * found.sides);  // every side measured before each step
  EXPECT_GT(found.judged_cuts, found.steps);
  ASSERT_EQ(found.openings.size(), 2u);
  const double half_step = 0.5 * edge_steps(scene.domain.element_size(), 0.0, true).back();
  for (size_t i = 0; i < 2; ++i) {
    const PanelRectangle& r = found.openings[i];
    EXPECT_NEAR(r.u0, truth[i].u0, half_step) << i;
    EXPECT_NEAR(r.u1, truth[i].u1, half_step) << i;
    EXPECT_NEAR(r.v0, truth[i].v0, half_step) << i;
    EXPECT_NEAR(r.v1, truth[i].v1, half_step) << i;
  }
  EXPECT_TRUE(constraint_violations(scene.domain, found.openings, constraints).empty());
  const SensorValues again = records.cut(std::vector<OpeningInput>(found.openings.begin(), found.openings.end()),
                                         kJointEdgeRunJudgePaths, kThickWallJointEdgeStream);
  EXPECT_TRUE((found.values.value.array() == again.value.array()).all());
  const double before = prediction_error(objective, found.start_values.value - c.closed.value);
  const double after = prediction_error(objective, found.values.value - c.closed.value);
  EXPECT_LT(after, 0.05 * before);
}

// Where the joint steps stall beyond the noise, the edge search's pair scans follow from where the
// steps began, and their result is judged as a step is. The goals are a truth's own cut on the
// scans' random numbers at the solver's paths, and the start the grid window beside it. The scans
// gain more than the noise of the cuts, and the judged cut of their openings is kept. (They need
// not end on the truth's edges: every candidate's sky samples aim at its own openings, so nearby
// candidates differ by noise as well as by the light their change makes. Measured here, as
// prediction_error (the squared relative RMS): the truth's own judged cut misses the goals by
// 0.00083, the scans' openings by 0.0020, the start by 0.028.)
TEST(ThickWall, PairScansFollowStalledJointStepsAndAreJudged) {
  TempDir dir;
  const Scene scene = room(dir, {0.3f, 0.25f, false, false}, 256, work_plane_sensors());
  const Contributions c = compute_contributions(scene);
  LocalRecordQueries records(scene, c, nullptr);
  const double step = edge_steps(scene.domain.element_size(), 0.0, true).back();
  const PanelRectangle grid{0, 1.0, 2.0, 0.75, 1.75};
  const PanelRectangle truth{0, 1.0 + 2 * step, 2.0 + step, 0.75 - step, 1.75 + 3 * step};
  const int paths = kThickWallEdgeCutPaths, judge_paths = kJointEdgeJudgeFactor * paths;
  const SensorValues goals = records.cut({OpeningInput(truth)}, paths, kThickWallEdgeCutStream);
  const LinearObjective objective = goals_objective(goals, c);
  ThickWallJointEdges joint;
  joint.openings = {grid};
  joint.start_values = joint.values = records.cut({OpeningInput(grid)}, judge_paths, kThickWallJointEdgeStream);
  scan_stalled_joint_edges(scene.domain, records, objective, OpeningConstraints(), {grid}, paths, judge_paths,
                           kThickWallJointEdgeStream, nullptr, &joint);
  EXPECT_TRUE(joint.scanned);
  EXPECT_GT(joint.scan_cuts, 0);
  EXPECT_GT(joint.scan_moves, 0);
  EXPECT_EQ(joint.judged_cuts, 1);
  ASSERT_EQ(joint.openings.size(), 1u);
  EXPECT_NE(joint.openings[0], grid);
  const SensorValues judged = records.cut({OpeningInput(joint.openings[0])}, judge_paths, kThickWallJointEdgeStream);
  EXPECT_TRUE((joint.values.value.array() == judged.value.array()).all());
  const double start_error = prediction_error(objective, joint.start_values.value - c.closed.value);
  const double error = prediction_error(objective, joint.values.value - c.closed.value);
  EXPECT_LT(error + noise_error(judged, goals), start_error);
}

// The goals' second window is lower than the constraints allow, so a step towards them would make
// the start's second window (at the smallest height allowed) too small: its sides are held, and the
// first window's sides still move to the goals' own.
TEST(ThickWall, JointEdgeStepsHoldAnOpeningTheyWouldMakeTooSmall) {
  TempDir dir;
  const std::vector<PanelRectangle> goals_openings = {{0, 0.43, 1.37, 0.81, 1.93}, {0, 1.9, 2.5, 1.2, 1.6}};
  const std::vector<PanelRectangle> start = {{0, 0.35, 1.3, 0.86, 1.85}, {0, 1.9, 2.5, 1.1, 1.6}};
  OpeningConstraints constraints;
  constraints.min_height = 0.5;
  const JointEdgeRun run = joint_edge_steps(dir, goals_openings, start, constraints);
  const Scene& scene = run.scene;
  const ThickWallJointEdges& found = run.found;
  EXPECT_GE(found.steps, 1);
  ASSERT_EQ(found.openings.size(), 2u);
  EXPECT_TRUE(constraint_violations(scene.domain, found.openings, constraints).empty());
  EXPECT_GE(found.openings[1].height(), constraints.min_height - 1e-9);
  const double half_step = 0.5 * edge_steps(scene.domain.element_size(), 0.0, true).back();
  const PanelRectangle& r = found.openings[0];
  EXPECT_NEAR(r.u0, goals_openings[0].u0, half_step);
  EXPECT_NEAR(r.u1, goals_openings[0].u1, half_step);
  EXPECT_NEAR(r.v0, goals_openings[0].v0, half_step);
  EXPECT_NEAR(r.v1, goals_openings[0].v1, half_step);
}

TEST(ThickWall, CutPathsFollowTheSolvesPaths) {
  // A sixteenth of the solve's paths, from 128 (or the solve's own when fewer) to 1 024.
  EXPECT_EQ(thick_wall_cut_paths(16384), kThickWallEdgeCutPaths);
  EXPECT_EQ(thick_wall_cut_paths(1 << 20), kThickWallEdgeCutPaths);
  EXPECT_EQ(thick_wall_cut_paths(4096), 256);
  EXPECT_EQ(thick_wall_cut_paths(2048), kThickWallEdgeCutPathsAtLeast);
  EXPECT_EQ(thick_wall_cut_paths(1024), kThickWallEdgeCutPathsAtLeast);
  EXPECT_EQ(thick_wall_cut_paths(100), 100);
  EXPECT_EQ(thick_wall_cut_paths(1), 1);
}

TEST(ThickWall, LinesAheadCountsTheTubeSidesLeftInTheWall) {
  TempDir dir;
  const Scene scene = room(dir, {0.3f, 0.25f, false, false}, 16);
  const OpeningDomain& domain = scene.domain;
  const Panel& panel = domain.panels()[0];
  ASSERT_NEAR(panel.thickness, 0.3f, 1e-6f);
  // From a point on the grid line u = 1.0, 0.1 m into the wall, heading outward and along +u at 45
  // degrees: 0.2 m to the outer face, so u reaches 1.2, crossing no other line (the next is 1.25).
  const Vec3 p = panel.origin + 1.0f * panel.u_axis + 1.1f * panel.v_axis + 0.1f * panel.outward;
  const Vec3 diagonal = (panel.outward + panel.u_axis).normalized();
  EXPECT_EQ(domain.lines_ahead(0, p, diagonal), 0);
  // Shallower, 0.6 m along u per 0.2 m outward: lines 1.25 and 1.5.
  EXPECT_EQ(domain.lines_ahead(0, p, (panel.outward + 3.0f * panel.u_axis).normalized()), 2);
  // Back toward the room (0.1 m to the inner face), along -u and +v: u 1.0 -> 0.52 (0.75), v 1.1
  // -> 1.58 (1.25, 1.5).
  EXPECT_EQ(domain.lines_ahead(0, p, (-panel.outward - 4.8f * panel.u_axis + 4.8f * panel.v_axis).normalized()), 3);
  // Parallel to the wall: to the grid's ends (u 1.0 -> 3.0: 1.25 ... 3.0, eight lines).
  EXPECT_EQ(domain.lines_ahead(0, p, panel.u_axis), 8);
}

TEST(ThickWall, EdgeStepsStopAboveTheThickWallStep) {
  for (double s : {0.2, 0.25, 0.3, 0.5}) {
    const std::vector<double> thin = edge_steps(s, 0.0, false), thick = edge_steps(s, 0.0, true);
    EXPECT_NEAR(thin.back(), s / std::pow(2.0, std::floor(std::log2(s / kContinuousEdgeStep))), 1e-12) << s;
    EXPECT_GE(thick.back(), kThickWallEdgeStep - 1e-12) << s;
    EXPECT_LT(thick.back(), 2 * kThickWallEdgeStep) << s;
    // The positions an edge may take are the edge plus multiples of the finest step, within an
    // element and the finer steps' sum.
    const std::vector<float> at = edge_positions(1.0, s, 0.0, true);
    double span = s;
    for (size_t i = 1; i < thick.size(); ++i) span += thick[i];
    EXPECT_NEAR(thick_wall_edge_span(s, 0.0), span, 1e-12);
    EXPECT_EQ(at.size(), 2 * static_cast<size_t>(std::lround(span / thick.back())) + 1) << s;
    EXPECT_NEAR(at.front(), 1.0 - span, 1e-6);
    EXPECT_NEAR(at.back(), 1.0 + span, 1e-6);
  }
  // With a module, positions are its multiples.
  for (float x : edge_positions(0.75, 0.25, 0.05, true)) EXPECT_NEAR(x / 0.05, std::round(x / 0.05), 1e-4) << x;
}

TEST(ThickWall, RevealsTakeLightTheThinWallLets) {
  // The test above can tell: the same window in a 0.5 m wall and in a zero-thickness one differ
  // by many standard errors.
  TempDir thin_dir, thick_dir;
  const Scene thin = room(thin_dir, {0.0f, 0.25f, false, false}, 1 << 13);
  const Scene thick = room(thick_dir, {0.5f, 0.25f, false, false}, 1 << 13);
  const Rectangle window = {Vec3(1, 0, 1), Vec3(2, 0, 1), Vec3(2, 0, 2), Vec3(1, 0, 2)};
  const SensorValues a = evaluate_openings(thin, {window}), b = evaluate_openings(thick, {window});
  for (size_t i = 0; i < a.value.size(); ++i)
    EXPECT_GT(a.value[i] - b.value[i], 8.0 * std::hypot(a.standard_error[i], b.standard_error[i])) << "sensor " << i;
}

TEST(ThickWall, MeasuredFromTheModelUnlessGiven) {
  TempDir dir;
  const Scene measured = room(dir, {0.3f, 0.25f, true, false}, 16);
  EXPECT_NEAR(measured.domain.panels()[0].thickness, 0.3f, 1e-5);
  EXPECT_TRUE(measured.domain.panels()[0].solid_modelled);
  // A thickness that disagrees with the model is refused, naming both.
  std::string json;
  {
    std::ifstream in(dir.file("scene.json"));
    json.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string key = R"("element_size": 0.25)";
  json.replace(json.find(key), key.size(), key + R"(, "thickness": 0.2)");
  dir.write("scene.json", json);
  try {
    load_scene(dir.file("scene.json"));
    FAIL() << "a thickness of 0.2 m on a 0.3 m solid was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("0.2 m"), std::string::npos) << m;
    EXPECT_NE(m.find("0.3 m"), std::string::npos) << m;
    EXPECT_NE(m.find("facade"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace fenestra
