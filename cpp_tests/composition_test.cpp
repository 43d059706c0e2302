// Window catalogues and facade composition: which sizes a panel allows, which panels form a
// facade, and the rules' checks.
#include <gtest/gtest.h>

#include "test_scenes.h"

#include "scene/window_catalogue.h"
#include "solve/composition.h"
#include "solve/edge_refinement.h"

namespace fenestra {
namespace {

using Quad = std::array<Vec3, 4>;

OpeningDomain domain_of(const std::vector<Quad>& quads, float element_size = 0.25f) {
  return test::domain_of_quads(quads, element_size);
}

// Two walls in the plane y = 0 (x 0-4 and 5-9, not touching), a wall in x = 0, and a flat roof.
OpeningDomain two_facades_and_a_roof() {
  return domain_of({{Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(4, 0, 3), Vec3(0, 0, 3)},
                    {Vec3(5, 0, 0), Vec3(9, 0, 0), Vec3(9, 0, 3), Vec3(5, 0, 3)},
                    {Vec3(0, 4, 0), Vec3(0, 0, 0), Vec3(0, 0, 3), Vec3(0, 4, 3)},
                    {Vec3(0, 0, 3), Vec3(4, 0, 3), Vec3(4, 4, 3), Vec3(0, 4, 3)}});
}

TEST(WindowCatalogue, WallsTakeSizesAsGivenRoofsEitherWayRound) {
  const OpeningDomain d = two_facades_and_a_roof();
  ASSERT_EQ(d.panels().size(), 4u);
  const Panel* wall = nullptr;
  const Panel* roof = nullptr;
  for (const Panel& p : d.panels()) (is_wall(p) ? wall : roof) = &p;
  ASSERT_TRUE(wall && roof);
  WindowCatalogue c;
  c.walls = {{1.2, 1.5}};
  c.roofs = {{0.78, 1.18}};
  EXPECT_TRUE(c.allows(*wall, 1.2, 1.5));
  EXPECT_TRUE(c.allows(*wall, 1.2 + 5e-5, 1.5));  // within kCatalogueSizeTolerance
  EXPECT_FALSE(c.allows(*wall, 1.5, 1.2));        // a wall window is not turned
  EXPECT_FALSE(c.allows(*wall, 1.2, 1.6));
  EXPECT_TRUE(c.allows(*roof, 0.78, 1.18));
  EXPECT_TRUE(c.allows(*roof, 1.18, 0.78));
  EXPECT_EQ(c.sizes_for(*roof).size(), 2u);
  // A kind of panel without sizes stays free.
  c.roofs.clear();
  EXPECT_TRUE(c.allows(*roof, 3.3, 0.1));
  EXPECT_TRUE(c.sizes_for(*roof).empty());
  EXPECT_THROW(builtin_catalogue("palace"), std::invalid_argument);
  for (const std::string& name : catalogue_names()) EXPECT_FALSE(builtin_catalogue(name).walls.empty()) << name;
}

TEST(Composition, CoplanarWallsFormOneFacadeRoofsNone) {
  const OpeningDomain d = two_facades_and_a_roof();
  const std::vector<int> facade = facades_of(d);
  std::vector<int> south, other;
  for (size_t p = 0; p < d.panels().size(); ++p) {
    const Panel& panel = d.panels()[p];
    if (!is_wall(panel)) EXPECT_EQ(facade[p], -1);
    else if (std::abs(panel.normal.y()) > 0.5f) south.push_back(facade[p]);
    else other.push_back(facade[p]);
  }
  ASSERT_EQ(south.size(), 2u);
  ASSERT_EQ(other.size(), 1u);
  EXPECT_EQ(south[0], south[1]);
  EXPECT_NE(south[0], other[0]);
  EXPECT_GE(other[0], 0);
}

TEST(Composition, ViolationsNameTheRule) {
  const OpeningDomain d = domain_of({{Vec3(0, 0, 0), Vec3(6, 0, 0), Vec3(6, 0, 3), Vec3(0, 0, 3)}});
  const double a = d.element_size();
  const double w = d.panels()[0].cols * a;  // the grid's width: its axis is at w / 2
  OpeningConstraints c;
  c.align_sills = c.align_heads = c.equal_widths = c.symmetric = c.equal_spacing = true;
  // Three openings mirrored about the axis, one sill and head, equal widths and piers.
  const std::vector<PanelRectangle> good = {{0, w / 2 - 2.5, w / 2 - 1.5, 1.0, 2.0},
                                            {0, w / 2 - 0.5, w / 2 + 0.5, 1.0, 2.0},
                                            {0, w / 2 + 1.5, w / 2 + 2.5, 1.0, 2.0}};
  EXPECT_TRUE(composition_violations(d, c, good).empty());
  auto broken = [&](int i, double du0, double du1, double dv0, double dv1) {
    std::vector<PanelRectangle> s = good;
    s[i].u0 += du0, s[i].u1 += du1, s[i].v0 += dv0, s[i].v1 += dv1;
    std::string all;
    for (const std::string& v : composition_violations(d, c, s)) all += v + "\n";
    return all;
  };
  EXPECT_NE(broken(0, 0, 0, 0.1, 0).find("align_sills"), std::string::npos);
  EXPECT_NE(broken(0, 0, 0, 0, 0.1).find("align_heads"), std::string::npos);
  EXPECT_NE(broken(0, 0, 0.1, 0, 0).find("equal_widths"), std::string::npos);
  EXPECT_NE(broken(0, -0.2, -0.2, 0, 0).find("symmetric"), std::string::npos);
  EXPECT_NE(broken(0, -0.2, -0.2, 0, 0).find("equal_spacing"), std::string::npos);
  c = {};
  c.sill_heights = {0.9};
  EXPECT_NE(broken(0, 0, 0, 0, 0).find("none of sill_heights"), std::string::npos);
  c.sill_heights = {1.0};
  EXPECT_TRUE(composition_violations(d, c, good).empty());
  c = {};
  c.same_type_in_row = true;
  EXPECT_NE(broken(1, 0, 0.2, 0, 0).find("same_type_in_row"), std::string::npos);
  EXPECT_TRUE(composition_violations(d, c, good).empty());
}

}  // namespace
}  // namespace fenestra

namespace fenestra {
namespace {

// One window stacked above another cannot share its sill with it, nor take a sill height: the rule
// is kept by giving an opening up (the one whose loss costs least), and reported as met.
TEST(Composition, StackedOpeningsKeepTheRuleByGivingOneUp) {
  const OpeningDomain d = domain_of({{Vec3(0, 0, 0), Vec3(6, 0, 0), Vec3(6, 0, 3), Vec3(0, 0, 3)}});
  // A low wide window, a small one above it, and one beside them higher up.
  const std::vector<PanelRectangle> stacked = {{0, 1.0, 2.5, 0.5, 1.5}, {0, 1.25, 2.0, 2.0, 2.5},
                                               {0, 3.5, 4.5, 1.0, 2.0}};
  // Every opening is worth its area; losing the small one costs least.
  auto error_of = [](const std::vector<PanelRectangle>& set) {
    double area = 0.0;
    for (const PanelRectangle& r : set) area += r.width() * r.height();
    return 10.0 - area;
  };
  for (const bool align : {true, false}) {
    OpeningConstraints c;
    c.min_gap = 0.25, c.margin = 0.0, c.min_width = c.min_height = 0.25;
    if (align)
      c.align_sills = true;
    else
      c.sill_heights = {0.5, 1.0};
    ASSERT_FALSE(composition_violations(d, c, stacked).empty());
    const Composition out = compose_facades(d, c, stacked, error_of, nullptr);
    EXPECT_TRUE(composition_violations(d, c, out.openings).empty()) << (align ? "align_sills" : "sill_heights");
    EXPECT_TRUE(constraint_violations(d, out.openings, c).empty());
    ASSERT_EQ(out.steps.size(), 1u);
    EXPECT_TRUE(out.steps[0].met);
    EXPECT_EQ(out.openings.size(), 2u);
    for (const PanelRectangle& r : out.openings) EXPECT_LT(r.v0, 1.9) << "the stacked window is the one given up";
  }
}

// Sills and heads aligned automatically: kept where they cost at most a point of error, else the
// openings stay as they were and the step says so; one opening on a facade has nothing to align.
TEST(Composition, AutomaticAlignmentIsKeptOnlyWhereItIsCheap) {
  const OpeningDomain d = domain_of({{Vec3(0, 0, 0), Vec3(6, 0, 0), Vec3(6, 0, 3), Vec3(0, 0, 3)}});
  const std::vector<PanelRectangle> apart = {{0, 0.5, 2.0, 0.75, 2.0}, {0, 3.5, 5.0, 1.0, 2.25}};
  OpeningConstraints c;
  c.min_gap = 0.25, c.min_width = c.min_height = 0.5;
  c.align_sills = c.align_heads = c.automatic_alignment = true;
  EXPECT_TRUE(composition_violations(d, c, apart).empty());  // automatic: nothing the answer breaks
  const auto sills_equal = [](const std::vector<PanelRectangle>& set) {
    return set.size() == 2 && std::abs(set[0].v0 - set[1].v0) < 1e-6;
  };
  // Cheap: every set of the same area is as good (alignment costs nothing).
  const auto by_area = [](const std::vector<PanelRectangle>& set) {
    double area = 0.0;
    for (const PanelRectangle& r : set) area += r.width() * r.height();
    return 0.2 + 0.001 * std::abs(area - 3.75);
  };
  const Composition cheap = compose_facades(d, c, apart, by_area, nullptr);
  ASSERT_EQ(cheap.steps.size(), 2u);
  for (const CompositionStep& step : cheap.steps) {
    EXPECT_TRUE(step.automatic && step.kept && step.met) << step.rule;
    EXPECT_LE(step.error_after, step.error_before + kAutomaticAlignmentCost);
  }
  EXPECT_TRUE(sills_equal(cheap.openings));
  // Dear: lined-up sills cost 5 points of error.
  const auto apart_is_better = [&](const std::vector<PanelRectangle>& set) {
    return sills_equal(set) ? 0.25 : 0.2;
  };
  const Composition dear = compose_facades(d, c, apart, apart_is_better, nullptr);
  ASSERT_FALSE(dear.steps.empty());
  EXPECT_EQ(dear.steps[0].rule, "align_sills");
  EXPECT_FALSE(dear.steps[0].kept);
  EXPECT_NEAR(dear.steps[0].error_before, 0.2, 1e-12);
  EXPECT_FALSE(sills_equal(dear.openings));
  // One opening: no step at all.
  EXPECT_TRUE(compose_facades(d, c, {apart[0]}, by_area, nullptr).steps.empty());
}

}  // namespace
}  // namespace fenestra
