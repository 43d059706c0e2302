// The setup checks (study/setup_checks.h): each misleading setup is found, with its sensors, and a
// sound closed room gets no warning, near the origin and at site coordinates; a solve without goals
// is refused before any ray is traced.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "solve/goals.h"
#include "solve/solver.h"
#include "study/setup_checks.h"
#include "test_scenes.h"
#include "trace/ray_scene.h"

namespace fenestra {
namespace {

using test::ObjBuilder;
using test::TempDir;
using Kind = SetupWarning::Kind;

struct Room {
  Vec3 offset = Vec3::Zero();
  bool ceiling = true;
  std::string goals = R"({"uniform": [{"level": 0.5}]})";
  std::string normals = "[0, 0, 1]";
  std::vector<Vec3> extra_sensors;  // after the 4 x 4 grid inside
};

// A 4 x 4 x 2.7 m zero-thickness room (its south wall y = 0 the domain), moved by `offset`, with a
// 4 x 4 grid of sensors at 0.8 m.
Scene room_scene(const TempDir& dir, const Room& r) {
  ObjBuilder obj;
  const Vec3 lo = r.offset, hi = r.offset + Vec3(4, 4, 2.7f);
  const float x0 = lo.x(), y0 = lo.y(), z0 = lo.z(), x1 = hi.x(), y1 = hi.y(), z1 = hi.z();
  obj.quad("floor", "grey", {x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, y0, z0});
  if (r.ceiling) obj.quad("ceiling", "grey", {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1});
  obj.quad("south", "facade", {x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1});
  obj.quad("north", "grey", {x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0});
  obj.quad("west", "grey", {x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0});
  obj.quad("east", "grey", {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1});
  dir.write("scene.obj", obj.str());
  std::ostringstream points;
  points.precision(12);
  std::vector<Vec3> sensors;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) sensors.push_back(r.offset + Vec3(0.5f + i, 0.5f + j, 0.8f));
  sensors.insert(sensors.end(), r.extra_sensors.begin(), r.extra_sensors.end());
  for (size_t k = 0; k < sensors.size(); ++k)
    points << (k ? ", " : "") << "[" << double(sensors[k].x()) << ", " << double(sensors[k].y()) << ", "
           << double(sensors[k].z()) << "]";
  dir.write("scene.json", R"({"fenestra": 1, "geometry": "scene.obj",
      "materials": {"grey": {"reflectance": 0.5}, "facade": {"reflectance": 0.5}},
      "opening_domain": {"materials": ["facade"], "element_size": 0.5},
      "sensors": {"points": [)" + points.str() + R"(], "normals": )" + r.normals + R"(},)" +
                              (r.goals.empty() ? "" : R"("goals": )" + r.goals + ",") + R"(
      "sky": {"type": "uniform", "radiance": 100}, "render": {"paths_per_sensor": 64}})");
  return load_scene(dir.file("scene.json"));
}

std::vector<Kind> kinds(const std::vector<SetupWarning>& w) {
  std::vector<Kind> out;
  for (const SetupWarning& x : w) out.push_back(x.kind);
  return out;
}

const SetupWarning* find(const std::vector<SetupWarning>& w, Kind kind) {
  for (const SetupWarning& x : w)
    if (x.kind == kind) return &x;
  return nullptr;
}

std::vector<int> range(int a, int b) {
  std::vector<int> v;
  for (int i = a; i < b; ++i) v.push_back(i);
  return v;
}

TEST(SetupChecks, AClosedRoomIsSoundAtTheOriginAndAtSiteCoordinates) {
  for (const Vec3& offset : {Vec3(0, 0, 0), Vec3(1e5f, 1e5f, 0), Vec3(5e5f, 9e5f, 300)}) {
    TempDir dir;
    Room r;
    r.offset = offset;
    const Scene scene = room_scene(dir, r);
    for (SetupStage stage : {SetupStage::Solve, SetupStage::Contributions, SetupStage::Evaluate}) {
      const auto found = check_setup(scene, stage);
      EXPECT_TRUE(found.empty()) << offset.transpose() << ": " << (found.empty() ? "" : found[0].message);
    }
  }
}

TEST(SetupChecks, AllGoalsZero) {
  TempDir dir;
  Room r;
  r.goals = R"({"uniform": [{"level": 0}]})";
  const Scene scene = room_scene(dir, r);
  const auto found = check_setup(scene, SetupStage::Solve);
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::ZeroGoals});
  EXPECT_EQ(found[0].sensors, range(0, 16));
  EXPECT_NE(found[0].message.find("all 16 sensor goals are 0 (goals.uniform)"), std::string::npos) << found[0].message;
  EXPECT_TRUE(check_setup(scene, SetupStage::Contributions).empty());  // no goals there
  // A goal above 0 on one sensor is something to open for.
  TempDir dir2;
  r.goals = R"({"uniform": [{"level": 0, "sensors": [0, 1, 2]}, {"level": 0.3, "sensors": [3]}]})";
  EXPECT_TRUE(check_setup(room_scene(dir2, r), SetupStage::Solve).empty());
}

TEST(SetupChecks, SensorsOutdoorsAreNamedWithTheirPositions) {
  TempDir dir;
  Room r;
  r.extra_sensors = {{6.5f, 0.5f, 0.8f}, {7.5f, 1.5f, 0.8f}};
  const Scene scene = room_scene(dir, r);
  const auto found = check_setup(scene, SetupStage::Solve);
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::Outdoors});
  EXPECT_EQ(found[0].sensors, (std::vector<int>{16, 17}));
  EXPECT_EQ(found[0].total, 18u);
  EXPECT_EQ(found[0].message.rfind("2 of 18 sensors are outdoors", 0), 0u) << found[0].message;
  EXPECT_NE(found[0].message.find("sensors 16 (6.50, 0.50, 0.80), 17 (7.50, 1.50, 0.80)"), std::string::npos)
      << found[0].message;
  EXPECT_TRUE(check_setup(scene, SetupStage::Evaluate).empty());  // measured as they are
}

TEST(SetupChecks, ARoomWithoutACeilingIsOpenUpward) {
  TempDir dir;
  Room r;
  r.ceiling = false;
  const Scene scene = room_scene(dir, r);
  const auto found = check_setup(scene, SetupStage::Contributions);
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::OpenRoom});
  EXPECT_EQ(found[0].sensors, range(0, 16));
  EXPECT_GT(found[0].direction.z(), 0.5f);
  EXPECT_GT(found[0].share, 0.0);
  EXPECT_LT(found[0].share, 0.5);
  EXPECT_NE(found[0].message.find("mostly upward"), std::string::npos) << found[0].message;
  EXPECT_NE(found[0].message.find("and 13 more"), std::string::npos) << found[0].message;
}

TEST(SetupChecks, SensorsFacingDown) {
  TempDir dir;
  Room r;
  r.normals = "[0, 0, -1]";
  const Scene scene = room_scene(dir, r);
  for (SetupStage stage : {SetupStage::Solve, SetupStage::Evaluate}) {
    const auto found = check_setup(scene, stage);
    ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::Downward});
    EXPECT_EQ(found[0].sensors, range(0, 16));
    EXPECT_NE(found[0].message.find("16 of 16 sensors face downward"), std::string::npos) << found[0].message;
    EXPECT_NE(found[0].message.find("sensors.normals"), std::string::npos) << found[0].message;
  }
}

// Room A's south wall (y = 0, the domain) is seen by A's 16 sensors from y > 0; room B south of
// it, closed, has 36 sensors at y < 0: the solver takes y < 0 for the wall's room.
TEST(SetupChecks, ADomainSeenFromTheSideTheSolverDoesNotTakeForTheRoom) {
  TempDir dir;
  ObjBuilder obj;
  obj.box({0, 0, 0}, {4, 4, 2.7f}, [](const std::string& f) { return f == "south" ? "facade" : "grey"; });
  obj.box({0, -10, 0}, {6, -4, 2.7f}, [](const std::string&) { return "grey"; });
  dir.write("scene.obj", obj.str());
  std::ostringstream points;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) points << "[" << 0.5 + i << ", " << 0.5 + j << ", 0.8], ";
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) points << "[" << 0.5 + i << ", " << -9.5 + j << ", 0.8]" << (i == 5 && j == 5 ? "" : ", ");
  dir.write("scene.json", R"({"fenestra": 1, "geometry": "scene.obj",
      "materials": {"grey": {"reflectance": 0.5}, "facade": {"reflectance": 0.5}},
      "opening_domain": {"materials": ["facade"], "element_size": 0.5},
      "sensors": {"points": [)" + points.str() + R"(]}, "goals": {"uniform": [{"level": 0.5}]},
      "sky": {"type": "uniform", "radiance": 100}})");
  const Scene scene = load_scene(dir.file("scene.json"));
  const auto found = check_setup(scene, SetupStage::Evaluate);
  ASSERT_EQ(kinds(found), std::vector<Kind>{Kind::DomainSide});
  ASSERT_EQ(found[0].panels.size(), 1u);
  EXPECT_EQ(found[0].panels[0].seen_from_outside, 16);
  EXPECT_EQ(found[0].panels[0].on_room_side, 36);
  EXPECT_EQ(found[0].panels[0].groups, std::vector<std::string>{"south"});
  EXPECT_NE(found[0].message.find("is seen by 16 sensors from one side, but 36 of 52 sensors lie on the other side"),
            std::string::npos)
      << found[0].message;
}

// Sensors in the domain wall's plane (y = 0) or 3 cm off it, 2 cm off a wall or under the ceiling;
// on the floor facing up, 8 cm off a wall or under the ceiling is where sensors may be.
TEST(SetupChecks, SensorsOnTheDomainOrOnAnotherSurface) {
  TempDir dir;
  Room r;
  r.extra_sensors = {{2.0f, 0.0f, 0.8f},  {2.5f, 0.03f, 1.2f}, {0.02f, 2.0f, 0.8f}, {2.0f, 2.0f, 2.68f},
                     {2.0f, 2.0f, 0.0f},  {2.0f, 0.08f, 0.8f}, {3.92f, 2.0f, 0.8f}, {2.0f, 2.0f, 2.62f}};
  const Scene scene = room_scene(dir, r);
  for (SetupStage stage : {SetupStage::Solve, SetupStage::Evaluate}) {
    const auto found = check_setup(scene, stage);
    const SetupWarning* domain = find(found, Kind::OnDomain);
    const SetupWarning* surface = find(found, Kind::NearSurface);
    ASSERT_TRUE(domain && surface);
    EXPECT_EQ(domain->sensors, (std::vector<int>{16, 17}));
    EXPECT_EQ(surface->sensors, (std::vector<int>{18, 19}));
    EXPECT_EQ(domain->message.rfind("2 of 24 sensors lie on the opening domain (within 0.05 m of it): sensors 16 "
                                    "(2.00, 0.00, 0.80), 17 (2.50, 0.03, 1.20)",
                                    0),
              0u)
        << domain->message;
    EXPECT_NE(surface->message.find("on a wall, ceiling or other surface"), std::string::npos) << surface->message;
  }
  // The sound room's own 16 sensors, 0.5 m off the walls, are not named.
  TempDir dir2;
  const auto sound = check_setup(room_scene(dir2, Room()), SetupStage::Solve);
  EXPECT_EQ(find(sound, Kind::OnDomain), nullptr);
  EXPECT_EQ(find(sound, Kind::NearSurface), nullptr);
}

TEST(SetupChecks, StrictMakesThemAnError) {
  TempDir dir;
  Room r;
  r.normals = "[0, 0, -1]";
  const Scene scene = room_scene(dir, r);
  const auto found = check_setup(scene, SetupStage::Solve);
  EXPECT_EQ(setup_messages(scene, found, false).size(), 1u);
  try {
    setup_messages(scene, found, true);
    FAIL() << "not refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the setup checks found 1 problem (strict); 16 of 16 sensors face downward"),
              std::string::npos)
        << e.what();
  }
}

TEST(SetupChecks, ASolveWithoutGoalsIsRefusedBeforeTracing) {
  TempDir dir;
  Room r;
  r.goals = "";
  const Scene scene = room_scene(dir, r);
  const uint64_t before = rays_traced();
  try {
    solve_openings(scene);
    FAIL() << "not refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no sensor has a goal"), std::string::npos) << e.what();
  }
  EXPECT_EQ(rays_traced(), before);
}

}  // namespace
}  // namespace fenestra
