// Outputs written all or nothing, checked before the work, never over an input or a non-regular
// file; and cancellation of the daylight build and of the exact evaluation.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "daylight/daylight.h"
#include "format/atomic_file.h"
#include "solve/nnls.h"
#include "test_scenes.h"
#include "trace/contributions.h"

namespace fenestra {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

std::set<std::string> listing(const TempDir& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir.path())) names.insert(e.path().filename().string());
  return names;
}

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

FileWriter text(const std::string& t) {
  return [t](std::ostream& o) { o << t; };
}

::testing::AssertionResult refused(const std::function<void()>& f, const std::vector<std::string>& needles) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    for (const auto& n : needles)
      if (what.find(n) == std::string::npos)
        return ::testing::AssertionFailure() << "message lacks '" << n << "': " << what;
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "not refused";
}

TEST(AtomicFiles, APairIsWrittenWholeAndLeavesNoTemporaries) {
  TempDir dir;
  write_files_atomically({{dir.file("a.npz"), text("arrays")}, {dir.file("a.json"), text("{}")}});
  EXPECT_EQ(read(dir.file("a.npz")), "arrays");
  EXPECT_EQ(read(dir.file("a.json")), "{}");
  EXPECT_EQ(listing(dir), (std::set<std::string>{"a.npz", "a.json"}));
  // Replacing existing files.
  write_atomically(dir.file("a.json"), text("{\"v\": 2}"));
  EXPECT_EQ(read(dir.file("a.json")), "{\"v\": 2}");
  EXPECT_EQ(listing(dir).size(), 2u);
}

TEST(AtomicFiles, AFailureAnywhereLeavesTheDirectoryAsItWas) {
  TempDir dir;
  dir.write("old.json", "old");
  const auto before = listing(dir);
  const FileWriter fails = [](std::ostream& o) {
    o << "half";
    throw std::runtime_error("writer failed");
  };
  // The second file fails: the first is not left behind, and an existing target keeps its content.
  EXPECT_THROW(write_files_atomically({{dir.file("new.npz"), text("arrays")}, {dir.file("old.json"), fails}}),
               std::runtime_error);
  EXPECT_EQ(listing(dir), before);
  EXPECT_EQ(read(dir.file("old.json")), "old");
  // The second path is refused before anything is written.
  EXPECT_TRUE(refused([&] { write_files_atomically({{dir.file("x.exr"), text("map")}, {dir.file("missing/x.json"), text("{}")}}); },
                      {"missing/x.json", "does not exist"}));
  EXPECT_EQ(listing(dir), before);
  // A stream error (the device is full, here: the writer sets badbit) fails the set too.
  EXPECT_THROW(write_files_atomically({{dir.file("y.json"), [](std::ostream& o) { o.setstate(std::ios::badbit); }}}),
               std::invalid_argument);
  EXPECT_EQ(listing(dir), before);
}

TEST(AtomicFiles, AnInterruptBeforeTheRenamesWritesNothing) {
  TempDir dir;
  Progress interrupt;
  interrupt.cancel();
  EXPECT_THROW(write_files_atomically({{dir.file("a.npz"), text("a")}, {dir.file("a.json"), text("b")}}, {}, &interrupt),
               Cancelled);
  EXPECT_TRUE(listing(dir).empty());
  // The same through the process-wide interrupt the command line sets.
  set_write_interrupt(&interrupt);
  EXPECT_THROW(write_atomically(dir.file("b.json"), text("b")), Cancelled);
  set_write_interrupt(nullptr);
  EXPECT_TRUE(listing(dir).empty());
  write_atomically(dir.file("b.json"), text("b"));
  EXPECT_EQ(listing(dir), (std::set<std::string>{"b.json"}));
}

TEST(OutputPaths, RefusesWhatIsNotARegularFileOrIsAnInput) {
  TempDir dir;
  dir.write("scene.json", "{}");
  dir.write("target.json", "t");
  fs::create_symlink(dir.file("target.json"), dir.file("link.json"));
  fs::create_symlink(dir.file("nowhere.json"), dir.file("dangling.json"));
  ASSERT_EQ(::mkfifo(dir.file("fifo.json").c_str(), 0600), 0);
  fs::create_directory(dir.file("sub"));
  fs::create_hard_link(dir.file("scene.json"), dir.file("hard.json"));
  const auto before = listing(dir);

  EXPECT_TRUE(refused([&] { check_output_path(dir.file("link.json")); }, {"link.json", "symbolic link"}));
  EXPECT_TRUE(refused([&] { check_output_path(dir.file("dangling.json")); }, {"symbolic link"}));
  EXPECT_TRUE(refused([&] { check_output_path(dir.file("fifo.json")); }, {"fifo.json", "not a regular file"}));
  EXPECT_TRUE(refused([&] { check_output_path("/dev/null"); }, {"/dev/null", "not a regular file"}));
  EXPECT_TRUE(refused([&] { check_output_path(dir.file("sub")); }, {"is a directory"}));
  EXPECT_TRUE(refused([&] { check_output_path(dir.file("nodir/out.json")); }, {"nodir", "does not exist"}));
  EXPECT_TRUE(refused([&] { check_output_path(dir.file("target.json/out.json")); }, {"not a directory"}));
  EXPECT_TRUE(refused([&] { check_output_path(""); }, {"empty"}));
  // Inputs, however they are spelled (relative, through "..", a hard link).
  const std::string scene = dir.file("scene.json");
  EXPECT_TRUE(refused([&] { check_output_path(scene, {scene}); }, {"scene.json", "input", "refusing"}));
  EXPECT_TRUE(refused([&] { check_output_path(dir.file("sub/../scene.json"), {scene}); }, {"input file '" + scene + "'"}));
  EXPECT_TRUE(refused([&] { check_output_path(dir.file("hard.json"), {scene}); }, {"hard.json", scene}));
  EXPECT_NO_THROW(check_output_path(dir.file("target.json"), {scene}));
  EXPECT_NO_THROW(check_output_path(dir.file("new.json"), {scene}));
  // The same output twice.
  EXPECT_TRUE(refused([&] { check_output_paths({dir.file("a.exr"), dir.file("sub/../a.exr")}); }, {"also the output"}));
  // Nothing was touched: the FIFO is still a FIFO, the link still a link.
  EXPECT_EQ(listing(dir), before);
  EXPECT_TRUE(fs::is_fifo(dir.file("fifo.json")));
  EXPECT_TRUE(fs::is_symlink(dir.file("link.json")));
  EXPECT_THROW(write_atomically(dir.file("fifo.json"), text("x")), std::invalid_argument);
  EXPECT_THROW(write_atomically(dir.file("link.json"), text("x")), std::invalid_argument);
  EXPECT_EQ(read(dir.file("target.json")), "t");
}

TEST(OutputPaths, TemporariesOfFinishedProcessesAreRemovedByTheNextWrite) {
  TempDir dir;
  // A process id that cannot be running (above the kernel's pid_max of 2^22).
  const std::string stale = ".out.json.fenestra-99999999-0.tmp";
  const std::string live = ".out.json.fenestra-" + std::to_string(::getppid()) + "-0.tmp";
  const std::string unrelated = ".notes.tmp";
  dir.write(stale, "x");
  dir.write(live, "x");
  dir.write(unrelated, "x");
  write_atomically(dir.file("out.json"), text("{}"));
  EXPECT_EQ(listing(dir), (std::set<std::string>{"out.json", live, unrelated}));
}

TEST(Cancel, TheDaylightBuildStopsBetweenSteps) {
  DaylightSettings s;
  s.place = {37.98, 23.73, 0.0};
  s.time_zone = TimeZone::fixed(3.0);
  s.date = parse_date("2026-01-01");
  s.date_end = parse_date("2026-12-31");  // a year of 15-minute steps: minutes to build
  s.start_minutes = 6 * 60, s.end_minutes = 18 * 60;
  Progress progress;
  std::atomic<bool> threw{false};
  std::chrono::steady_clock::time_point ended;
  std::thread worker([&] {
    try {
      make_daylight(s, &progress);
    } catch (const Cancelled&) {
      threw = true;
    }
    ended = std::chrono::steady_clock::now();
  });
  while (progress.fraction() == 0.0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(progress.status(), "building the daylight sky");
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const auto cancelled = std::chrono::steady_clock::now();
  progress.cancel();
  worker.join();
  EXPECT_TRUE(threw);
  const double latency = std::chrono::duration<double>(ended - cancelled).count();
  EXPECT_LT(latency, 2.0);
  std::printf("[ timing   ] daylight build cancel latency %.3f s\n", latency);
}

TEST(Cancel, TheLinearStartPollsTheFlag) {
  const Eigen::MatrixXd A = Eigen::MatrixXd::Random(20, 40).cwiseAbs();
  const Eigen::VectorXd b = A * Eigen::VectorXd::Ones(40);
  Progress running;
  EXPECT_NO_THROW(nnls(A, b, 0, 0.0, &running));
  Progress cancelled;
  cancelled.cancel();
  EXPECT_THROW(nnls(A, b, 0, 0.0, &cancelled), Cancelled);
}

TEST(Cancel, TheExactEvaluationPollsTheFlag) {
  Contributions c;
  c.E = Eigen::MatrixXd::Zero(2, 3);
  c.records.resize(2);
  for (auto& r : c.records) r.path_begin.assign(100001, 0);  // empty paths
  const std::vector<uint8_t> open(3, 1);
  Progress running;
  EXPECT_NO_THROW(c.evaluate(open, &running));
  Progress cancelled;
  cancelled.cancel();
  EXPECT_THROW(c.evaluate(open, &cancelled), Cancelled);
}

}  // namespace
}  // namespace fenestra
