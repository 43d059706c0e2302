#include "solve/constraint_costs.h"

#include <gtest/gtest.h>

namespace fenestra {
namespace {

OpeningConstraints automatic_like() {
  OpeningConstraints c;
  c.min_width = c.min_height = 0.5;
  c.margin = 0.2;
  c.sill_min = 0.3;
  c.head_clearance = 0.2;
  c.min_gap = 0.5;
  return c;
}

// Errors with a closed form: 0.2 while the margin and the sill both hold, 0.05 when either is
// lifted; the gap alone adds 0.01.
double door_error(const OpeningConstraints& c) {
  return (c.margin > 0.0 && c.sill_min > 0.0 ? 0.2 : 0.05) + (c.min_gap > 0.0 ? 0.01 : 0.0);
}

TEST(ConstraintCosts, EachFamilyLiftedAloneLeastErrorFirst) {
  int calls = 0;
  const std::vector<ConstraintCost> costs = constraint_costs(
      automatic_like(), [&](const OpeningConstraints& c) { return ++calls, door_error(c); }, 0.02, 0.21);
  // Four families are set: sizes, margin, sills and heads, gap.
  ASSERT_EQ(costs.size(), 4u);
  EXPECT_EQ(calls, 4);  // the best alone (0.06) is below halfway (0.115): no joint search
  EXPECT_DOUBLE_EQ(costs[0].error_without, 0.06);
  EXPECT_DOUBLE_EQ(costs[1].error_without, 0.06);
  EXPECT_EQ(costs[0].keys, (std::vector<std::string>{"margin"}));
  EXPECT_EQ(costs[1].keys, (std::vector<std::string>{"sill_min", "head_clearance"}));  // only the keys set
  EXPECT_DOUBLE_EQ(costs[2].error_without, 0.2);
  EXPECT_DOUBLE_EQ(costs[3].error_without, 0.21);
}

TEST(ConstraintCosts, LimitsThatBindTogetherAreLiftedTogether) {
  // 0.2 while either the margin or the sill holds: neither alone explains the cost.
  auto both = [](const OpeningConstraints& c) { return c.margin > 0.0 || c.sill_min > 0.0 ? 0.2 : 0.03; };
  int calls = 0;
  const std::vector<ConstraintCost> costs =
      constraint_costs(automatic_like(), [&](const OpeningConstraints& c) { return ++calls, both(c); }, 0.02, 0.2);
  ASSERT_EQ(costs.size(), 6u);  // four families, the two that bind, all at once
  EXPECT_EQ(calls, 4 + 4 + 2);
  EXPECT_EQ(costs[0].keys, (std::vector<std::string>{"margin", "sill_min", "head_clearance"}));
  EXPECT_DOUBLE_EQ(costs[0].error_without, 0.03);
  EXPECT_EQ(costs[1].keys.size(), 6u);  // every key set
  EXPECT_DOUBLE_EQ(costs[1].error_without, 0.03);
  const std::string warning = constraint_cost_warning(0.02, 0.2, costs);
  EXPECT_NE(warning.find("at 20.0 % on the element grid, the free answer at 2.0 %"), std::string::npos) << warning;
  EXPECT_NE(warning.find("without margin, sill_min, head_clearance it would be 3.0 %"), std::string::npos) << warning;
}

TEST(ConstraintCosts, LimitsThatOnlyCostTogetherAreLiftedAllAtOnce) {
  // Each family adds 0.05: none alone blocks, none alone explains the cost.
  auto sum = [](const OpeningConstraints& c) {
    return 0.01 + 0.05 * ((c.min_width > 0.0) + (c.margin > 0.0) + (c.sill_min > 0.0) + (c.min_gap > 0.0));
  };
  const std::vector<ConstraintCost> costs = constraint_costs(automatic_like(), sum, 0.01, 0.21);
  ASSERT_EQ(costs.size(), 5u);
  EXPECT_EQ(costs[0].keys, (std::vector<std::string>{"min_width", "min_height", "margin", "sill_min",
                                                     "head_clearance", "min_gap"}));
  EXPECT_DOUBLE_EQ(costs[0].error_without, 0.01);
  EXPECT_DOUBLE_EQ(costs[1].error_without, 0.16);
}

TEST(ConstraintCosts, CatalogueAndPerPanelLimitsCount) {
  OpeningConstraints c;
  c.catalogue.walls = {{1.2, 1.5}};
  c.per_panel = {OpeningConstraints{}, OpeningConstraints{}};
  c.per_panel[1].min_gap = 1.0;
  const std::vector<ConstraintCost> costs =
      constraint_costs(c, [](const OpeningConstraints& x) { return x.catalogue.empty() ? 0.1 : 0.3; }, 0.0, 0.3);
  ASSERT_EQ(costs.size(), 2u);
  EXPECT_EQ(costs[0].keys, (std::vector<std::string>{"catalogue"}));
  EXPECT_EQ(costs[1].keys, (std::vector<std::string>{"min_gap"}));
  EXPECT_TRUE(constraint_costs(OpeningConstraints{}, [](const OpeningConstraints&) { return 1.0; }, 0.0, 1.0).empty());
}

TEST(ConstraintCosts, SaysSoWhenLiftingTheLimitsDoesNotHelp) {
  // The search within the limits, not the limits, keeps the answer from the goals.
  const std::vector<ConstraintCost> costs =
      constraint_costs(automatic_like(), [](const OpeningConstraints&) { return 0.2; }, 0.03, 0.2);
  ASSERT_EQ(costs.size(), 5u);  // four families, then all at once (none binds more than another)
  const std::string warning = constraint_cost_warning(0.03, 0.2, costs);
  EXPECT_NE(warning.find("lifting the constraints, alone or together, does not bring it lower"), std::string::npos)
      << warning;
  EXPECT_EQ(warning.find("without"), std::string::npos) << warning;
}

TEST(ConstraintCosts, OnlyWhenTheConstraintsCostMuch) {
  EXPECT_FALSE(constraints_cost_much(0.02, 0.035));  // within 2 points
  EXPECT_FALSE(constraints_cost_much(0.20, 0.24));   // within 25 %
  EXPECT_TRUE(constraints_cost_much(0.02, 0.05));
}

}  // namespace
}  // namespace fenestra
