// A study in shards of sensors (fenestra.distributed): every shard's rows, records and values
// equal the whole study's bit for bit, and T assembled from the shards' entries equals its T.
#include <gtest/gtest.h>

#include <random>

#include "annual/annual_contributions.h"
#include "solve/exact_values.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"
#include "trace/transport_matrix.h"

namespace fenestra {
namespace {

using test::room_with_neighbour;
using test::TempDir;

bool same(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && (a.array() == b.array()).all();
}

TEST(SensorRange, ShardsEqualTheWholeStudyBitForBit) {
  TempDir dir;
  Scene scene = room_with_neighbour(dir, 1 << 9);
  const Contributions whole = compute_contributions(scene);
  // Uneven blocks, and different thread counts (results must not depend on them).
  const std::vector<SensorRange> blocks = {{0, 1}, {1, 3}, {3, 4}};
  std::vector<TransportEntries> entries;
  for (size_t b = 0; b < blocks.size(); ++b) {
    scene.render.threads = static_cast<int>(b + 1);
    const Contributions shard = compute_contributions(scene, nullptr, /*transport=*/false, blocks[b]);
    const Eigen::Index begin = static_cast<Eigen::Index>(blocks[b].begin), rows = static_cast<Eigen::Index>(blocks[b].size());
    ASSERT_EQ(shard.sensor_count(), blocks[b].size());
    EXPECT_TRUE(same(shard.E, whole.E.middleRows(begin, rows))) << "block " << b;
    EXPECT_TRUE(same(shard.E_stderr, whole.E_stderr.middleRows(begin, rows)));
    EXPECT_TRUE(same(shard.A, whole.A.middleRows(begin, rows)));
    EXPECT_TRUE((shard.all_open.value.array() == whole.all_open.value.segment(begin, rows).array()).all());
    EXPECT_TRUE((shard.closed.standard_error.array() == whole.closed.standard_error.segment(begin, rows).array()).all());
    EXPECT_EQ(shard.T.size(), 0);
    entries.push_back(transport_entries(shard.records));
    const SensorValues cut = evaluate_openings(scene, {}, nullptr, 64, blocks[b]);
    const SensorValues cut_whole = evaluate_openings(scene, {}, nullptr, 64);
    EXPECT_TRUE((cut.value.array() == cut_whole.value.segment(begin, rows).array()).all());
  }
  std::vector<const TransportEntries*> in;
  for (const TransportEntries& e : entries) in.push_back(&e);
  const Eigen::MatrixXd T = transport_matrix_from_entries(in, whole.element_count(), whole.paths_per_sensor, 2, nullptr);
  EXPECT_TRUE(whole.T.any());
  EXPECT_TRUE(same(T, whole.T));
}

// The solver's exact values choose per sensor between a full evaluation and one from the
// sensor's reference, so a shard's sensors get the whole study's numbers bit for bit over any
// sequence of sets (near ones, far ones, repeats).
TEST(SensorRange, ExactValuesOfAShardEqualTheWholeStudysBitForBit) {
  TempDir dir;
  const Scene scene = room_with_neighbour(dir, 1 << 9);
  const Contributions whole = compute_contributions(scene);
  const SensorRange block{1, 3};
  const Contributions shard = compute_contributions(scene, nullptr, false, block);
  ExactValues a(whole, nullptr), b(shard, nullptr);
  std::mt19937 rng(23);
  std::vector<uint8_t> open(whole.element_count(), 0);
  for (int set = 0; set < 40; ++set) {
    const size_t flips = set % 8 == 7 ? open.size() / 2 : 1 + rng() % 3;
    for (size_t f = 0; f < flips; ++f) open[rng() % open.size()] ^= 1;
    const SensorValues& x = a(open);
    const SensorValues& y = b(open);
    for (size_t i = 0; i < block.size(); ++i) {
      const Eigen::Index w = static_cast<Eigen::Index>(block.begin + i), s = static_cast<Eigen::Index>(i);
      ASSERT_EQ(x.value[w], y.value[s]) << "set " << set << " sensor " << w;
      ASSERT_EQ(x.standard_error[w], y.standard_error[s]) << "set " << set << " sensor " << w;
    }
  }
  EXPECT_GT(a.full_evaluations(), 0u);
  EXPECT_LT(a.full_evaluations(), a.sensor_evaluations());  // some from the references
}

TEST(SensorRange, EmptyOrOutOfRangeBlocksAreRefused) {
  TempDir dir;
  const Scene scene = room_with_neighbour(dir, 16);
  EXPECT_THROW(compute_contributions(scene, nullptr, false, {2, 2}), std::invalid_argument);
  EXPECT_THROW(compute_contributions(scene, nullptr, false, {4, 9}), std::invalid_argument);
  TransportEntries bad;
  bad.from = {0}, bad.to = {100000}, bad.value = {1.0f}, bad.sensors = 1;
  EXPECT_THROW(transport_matrix_from_entries({&bad}, 10, 16, 1, nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace fenestra
