// The portal sampler's sample() and pdf() tied together, as pbrt-v4's lightsamplers_test ties its
// samplers' Sample and PMF: the directions sample() draws from a vertex, histogrammed on the
// sphere, against the integral of pdf() over every cell (Pearson's chi-square, chi2.h), and pdf()'s
// integral over the sphere against the share of samples that land on an element. Portal layouts:
// one wall (by panel in solid angle); a wall and a ceiling (by panel, and element by element by
// area); a wall and a far, small window whose solid angle falls below the threshold (by area).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "chi2.h"
#include "test_scenes.h"
#include "trace/portal_sampler.h"

namespace fenestra {
namespace {

using fenestra_test::Chi2Result;
using fenestra_test::kSignificance;
using fenestra_test::next2;
using fenestra_test::SphereGrid;

struct Layout {
  std::string name;
  std::vector<std::array<Vec3, 4>> quads;
  float element_size;
  RenderSettings::Sampler sampler;
  Vec3 from;
};

// A wall y = 0 (2 x 1 m) seen from inside the room (y > 0).
const std::array<Vec3, 4> kWall = {Vec3(0, 0, 0.5f), Vec3(2, 0, 0.5f), Vec3(2, 0, 1.5f), Vec3(0, 0, 1.5f)};
// A ceiling z = 2.5 (2 x 2 m) above the same room.
const std::array<Vec3, 4> kCeiling = {Vec3(0, 0.5f, 2.5f), Vec3(0, 2.5f, 2.5f), Vec3(2, 2.5f, 2.5f),
                                      Vec3(2, 0.5f, 2.5f)};
// A 5 cm window 10 m away in the wall x = 10 (its solid angle 2.5e-5 sr, below the sampler's 1e-4).
const std::array<Vec3, 4> kFarWindow = {Vec3(10, 1, 1), Vec3(10, 1.05f, 1), Vec3(10, 1.05f, 1.05f),
                                        Vec3(10, 1, 1.05f)};

std::vector<Layout> layouts() {
  using S = RenderSettings::Sampler;
  return {{"wall, by panel", {kWall}, 0.5f, S::kSobol, Vec3(0.7f, 1.2f, 0.8f)},
          {"wall and ceiling, by panel", {kWall, kCeiling}, 0.5f, S::kSobol, Vec3(1.3f, 1.0f, 1.1f)},
          {"wall and ceiling, by element", {kWall, kCeiling}, 0.5f, S::kIndependent, Vec3(1.3f, 1.0f, 1.1f)},
          {"wall and a far window", {kWall, kFarWindow}, 0.025f, S::kSobol, Vec3(0.7f, 1.2f, 0.8f)}};
}

// One layout's domain and sampler, and the element a direction from `from` meets first.
struct Portals {
  explicit Portals(const Layout& l) : domain(test::domain_of_quads(l.quads, l.element_size)), sampler(domain, render(l)) {}
  static RenderSettings render(const Layout& l) {
    RenderSettings r;
    r.sampler = l.sampler;
    return r;
  }
  // The solid-angle density of direction d (unit) from x: pdf() at the element d meets first.
  float pdf(const Vec3& x, const Vec3& d) const {
    float nearest = std::numeric_limits<float>::infinity(), density = 0.0f;
    for (size_t p = 0; p < domain.panels().size(); ++p) {
      const Panel& panel = domain.panels()[p];
      const float along = d.dot(panel.normal);
      if (along == 0.0f) continue;
      const float t = (panel.origin - x).dot(panel.normal) / along;
      if (!(t > 0.0f) || t >= nearest) continue;
      const PanelPoint at = domain.panel_point(static_cast<int>(p), x + t * d);
      const int k = domain.element_at(static_cast<int>(p), at);
      if (k < 0) continue;
      nearest = t;
      density = sampler.pdf(k, at, x, t, d);
    }
    return density;
  }
  // A direction drawn by sample() from x, false when it lands on no element (the tracer drops it).
  bool sample(Rng& rng, const Vec3& x, Vec3* d) const {
    const float u_pick = rng.uniform();
    const PortalSampler::Aim aim = sampler.sample(u_pick, next2(rng), x, Vec3(0, 0, 1));
    const int element = aim.portal >= 0 ? aim.portal : domain.element_at(aim.panel, aim.point.at);
    if (element < 0) return false;
    *d = (aim.point.position - x).normalized();
    return true;
  }

  OpeningDomain domain;
  PortalSampler sampler;
};

TEST(PortalSampler, SampleFollowsPdfChi2) {
  const std::vector<Layout> all = layouts();
  const double alpha = fenestra_test::sidak_correction(kSignificance, static_cast<int>(all.size()));
  constexpr int kSamples = 300000;
  for (const Layout& l : all) {
    const Portals portals(l);
    SphereGrid grid;
    grid.theta_res = 30;
    grid.phi_res = 60;
    // The pdf jumps at the panels' edges: integration splits at their corners' angles (a wall's
    // upright edges lie along constant azimuths).
    for (const Panel& p : portals.domain.panels())
      for (const float u : {p.parameter_lower.x(), p.parameter_upper.x()})
        for (const float v : {p.parameter_lower.y(), p.parameter_upper.y()}) {
        const Vec3 d = (p.origin + u * p.u_axis + v * p.v_axis - l.from).normalized();
        grid.theta_breaks.push_back(std::acos(std::clamp(double(d.z()), -1.0, 1.0)));
        grid.phi_breaks.push_back(std::atan2(double(d.y()), double(d.x())));
      }
    // Every sample lands on an element (the next test checks it, and that pdf() integrates to 1).
    const Chi2Result r = fenestra_test::sphere_chi2_every_sample_drawn(
        grid, kSamples, 17, [&](Rng& rng, Vec3* d) { return portals.sample(rng, l.from, d); },
        [&](const Vec3& d) { return portals.pdf(l.from, d.normalized()); }, alpha);
    EXPECT_TRUE(r.passed) << l.name << ": " << r.message;
  }
}

TEST(PortalSampler, PdfIntegratesToTheShareOfSamplesOnElements) {
  // Every sample lands on an element (the rectangles the panels' elements span are whole), so
  // the density integrates to 1 over the directions toward the elements.
  for (const Layout& l : layouts()) {
    const Portals portals(l);
    const double integral =
        fenestra_test::integrate_sphere([&](const Vec3& d) { return portals.pdf(l.from, d.normalized()); });
    EXPECT_NEAR(integral, 1.0, 2e-3) << l.name;
    Rng rng(3, 1);
    int landed = 0;
    Vec3 d;
    for (int i = 0; i < 10000; ++i) landed += portals.sample(rng, l.from, &d);
    EXPECT_EQ(landed, 10000) << l.name;
  }
}

}  // namespace
}  // namespace fenestra
