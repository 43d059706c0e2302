// The solver linearises about the same sets again and again: the flip effects are kept by the set
// they were taken about, equal to a fresh computation, the least recently used dropped first, and
// never one a cancelled computation left partly filled.
#include <gtest/gtest.h>

#include <vector>

#include "solve/flip_effects_cache.h"

namespace fenestra {
namespace {

// A distinct matrix per set (its first entry counts the computations).
struct Counted {
  int computed = 0;
  Eigen::MatrixXd operator()(const std::vector<uint8_t>& about) {
    ++computed;
    Eigen::MatrixXd m = Eigen::MatrixXd::Constant(2, 3, static_cast<double>(about[0] + 10 * about[1]));
    m(0, 0) = computed;
    return m;
  }
};

TEST(FlipEffectsCache, AKnownSetIsNotComputedAgainAndGivesTheSameMatrix) {
  FlipEffectsCache cache;
  Counted f;
  const std::vector<uint8_t> a = {1, 0}, b = {0, 1};
  const Eigen::MatrixXd first = cache.about(a, [&] { return f(a); });
  const Eigen::MatrixXd other = cache.about(b, [&] { return f(b); });
  const Eigen::MatrixXd again = cache.about(a, [&] { return f(a); });
  EXPECT_EQ(f.computed, 2);
  EXPECT_EQ(again, first);
  EXPECT_NE(other, first);
  EXPECT_EQ(cache.hits(), 1u);
  EXPECT_EQ(cache.misses(), 2u);
  EXPECT_EQ(cache.memory_bytes(), 2u * 6u * sizeof(double));
}

TEST(FlipEffectsCache, TheLeastRecentlyUsedGoesFirst) {
  FlipEffectsCache cache(size_t{1} << 20, 2);  // two kept
  Counted f;
  const std::vector<uint8_t> a = {1, 0}, b = {0, 1}, c = {1, 1};
  cache.about(a, [&] { return f(a); });
  cache.about(b, [&] { return f(b); });
  cache.about(a, [&] { return f(a); });  // a used after b: b is the older
  cache.about(c, [&] { return f(c); });  // drops b
  EXPECT_EQ(f.computed, 3);
  cache.about(a, [&] { return f(a); });
  EXPECT_EQ(f.computed, 3);
  cache.about(b, [&] { return f(b); });
  EXPECT_EQ(f.computed, 4);
  EXPECT_EQ(cache.memory_bytes(), 2u * 6u * sizeof(double));
}

TEST(FlipEffectsCache, TheByteBudgetBoundsWhatIsKept) {
  const size_t one = 6 * sizeof(double);
  FlipEffectsCache cache(one + one / 2, 16);  // room for one matrix
  Counted f;
  const std::vector<uint8_t> a = {1, 0}, b = {0, 1};
  cache.about(a, [&] { return f(a); });
  cache.about(b, [&] { return f(b); });
  EXPECT_EQ(cache.memory_bytes(), one);
  cache.about(b, [&] { return f(b); });
  EXPECT_EQ(f.computed, 2);
  cache.about(a, [&] { return f(a); });
  EXPECT_EQ(f.computed, 3);
  FlipEffectsCache too_small(one - 1, 16);
  too_small.about(a, [&] { return f(a); });
  EXPECT_EQ(too_small.memory_bytes(), 0u);
}

TEST(FlipEffectsCache, AnAnswerNotToKeepIsComputedAgain) {
  FlipEffectsCache cache;
  Counted f;
  const std::vector<uint8_t> a = {1, 0};
  cache.about(a, [&] { return f(a); }, [] { return false; });  // e.g. cancelled halfway
  cache.about(a, [&] { return f(a); });
  EXPECT_EQ(f.computed, 2);
  EXPECT_EQ(cache.hits(), 0u);
}

}  // namespace
}  // namespace fenestra
