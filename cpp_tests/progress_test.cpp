// Progress (util/progress.h): a stage's status line held over the traces it runs, which restart
// only the count; nested stages give the line back to the outer one; released, traces name
// themselves again.
#include "util/progress.h"

#include <gtest/gtest.h>

namespace fenestra {
namespace {

TEST(Progress, AStageHoldsItsLineOverTheTracesItRuns) {
  Progress p;
  p.start("tracing contribution paths", 10);
  p.advance(10);
  {
    const StageStatus stage(&p, "solving: checking with real cutters");
    EXPECT_EQ(p.status(), "solving: checking with real cutters");
    EXPECT_DOUBLE_EQ(p.fraction(), 0.0);
    p.start("tracing the scene with its openings", 4);  // a trace within the stage
    p.advance(2);
    EXPECT_EQ(p.status(), "solving: checking with real cutters");
    EXPECT_DOUBLE_EQ(p.fraction(), 0.5);  // its count, under the stage's name
    {
      const StageStatus inner(&p, "solving: fewer openings");
      p.start("tracing the scene with its openings", 1);
      EXPECT_EQ(p.status(), "solving: fewer openings");
    }
    p.start("tracing the scene with its openings", 1);  // still held by the outer stage
    EXPECT_EQ(p.status(), "solving: fewer openings");
  }
  p.start("tracing the scene with its openings", 1);
  EXPECT_EQ(p.status(), "tracing the scene with its openings");
  const StageStatus none(nullptr, "no progress to hold");  // a stage without progress does nothing
}

}  // namespace
}  // namespace fenestra
