// The cost model (docs/cost.md): estimates against measured memory, refusals naming the figure
// and the setting, the memory limit's detection and overrides.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "annual/annual_contributions.h"
#include "daylight/daylight.h"
#include "scene/domain_estimate.h"
#include "scene/environment_map.h"
#include "study/cost_model.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "util/byte_size.h"
#include "util/cost_context.h"
#include "util/memory_limit.h"

namespace fenestra {
namespace {

using test::ObjBuilder;
using test::TempDir;

// A 4 x 3 x 2.6 m room, its south wall the domain; `sensors` along the room's middle.
std::string room_scene(double element_size, int sensors, const std::string& solver = "{}") {
  std::ostringstream s;
  s << R"({"fenestra": 1, "geometry": "scene.obj", "materials": {"wall": {"reflectance": 0.5},)"
    << R"( "facade": {"reflectance": 0.5}}, "opening_domain": {"materials": ["facade"], "element_size": )"
    << element_size << R"(}, "sensors": {"points": [)";
  for (int i = 0; i < sensors; ++i) s << (i ? ", " : "") << "[" << 0.5 + 3.0 * i / std::max(1, sensors - 1) << ", 1.5, 0.8]";
  s << R"(]}, "goals": {"uniform": [{"level": 0.5}]}, "sky": {"type": "uniform", "radiance": 100}, "solver": )" << solver
    << "}";
  return s.str();
}

std::string room_obj() {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {4, 3, 2.6f}, [](const std::string& f) { return f == "south" ? "facade" : "wall"; });
  return obj.str();
}

Scene load_room(const TempDir& dir, double element_size, int sensors, const std::string& solver = "{}") {
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", room_scene(element_size, sensors, solver));
  return load_scene(dir.file("scene.json"));
}

// Runs `f`, expects a CostError whose message holds every fragment.
template <typename F>
void expect_refusal(F f, const std::vector<std::string>& fragments) {
  try {
    f();
    FAIL() << "not refused; expected a message with '" << fragments.front() << "'";
  } catch (const CostError& e) {
    for (const auto& fragment : fragments) EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  } catch (const std::invalid_argument& e) {  // the loader rethrows with the scene and key in front
    for (const auto& fragment : fragments) EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(ByteSize, ParsesDecimalAndBinaryUnits) {
  EXPECT_EQ(parse_byte_size("8G"), 8000000000ull);
  EXPECT_EQ(parse_byte_size("512M"), 512000000ull);
  EXPECT_EQ(parse_byte_size("1.5GB"), 1500000000ull);
  EXPECT_EQ(parse_byte_size("2GiB"), 2ull << 30);
  EXPECT_EQ(parse_byte_size("64Ki"), 65536ull);
  EXPECT_EQ(parse_byte_size("123456"), 123456ull);
  EXPECT_EQ(parse_byte_size("3k"), 3000ull);
  for (const char* bad : {"", "G", "-1G", "0", "1X", "8GG", "1e400", "nan", "8 G"})
    EXPECT_THROW(parse_byte_size(bad), std::invalid_argument) << bad;
}

TEST(ByteSize, FormatsForMessages) {
  EXPECT_EQ(format_bytes(11.52e9), "11.5 GB");
  EXPECT_EQ(format_bytes(115.2e9), "115 GB");
  EXPECT_EQ(format_bytes(3.2e6), "3.2 MB");
  EXPECT_EQ(format_bytes(17), "17 bytes");
  EXPECT_EQ(format_count(1200000), "1 200 000");
  EXPECT_EQ(format_count(11993001, 3), "12 000 000");
  EXPECT_EQ(format_count(999), "999");
}

TEST(CostModel, MatricesAreSensorsTimesElementsAndElementsSquaredDoubles) {
  TempDir dir;
  const Scene scene = load_room(dir, 0.25, 8);
  const CostEstimate e = estimate_cost(scene, CostCommand::Contributions);
  const double S = 8, N = static_cast<double>(scene.domain.element_count());
  ASSERT_EQ(e.elements, scene.domain.element_count());
  std::map<std::string, double> bytes;
  for (const MemoryItem& m : e.memory) bytes[m.key] = m.bytes;
  EXPECT_EQ(bytes["E"], 8 * S * N);
  EXPECT_EQ(bytes["E_stderr"], 8 * S * N);
  EXPECT_EQ(bytes["A"], 8 * S * N);
  EXPECT_EQ(bytes["T"], 8 * N * N);
  EXPECT_EQ(bytes["path_records"], S * scene.render.paths_per_sensor * e.bytes_per_path);
  EXPECT_GT(e.peak_bytes(), e.kept_bytes());
}

// The kept part of the estimate against Contributions::memory_bytes() (E, E_stderr, A, T and the
// path records' capacity), measured: within a factor of 2, and not below (the model is conservative).
void expect_memory_estimate_within_two(const Scene& scene, const std::string& what) {
  const double estimate = estimate_cost(scene, CostCommand::Contributions).kept_bytes();
  const double measured = static_cast<double>(compute_contributions(scene).memory_bytes());
  EXPECT_GE(estimate, measured) << what;
  EXPECT_LE(estimate, 2.0 * measured) << what;
}

TEST(CostModel, EstimateWithinAFactorOfTwoOfMeasuredMemory) {
  TempDir dir;
  for (int paths : {512, 4096}) {
    Scene scene = load_room(dir, 0.25, 12);
    scene.render.paths_per_sensor = paths;
    expect_memory_estimate_within_two(scene, std::to_string(paths) + " paths");
  }
  // The reference room of the examples (Radiance-validated, 16 sensors, 192 elements).
  Scene reference = load_scene(std::string(FENESTRA_EXAMPLES) + "/reference_room/scene.json");
  reference.render.paths_per_sensor = 2048;
  expect_memory_estimate_within_two(reference, "reference room");
}

TEST(CostModel, ThickWallRecordsWithinAFactorOfTwo) {
  // 0.3 m walls: paths branch at the elements' tubes, and the records grow with them.
  Scene scene = load_scene(std::string(FENESTRA_EXAMPLES) + "/thick_walls_study/scene.json");
  scene.render.paths_per_sensor = 512;
  expect_memory_estimate_within_two(scene, "thick_walls_study");
}

TEST(CostModel, RecordsGrowWithBouncesAndReflectance) {
  TempDir dir;
  Scene scene = load_room(dir, 0.5, 1);
  const double base = path_record_bytes(scene);
  scene.render.max_bounces = 0;
  EXPECT_LT(path_record_bytes(scene), base);
  scene.render.max_bounces = 64;
  scene.materials[0].reflectance = Rgb::Constant(0.95f);
  EXPECT_GT(path_record_bytes(scene), 2 * base);
}

TEST(CostModel, RefusesWhatDoesNotFitNamingTheFigureAndTheSetting) {
  TempDir dir;
  Scene scene = load_room(dir, 0.25, 8);
  EXPECT_NO_THROW(check_cost(scene, CostCommand::Contributions, MemoryLimit{uint64_t{1} << 40, "test"}));
  scene.render.paths_per_sensor = 1 << 20;  // 8 sensors x 2^20 paths of records: gigabytes
  expect_refusal([&] { check_cost(scene, CostCommand::Contributions, MemoryLimit{uint64_t{1} << 30, "in the test"}); },
                 {"1 048 576 paths per sensor", "path records", " GB", "1.1 GB in the test", "render.paths_per_sensor",
                  "--max-memory"});
  // Within the override, the same scene runs.
  EXPECT_NO_THROW(check_cost(scene, CostCommand::Contributions, MemoryLimit{uint64_t{1} << 40, "test"}));
  // Evaluate keeps no records.
  EXPECT_NO_THROW(check_cost(scene, CostCommand::Evaluate, MemoryLimit{uint64_t{1} << 30, "test"}));
  // Solve traces with solver.paths when given.
  scene.render.paths_per_sensor = 1024;
  scene.solver.paths_per_sensor = 1 << 22;
  expect_refusal([&] { check_cost(scene, CostCommand::Solve, MemoryLimit{uint64_t{1} << 30, "test"}); },
                 {"4 194 304 paths per sensor", "solver.paths"});
}

TEST(CostModel, TIsNamedWhenElementsDominate) {
  TempDir dir;
  const Scene scene = load_room(dir, 0.05, 2);  // 80 x 52 elements
  expect_refusal([&] { check_cost(scene, CostCommand::Contributions, MemoryLimit{100000000, "in the test"}); },
                 {"element_size 0.05 m gives 4 160 elements", "error-compensation matrix T", "138 MB",
                  "100 MB in the test", "element_size"});
}

TEST(CostModel, GeneticAndLocalSearchBudgetsAreBounded) {
  TempDir dir;
  const Scene fine = load_room(dir, 0.25, 8);
  EXPECT_NO_THROW(check_cost(fine, CostCommand::Solve));  // the defaults: milliseconds
  const Scene generations = load_room(dir, 0.25, 8, R"({"generations": 10000000})");
  expect_refusal([&] { check_cost(generations, CostCommand::Solver); },
                 {"genetic algorithm", "min", "solver.generations (10 000 000)", "solver.time_budget_s"});
  // A time budget bounds the fine-grid runs; without coarse levels nothing else is unbounded.
  const Scene budget = load_room(dir, 0.25, 8, R"({"generations": 10000000, "time_budget_s": 5, "coarse_to_fine": false})");
  EXPECT_NO_THROW(check_cost(budget, CostCommand::Solver));
  const Scene coarse = load_room(dir, 0.25, 8, R"({"generations": 10000000, "time_budget_s": 5})");
  expect_refusal([&] { check_cost(coarse, CostCommand::Solver); }, {"genetic algorithm", "solver.generations"});
  const Scene iterations = load_room(dir, 0.25, 100, R"({"improve_iterations": 100000000})");
  expect_refusal([&] { check_cost(iterations, CostCommand::Solver); },
                 {"local search", "solver.improve_iterations (100 000 000)"});
}

TEST(LoadChecks, DomainEstimateMatchesTheDicing) {
  TempDir dir;
  for (double size : {0.5, 0.25, 0.1}) {
    const Scene scene = load_room(dir, size, 1);
    std::vector<std::vector<uint32_t>> panels;
    for (const Panel& p : scene.domain.panels()) panels.push_back(p.triangles);
    const DomainEstimate e = estimate_domain(scene.mesh, panels, static_cast<float>(size));
    const double n = static_cast<double>(scene.domain.element_count());
    EXPECT_GE(e.elements, n - 0.5) << size;
    EXPECT_LE(e.elements, 1.3 * n) << size;
    EXPECT_NEAR(e.largest_side, 4.0, 1e-3);
  }
}

TEST(LoadChecks, TinyElementsAreRefusedBeforeDicing) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  dir.write("scene.json", room_scene(0.001, 1));
  const auto start = std::chrono::steady_clock::now();
  {
    const CostScope scope({0, CostCommand::Contributions});
    expect_refusal([&] { load_scene(dir.file("scene.json")); },
                   {"opening_domain", "element_size 0.001 m gives about 10 400 000 elements", "matrix T alone",
                    " PB", "larger element_size"});
  }
  {  // evaluate does not need T, but the domain is not diced into millions of elements
    const CostScope scope({0, CostCommand::Evaluate});
    expect_refusal([&] { load_scene(dir.file("scene.json")); }, {"at most 1 000 000 elements"});
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  {  // 0.02 m: 26 000 elements; the domain's grid alone does not fit in 1 MB
    dir.write("scene.json", room_scene(0.02, 1));
    const CostScope scope({1000000, CostCommand::Evaluate});
    expect_refusal([&] { load_scene(dir.file("scene.json")); }, {"the opening domain's grid", "1.0 MB allowed"});
  }
}

TEST(LoadChecks, MillimetreGeometryIsNamed) {
  TempDir dir;
  ObjBuilder obj;
  obj.box({0, 0, 0}, {4000, 3000, 2600}, [](const std::string& f) { return f == "south" ? "facade" : "wall"; });
  dir.write("scene.obj", obj.str());
  dir.write("scene.json", room_scene(0.25, 1));
  const CostScope scope({0, CostCommand::Solve});
  expect_refusal([&] { load_scene(dir.file("scene.json")); }, {"millimetres", "4 000 m", "element_size"});
}

TEST(LoadChecks, ImageHeaderIsCheckedBeforeThePixels) {
  expect_refusal([] { check_image_cost("big.hdr", 30000, 15000, 3); },
                 {"'big.hdr' is 30000 x 15000 pixels", "450 000 000", "GB", "at most 134 217 728"});
  EXPECT_NO_THROW(check_image_cost("small.exr", 1024, 512, 4));
  const CostScope scope({1000000, CostCommand::Any});
  expect_refusal([] { check_image_cost("small.exr", 1024, 512, 4); }, {"reading it needs", "1.0 MB allowed"});
}

TEST(LoadChecks, LyingHdrHeaderIsRefusedWhenTheSceneIsRead) {
  TempDir dir;
  dir.write("scene.obj", room_obj());
  std::ofstream(dir.file("lie.hdr"), std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 15000 +X 30000\n"
                                                       << std::string("\x02\x02\x75\x30\x01\x02\x03\x04", 8);
  std::string text = room_scene(0.5, 1);
  const std::string uniform = R"({"type": "uniform", "radiance": 100})";
  text.replace(text.find(uniform), uniform.size(), R"({"type": "envmap", "file": "lie.hdr"})");
  dir.write("scene.json", text);
  expect_refusal([&] { load_scene(dir.file("scene.json")); }, {"sky.file", "30000 x 15000", "GB"});
}

TEST(LoadChecks, LongDaylightIntervalsAreRefused) {
  DaylightSettings s;
  s.place.latitude_deg = 48.85, s.place.longitude_deg = 2.35;
  s.time_zone = TimeZone::fixed(1.0);
  s.date = parse_date("2020-01-01");
  s.date_end = parse_date("2020-12-31");
  EXPECT_NO_THROW(check_daylight_cost(s));  // a year, 9-17 h every 15 min: about 2 min
  s.date_end = parse_date("2024-12-31");    // five years: about 10 min
  size_t steps = 0, up = 0;
  EXPECT_GT(daylight_build_seconds(s, &steps, &up), kMaxDaylightSeconds);
  EXPECT_EQ(steps, 1827u * 32u);
  EXPECT_GT(up, steps * 9 / 10);
  expect_refusal([&] { check_daylight_cost(s); }, {"58 464 time steps", "min", "sky.step_minutes"});
  s.step_minutes = 60.0;
  EXPECT_NO_THROW(check_daylight_cost(s));
  s.width = 16384, s.height = 8192;  // 134 M pixels: 10.7 GB to build
  const CostScope scope({1000000000, CostCommand::Sky});
  expect_refusal([&] { check_daylight_cost(s); }, {"16384 x 8192", "10.7 GB", "sky.resolution"});
}

TEST(MemoryLimit, DetectedAndOverridden) {
  const MemoryLimit detected = detect_available_memory();
  EXPECT_GT(detected.bytes, 0u);
  EXPECT_FALSE(detected.source.empty());
  {
    const CostScope scope({12345678, CostCommand::Any});
    EXPECT_EQ(memory_limit().bytes, 12345678u);
    EXPECT_NE(memory_limit().source.find("--max-memory"), std::string::npos);
    {
      const CostScope inner({0, CostCommand::Sky});  // 0: detect again
      EXPECT_GT(memory_limit().bytes, 12345678u);
      EXPECT_EQ(cost_context().command, CostCommand::Sky);
    }
    EXPECT_EQ(memory_limit().bytes, 12345678u);
  }
  EXPECT_EQ(cost_context().command, CostCommand::Any);
}

TEST(MemoryLimit, AddressSpaceLimitIsRespected) {
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_AS, &saved), 0);
  std::ifstream status("/proc/self/status");
  std::string line;
  uint64_t vm_kb = 0;
  while (std::getline(status, line))
    if (line.rfind("VmSize:", 0) == 0) vm_kb = std::stoull(line.substr(7));
  ASSERT_GT(vm_kb, 0u);
  // 256 MB above what is mapped now and what the worker threads will reserve (72 MB each, at most 16)
  const uint64_t threads = std::min(16u, std::max(1u, std::thread::hardware_concurrency()));
  const uint64_t cap = vm_kb * 1024 + threads * (uint64_t{72} << 20) + (uint64_t{256} << 20);
  if (saved.rlim_max != RLIM_INFINITY && saved.rlim_max < cap) GTEST_SKIP() << "hard limit too low";
  rlimit lowered = saved;
  lowered.rlim_cur = cap;
  ASSERT_EQ(setrlimit(RLIMIT_AS, &lowered), 0);
  const MemoryLimit limited = detect_available_memory();
  ASSERT_EQ(setrlimit(RLIMIT_AS, &saved), 0);
  EXPECT_LE(limited.bytes, uint64_t{256} << 20);
  EXPECT_GT(limited.bytes, uint64_t{200} << 20);
  EXPECT_NE(limited.source.find("ulimit -v"), std::string::npos) << limited.source;
}

}  // namespace
}  // namespace fenestra
