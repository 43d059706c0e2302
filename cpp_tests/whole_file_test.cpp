// Whole files read into memory (util/whole_file.h), and every reader built on it telling a failed
// allocation from the end of its file: under an address-space limit too small for the file, each
// throws OutOfMemory naming the file, where iostreams used to hand back a part of the file (a mesh
// of 12 triangles for one of 2 million) as if it were the whole.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cstdio>
#include <fstream>
#include <functional>

#include "daylight/weather_file.h"
#include "io/results.h"
#include "scene/mesh.h"
#include "scene/scene.h"
#include "test_scenes.h"
#include "util/cost_context.h"
#include "util/out_of_memory.h"
#include "util/whole_file.h"

namespace fenestra {
namespace {

using test::TempDir;

constexpr size_t kBigFile = 96u << 20;  // bytes: larger than the headroom the limit leaves
constexpr size_t kHeadroom = 48u << 20;

// A file of `bytes` bytes that starts with `head` and is filled out with `filler` lines.
void write_file(const std::string& path, const std::string& head, const std::string& filler, size_t bytes) {
  std::ofstream out(path, std::ios::binary);
  out << head;
  size_t written = head.size();
  while (written + filler.size() <= bytes) out << filler, written += filler.size();
}

// This process's address space in use now (VmSize), in bytes.
size_t address_space_in_use() {
  std::ifstream status("/proc/self/status");
  std::string key;
  size_t kb = 0;
  while (status >> key) {
    if (key == "VmSize:") {
      status >> kb;
      return kb << 10;
    }
    status.ignore(1 << 12, '\n');
  }
  return 0;
}

// In a forked child (a death test): limits the address space to what is in use plus kHeadroom,
// runs `read` and exits 0 when it throws OutOfMemory, printing its message; 1 for any other end.
// The cost checks are told of plenty of memory (as --max-memory 1T does): the readers themselves
// are under test.
[[noreturn]] void read_under_limit(const std::function<void()>& read) {
  set_cost_context({uint64_t{1} << 40, CostCommand::Any});
  const rlim_t limit = address_space_in_use() + kHeadroom;
  const struct rlimit rl{limit, limit};
  setrlimit(RLIMIT_AS, &rl);
  try {
    read();
    std::fprintf(stderr, "read without an error\n");
  } catch (const OutOfMemory& e) {
    std::fprintf(stderr, "%s\n", e.what());
    std::_Exit(0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "another error: %s\n", e.what());
  }
  std::_Exit(1);
}

TEST(WholeFile, ReadsEveryByte) {
  TempDir dir;
  const std::string bytes("line\r\nnul \0 inside\n\xff\xfe no end", 30);
  std::ofstream(dir.file("f.bin"), std::ios::binary) << bytes;
  EXPECT_EQ(read_whole_file(dir.file("f.bin"), "test file"), bytes);
  std::ofstream(dir.file("empty"), std::ios::binary);
  EXPECT_EQ(read_whole_file(dir.file("empty"), "test file"), "");
}

TEST(WholeFile, NamesWhatCannotBeOpened) {
  TempDir dir;
  try {
    read_whole_file(dir.file("missing.obj"), "geometry file");
    FAIL() << "read a missing file";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open geometry file '" + dir.file("missing.obj") + "'"),
              std::string::npos)
        << e.what();
  }
  try {
    read_whole_file(dir.path().string(), "scene file");
    FAIL() << "read a directory";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scene file"), std::string::npos) << e.what();
  }
}

TEST(WholeFileDeathTest, OutOfMemoryIsNotTheEndOfTheFile) {
  TempDir dir;
  write_file(dir.file("big.bin"), "", std::string(1023, 'x') + "\n", kBigFile);
  EXPECT_EXIT(read_under_limit([&] { read_whole_file(dir.file("big.bin"), "test file"); }),
              ::testing::ExitedWithCode(0), "out of memory while reading test file '.*big.bin' \\(");
}

TEST(WholeFileDeathTest, EveryReaderTellsOutOfMemoryFromTheEnd) {
  TempDir dir;
  // A triangle, then far more vertices than the limit leaves room for.
  write_file(dir.file("big.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "v 0.125 0.25 0.5\n", kBigFile);
  EXPECT_EXIT(read_under_limit([&] { load_obj(dir.file("big.obj"), {"default"}); }), ::testing::ExitedWithCode(0),
              "out of memory while reading geometry file '.*big.obj'");

  write_file(dir.file("big.epw"), "LOCATION,Somewhere\n", std::string(200, ',') + "\n", kBigFile);
  EXPECT_EXIT(read_under_limit([&] { read_weather(dir.file("big.epw")); }), ::testing::ExitedWithCode(0),
              "out of memory while reading weather file '.*big.epw'");

  write_file(dir.file("openings.json"), "{\"openings\": []", std::string(1023, ' ') + "\n", kBigFile);
  EXPECT_EXIT(read_under_limit([&] { read_openings(dir.file("openings.json"), SiteFrame{}); }), ::testing::ExitedWithCode(0),
              "out of memory while reading openings file '.*openings.json'");

  write_file(dir.file("scene.json"), "{\"fenestra\": 1", std::string(1023, ' ') + "\n", kBigFile);
  EXPECT_EXIT(read_under_limit([&] { load_scene(dir.file("scene.json")); }), ::testing::ExitedWithCode(0),
              "out of memory while reading scene file '.*scene.json'");
}

TEST(WholeFile, AReaderPassesOnWhatItNames) {
  // out_of_memory_while names what was being done, and keeps a deeper reader's own message.
  try {
    out_of_memory_while("reading a scene", [] { throw std::bad_alloc(); });
    FAIL();
  } catch (const OutOfMemory& e) {
    EXPECT_STREQ(e.what(), "out of memory while reading a scene");
  }
  try {
    out_of_memory_while("reading a scene", [] { throw OutOfMemory("out of memory while reading geometry file 'a'"); });
    FAIL();
  } catch (const OutOfMemory& e) {
    EXPECT_STREQ(e.what(), "out of memory while reading geometry file 'a'");
  }
}

}  // namespace
}  // namespace fenestra
