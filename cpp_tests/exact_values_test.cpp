// The solver's exact values of open-element sets: evaluated from a reference set (only the paths
// that met a changed element evaluated again), they equal a full evaluation of the records.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "annual/annual_contributions.h"
#include "solve/exact_values.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/path_record.h"

namespace fenestra {
namespace {

using test::room_with_neighbour;
using test::TempDir;

// A seeded walk over open sets, flipping one to a few elements at a time (evaluated from the
// reference) and now and then many (evaluated in full, and the new reference).
TEST(ExactValues, EqualAFullEvaluationNearAndFarFromTheReference) {
  TempDir dir;
  const Scene scene = room_with_neighbour(dir, 1 << 9);
  const Contributions c = compute_contributions(scene);
  ExactValues exact(c, nullptr);
  std::mt19937 rng(11);
  std::vector<uint8_t> open(c.element_count(), 0);
  const int sets = 60;
  for (int set = 0; set < sets; ++set) {
    const size_t flips = set % 10 == 9 ? c.element_count() / 2 : 1 + rng() % 3;
    for (size_t f = 0; f < flips; ++f) open[rng() % open.size()] ^= 1;
    const SensorValues& got = exact(open);
    const SensorValues full = c.evaluate(open);
    for (Eigen::Index i = 0; i < full.value.size(); ++i) {
      ASSERT_NEAR(got.value[i], full.value[i], 1e-12 * (1.0 + full.value[i])) << "set " << set << " sensor " << i;
      ASSERT_NEAR(got.standard_error[i], full.standard_error[i], 1e-9 * (1.0 + full.standard_error[i]))
          << "set " << set << " sensor " << i;
    }
  }
  // Most sensor evaluations from the sensor's reference; the far sets, and the first, in full.
  std::printf("[ exact    ] %zu of %zu sensor evaluations in full\n", exact.full_evaluations(), exact.sensor_evaluations());
  EXPECT_LT(exact.full_evaluations(), exact.sensor_evaluations() / 2);
  EXPECT_GT(exact.full_evaluations(), c.sensor_count() * (sets / 10));
  // The cost model counts the index as kExactValuesIndexShare of the path records (docs/cost.md).
  size_t record_bytes = 0;
  for (const SensorRecord& r : c.records) record_bytes += r.memory_bytes();
  EXPECT_LT(static_cast<double>(exact.memory_bytes()), 0.5 * static_cast<double>(record_bytes));
  EXPECT_GT(static_cast<double>(exact.memory_bytes()), 0.05 * static_cast<double>(record_bytes));
}


// Paths of the records that met element k, over all sensors (each path once).
size_t paths_meeting(const Contributions& c, const std::vector<int32_t>& elements) {
  size_t n = 0;
  std::vector<int32_t> met;
  for (const SensorRecord& r : c.records)
    for (size_t p = 0; p < r.path_count(); ++p) {
      path_elements(r, p, &met);
      n += std::any_of(elements.begin(), elements.end(),
                       [&](int32_t k) { return std::find(met.begin(), met.end(), k) != met.end(); });
    }
  return n;
}

// Every element closed, then every one open (the index is built on the second): returns every
// third element open, far from both, not yet evaluated.
std::vector<uint8_t> after_two_far_sets(ExactValues& exact, size_t elements) {
  std::vector<uint8_t> open(elements, 0);
  exact(open);
  exact(std::vector<uint8_t>(elements, 1));
  for (size_t k = 0; k < elements; k += 3) open[k] = 1;
  return open;
}

void expect_full_evaluations_values(const Contributions& c, const std::vector<uint8_t>& open, const SensorValues& got) {
  const SensorValues full = c.evaluate(open);
  for (Eigen::Index i = 0; i < full.value.size(); ++i)
    EXPECT_NEAR(got.value[i], full.value[i], 1e-12 * (1.0 + full.value[i])) << "sensor " << i;
}

// A search steps from set to set: each step re-evaluates the paths of its own change only, not
// those of every change since the last set evaluated in full.
TEST(ExactValues, AStepReEvaluatesOnlyThePathsOfItsOwnChange) {
  TempDir dir;
  const Scene scene = room_with_neighbour(dir, 1 << 9);
  const Contributions c = compute_contributions(scene);
  ExactValues exact(c, nullptr);
  std::vector<uint8_t> open = after_two_far_sets(exact, c.element_count());
  const size_t full_before = exact.full_evaluations();
  exact(open);  // far from both: in full
  ASSERT_EQ(exact.full_evaluations() - full_before, c.sensor_count());
  // Two single-element steps, on elements that each met some paths but not the same ones.
  const int32_t first = 1, second = static_cast<int32_t>(open.size()) - 2;
  ASSERT_GT(paths_meeting(c, {first}), 0u);
  ASSERT_GT(paths_meeting(c, {first, second}), paths_meeting(c, {second}));
  open[first] ^= 1;
  exact(open);
  open[second] ^= 1;
  const size_t before = exact.path_evaluations();
  const SensorValues& got = exact(open);
  EXPECT_EQ(exact.path_evaluations() - before, paths_meeting(c, {second}));
  expect_full_evaluations_values(c, open, got);
}

// A search scores the neighbours of its best set one after another: each starts from the best
// (one move away), the reference the neighbour before started from, not from that neighbour (two
// moves away).
TEST(ExactValues, ANeighbourStartsFromTheSetItsPredecessorStartedFrom) {
  TempDir dir;
  const Scene scene = room_with_neighbour(dir, 1 << 9);
  const Contributions c = compute_contributions(scene);
  ExactValues exact(c, nullptr);
  const std::vector<uint8_t> best = after_two_far_sets(exact, c.element_count());
  exact(best);  // in full
  const int32_t first = 1, second = static_cast<int32_t>(best.size()) - 2;
  ASSERT_GT(paths_meeting(c, {first, second}), paths_meeting(c, {second}));
  std::vector<uint8_t> one = best, two = best;
  one[first] ^= 1;
  two[second] ^= 1;
  exact(one);
  const size_t before = exact.path_evaluations();
  const SensorValues& got = exact(two);
  EXPECT_EQ(exact.path_evaluations() - before, paths_meeting(c, {second}));
  expect_full_evaluations_values(c, two, got);
}

// The screen's values, from one path in four of those that changed since a sensor's reference:
// each is within its own sampling error of the exact value (z scores over many sets and sensors,
// under a sun whose few paths carry much of the light), for well under half the path
// evaluations, and the exact values that follow (taking the sampled paths' values) are bit for
// bit those without the screen.
TEST(ExactValues, SampledValuesAreWithinTheirOwnSamplingErrorOfTheExactOnes) {
  TempDir dir;
  const Scene scene = room_with_neighbour(dir, 1 << 14);
  const Contributions c = compute_contributions(scene);
  ExactValues screened(c, nullptr), unscreened(c, nullptr);
  std::vector<uint8_t> best(c.element_count(), 0);
  for (size_t k = 0; k < best.size(); k += 4) best[k] = 1;
  screened(best);
  unscreened(best);
  std::mt19937 rng(3);
  double squares = 0.0, worst = 0.0;
  size_t sampled_sensors = 0, exact_paths = 0;
  for (int set = 0; set < 60; ++set) {
    std::vector<uint8_t> candidate = best;
    for (int f = 0; f < 6; ++f) candidate[rng() % candidate.size()] ^= 1;
    const size_t paths_before = screened.path_evaluations();
    const SensorValues s = screened.sampled(candidate, 4);
    ASSERT_EQ(screened.path_evaluations(), paths_before);
    const SensorValues e = screened(candidate);
    exact_paths += screened.path_evaluations() - paths_before;
    const SensorValues& u = unscreened(candidate);
    for (Eigen::Index i = 0; i < e.value.size(); ++i) {
      ASSERT_EQ(e.value[i], u.value[i]) << "set " << set << " sensor " << i;
      if (s.standard_error[i] > 0.0) {
        const double z = (s.value[i] - e.value[i]) / s.standard_error[i];
        squares += z * z, worst = std::max(worst, std::abs(z)), ++sampled_sensors;
      } else {
        EXPECT_NEAR(s.value[i], e.value[i], 1e-9 * (1.0 + e.value[i])) << "set " << set << " sensor " << i;
      }
    }
    if (set % 6 == 5) best = candidate;  // the search moves on now and then
  }
  std::printf("[ sampled  ] %zu sampled sensor values: mean z^2 %.3f, worst |z| %.2f; %zu of %zu paths\n",
              sampled_sensors, squares / double(sampled_sensors), worst, screened.sampled_path_evaluations(), exact_paths);
  ASSERT_GT(sampled_sensors, 100u);
  // Mean z^2 of n standard normals: 1 with standard deviation sqrt(2 / n).
  const double spread = std::sqrt(2.0 / double(sampled_sensors));
  EXPECT_NEAR(squares / double(sampled_sensors), 1.0, 4.0 * spread);
  EXPECT_LT(worst, 5.0);
  // Each set scored right after its sample takes the sampled paths' values, bit for bit (above).
  EXPECT_GT(screened.sampled_paths_reused(), screened.sampled_path_evaluations() * 9 / 10);
  EXPECT_LE(screened.sampled_paths_reused(), screened.sampled_path_evaluations());
  EXPECT_LT(screened.sampled_path_evaluations(), exact_paths / 2);
  EXPECT_GT(screened.sampled_path_evaluations(), exact_paths / 8);
}

// With a share of one every changed path is evaluated: the exact values, with no sampling error.
TEST(ExactValues, SampledWithAShareOfOneAreTheExactValues) {
  TempDir dir;
  const Scene scene = room_with_neighbour(dir, 1 << 9);
  const Contributions c = compute_contributions(scene);
  ExactValues exact(c, nullptr);
  const std::vector<uint8_t> open = after_two_far_sets(exact, c.element_count());
  const SensorValues s = exact.sampled(open, 1);
  EXPECT_EQ(s.standard_error.cwiseAbs().maxCoeff(), 0.0);
  expect_full_evaluations_values(c, open, s);
}

}  // namespace
}  // namespace fenestra
