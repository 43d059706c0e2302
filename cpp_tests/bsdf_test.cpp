// Tests of the BSDFs in the shading frame (+Z the normal on the side of wo): sampled weights
// are eval / pdf, sampled directions follow bsdf_pdf (chi-square, see chi2.h), energy is
// conserved, evaluation is reciprocal, and the glass helpers reproduce their defining relations.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "chi2.h"
#include "scene/bsdf.h"
#include "scene/material.h"
#include "util/rng.h"

namespace fenestra {
namespace {

using fenestra_test::Chi2Result;
using fenestra_test::kPiD;
using fenestra_test::SphereGrid;

using fenestra_test::kSignificance;
using fenestra_test::next2;


Vec3 spherical_deg(double theta_deg, double phi_rad) {
  return SphereGrid::direction(theta_deg * kPiD / 180.0, phi_rad);
}

SphereGrid hemisphere_grid() {
  SphereGrid g;
  g.theta_res = 15;
  g.phi_res = 41;
  g.theta_max = kPiD / 2;
  return g;
}

Material diffuse(const Rgb& reflectance) {
  Material m;
  m.name = "diffuse";
  m.type = MaterialType::Diffuse;
  m.reflectance = reflectance;
  return m;
}

Material glossy(float roughness, float metallic, const Rgb& reflectance) {
  Material m;
  m.name = "glossy r" + std::to_string(roughness) + " m" + std::to_string(metallic);
  m.type = MaterialType::Glossy;
  m.roughness = roughness;
  m.metallic = metallic;
  m.reflectance = reflectance;
  return m;
}

Material thin_glass(float ior, const Rgb& internal_transmittance) {
  Material m;
  m.name = "glass";
  m.type = MaterialType::Glass;
  m.thin = true;
  m.ior = ior;
  m.internal_transmittance = internal_transmittance;
  return m;
}

// Near-mirror to rough, dielectric to metal, dark to white.
std::vector<Material> glossy_materials() {
  return {glossy(0.02f, 1.0f, Rgb(0.9f, 0.9f, 1.0f)), glossy(0.05f, 0.0f, Rgb::Constant(0.3f)), glossy(0.2f, 0.0f, Rgb::Constant(0.8f)),
          glossy(0.5f, 1.0f, Rgb(0.95f, 0.64f, 0.54f)), glossy(0.8f, 0.5f, Rgb::Constant(0.5f)),
          glossy(0.35f, 0.0f, Rgb::Ones()), glossy(0.9f, 1.0f, Rgb::Ones())};
}

// Outgoing directions from near-normal to grazing, off the grid's symmetry planes.
const std::vector<double> kThetaOut = {10.0, 60.0, 85.0};

std::string describe(const Material& m, const Vec3& wo) {
  std::ostringstream s;
  s << m.to_string() << ", wo = (" << wo.transpose() << ")";
  return s.str();
}

bool rgb_near(const Rgb& a, const Rgb& b, float rel) {
  return ((a - b).abs() <= rel * a.abs().max(b.abs()) + 1e-30f).all();
}

// Mean and standard error of the sampled weights (failed samples count as zero).
struct Albedo {
  Rgb mean, std_error;
};

Albedo sampled_albedo(const Material& m, const Vec3& wo, int n, uint64_t seed) {
  Rng rng(seed, 3);
  Eigen::Array3d sum = Eigen::Array3d::Zero(), sum2 = Eigen::Array3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Vec2 u = next2(rng);
    const float u_lobe = rng.uniform();
    BsdfSample s;
    if (!bsdf_sample(m, wo, u, u_lobe, true, &s)) continue;
    const Eigen::Array3d w = s.weight.cast<double>();
    sum += w;
    sum2 += w * w;
  }
  const Eigen::Array3d mean = sum / n;
  const Eigen::Array3d var = (sum2 / n - mean * mean).max(0.0) / (n - 1);
  return {mean.cast<float>(), var.sqrt().cast<float>()};
}

void expect_samples_consistent(const Material& m, const Vec3& wo, int n, uint64_t seed) {
  Rng rng(seed, 1);
  int bad = 0, ok = 0;
  for (int i = 0; i < n; ++i) {
    const Vec2 u = next2(rng);
    const float u_lobe = rng.uniform();
    BsdfSample s;
    if (!bsdf_sample(m, wo, u, u_lobe, true, &s)) continue;
    ++ok;
    const Rgb f = bsdf_eval(m, wo, s.wi);
    const float pdf = bsdf_pdf(m, wo, s.wi);
    // weight = eval / pdf: a handful of float operations, each within 6e-8 relative.
    const bool good = s.wi.z() > 0.0f && std::abs(s.wi.norm() - 1.0f) < 1e-5f && !s.specular && !s.straight &&
                      pdf > 0.0f && std::abs(s.pdf - pdf) <= 1e-5f * pdf && rgb_near(s.weight, f / pdf, 1e-5f) &&
                      s.weight.isFinite().all() && (s.weight >= 0.0f).all();
    if (!good && ++bad <= 5)
      ADD_FAILURE() << describe(m, wo) << ": wi " << s.wi.transpose() << ", weight " << s.weight.transpose()
                    << ", eval/pdf " << (f / pdf).transpose() << ", sample pdf " << s.pdf << ", bsdf_pdf " << pdf;
  }
  EXPECT_EQ(bad, 0) << describe(m, wo);
  EXPECT_GT(ok, n / 2) << describe(m, wo);
}

Chi2Result bsdf_chi2(const Material& m, const Vec3& wo, double significance, uint64_t seed) {
  // Samples that fail (specular reflections below the horizon) fill the outside bin, which
  // expects 1 - (integral of bsdf_pdf over the hemisphere).
  return fenestra_test::sphere_chi2(
      hemisphere_grid(), 1000000, seed,
      [&](Rng& rng, Vec3* wi) {
        const Vec2 u = next2(rng);
        const float u_lobe = rng.uniform();
        BsdfSample s;
        if (!bsdf_sample(m, wo, u, u_lobe, true, &s)) return false;
        *wi = s.wi;
        return true;
      },
      [&](const Vec3& wi) { return bsdf_pdf(m, wo, wi); }, significance);
}

void expect_reciprocal(const Material& m, uint64_t seed) {
  Rng rng(seed, 2);
  for (int i = 0; i < 20000; ++i) {
    // Cosine-distributed pairs, some very close to the horizon.
    const Vec3 wo = SphereGrid::direction(std::acos(std::sqrt(rng.uniform())), 2.0 * kPiD * rng.uniform());
    const Vec3 wi = SphereGrid::direction(std::acos(std::sqrt(rng.uniform())), 2.0 * kPiD * rng.uniform());
    if (wo.z() <= 0.0f || wi.z() <= 0.0f) continue;
    const Rgb a = bsdf_eval(m, wo, wi) / wi.z(), b = bsdf_eval(m, wi, wo) / wo.z();
    // Both orders run the same float operations in a different order: ~1e-6 relative apart.
    ASSERT_TRUE(rgb_near(a, b, 1e-4f)) << m.to_string() << "\nwo " << wo.transpose() << "\nwi " << wi.transpose()
                                       << "\nf(wo, wi) " << a.transpose() << "\nf(wi, wo) " << b.transpose();
  }
}

// ============================================================================================
// Diffuse.

TEST(BsdfDiffuse, EvalAndPdf) {
  const Material m = diffuse(Rgb(0.2f, 0.5f, 0.9f));
  Rng rng(1, 0);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 wo = SphereGrid::direction(std::acos(rng.uniform()), 2.0 * kPiD * rng.uniform());
    const Vec3 wi = SphereGrid::direction(std::acos(2.0 * rng.uniform() - 1.0), 2.0 * kPiD * rng.uniform());
    const Rgb f = bsdf_eval(m, wo, wi);
    const float pdf = bsdf_pdf(m, wo, wi);
    if (wi.z() > 0.0f && wo.z() > 0.0f) {
      EXPECT_TRUE(rgb_near(f, m.reflectance * (wi.z() / kPi), 1e-6f)) << f.transpose();
      EXPECT_NEAR(pdf, wi.z() / kPi, 1e-6f * pdf);
    } else {
      EXPECT_TRUE((f == 0.0f).all());
      EXPECT_EQ(pdf, 0.0f);
    }
  }
  // Below-horizon viewing: nothing to sample.
  BsdfSample s;
  EXPECT_FALSE(bsdf_sample(m, Vec3(0.0f, 0.6f, -0.8f), Vec2(0.3f, 0.3f), 0.5f, true, &s));
  EXPECT_EQ(bsdf_pdf(m, Vec3(0.0f, 0.6f, -0.8f), Vec3(0, 0, 1)), 0.0f);
  EXPECT_TRUE((bsdf_eval(m, Vec3(0.0f, 0.6f, -0.8f), Vec3(0, 0, 1)) == 0.0f).all());
}

TEST(BsdfDiffuse, SampleWeightIsEvalOverPdf) {
  const Material m = diffuse(Rgb(0.2f, 0.5f, 0.9f));
  for (double t : kThetaOut) expect_samples_consistent(m, spherical_deg(t, 1.1), 100000, 2);
}

TEST(BsdfDiffuse, SamplesFollowPdf) {
  const Material m = diffuse(Rgb(0.2f, 0.5f, 0.9f));
  const double alpha = fenestra_test::sidak_correction(kSignificance, 2);
  for (double t : {10.0, 85.0}) {
    const Vec3 wo = spherical_deg(t, 1.1);
    const Chi2Result r = bsdf_chi2(m, wo, alpha, 3);
    EXPECT_TRUE(r.passed) << describe(m, wo) << ": " << r.message;
  }
}

TEST(BsdfDiffuse, AlbedoEqualsReflectance) {
  for (const Rgb& refl : std::vector<Rgb>{Rgb(0.2f, 0.5f, 0.9f), Rgb::Ones(), Rgb::Zero()}) {
    const Material m = diffuse(refl);
    for (double t : kThetaOut) {
      const Vec3 wo = spherical_deg(t, 1.1);
      const Albedo a = sampled_albedo(m, wo, 200000, 4);
      for (int c = 0; c < 3; ++c)
        // 1e-6: float rounding of the accumulated weights.
        EXPECT_NEAR(a.mean[c], refl[c], 4.0f * a.std_error[c] + 1e-6f) << describe(m, wo) << " channel " << c;
    }
  }
}

TEST(BsdfDiffuse, Reciprocity) { expect_reciprocal(diffuse(Rgb(0.2f, 0.5f, 0.9f)), 5); }

// ============================================================================================
// Glossy.

TEST(BsdfGlossy, SampleWeightIsEvalOverPdf) {
  for (const Material& m : glossy_materials())
    for (double t : kThetaOut) expect_samples_consistent(m, spherical_deg(t, 1.1), 50000, 6);
}

TEST(BsdfGlossy, BelowHorizonIsZero) {
  for (const Material& m : glossy_materials()) {
    const Vec3 up = spherical_deg(30.0, 0.4), down = spherical_deg(120.0, 2.0);
    EXPECT_TRUE((bsdf_eval(m, up, down) == 0.0f).all()) << m.to_string();
    EXPECT_TRUE((bsdf_eval(m, down, up) == 0.0f).all()) << m.to_string();
    EXPECT_EQ(bsdf_pdf(m, up, down), 0.0f) << m.to_string();
    EXPECT_EQ(bsdf_pdf(m, down, up), 0.0f) << m.to_string();
    BsdfSample s;
    EXPECT_FALSE(bsdf_sample(m, down, Vec2(0.3f, 0.6f), 0.5f, true, &s)) << m.to_string();
  }
}

// One test per material so that each stays short; the significance is corrected for the family.
class BsdfGlossyChi2 : public ::testing::TestWithParam<int> {};

TEST_P(BsdfGlossyChi2, SamplesFollowPdf) {
  const std::vector<Material> materials = glossy_materials();
  const Material& m = materials.at(GetParam());
  const double alpha = fenestra_test::sidak_correction(kSignificance, static_cast<int>(materials.size() * kThetaOut.size()));
  uint64_t seed = 10 + 10 * GetParam();
  for (double t : kThetaOut) {
    const Vec3 wo = spherical_deg(t, 1.1);
    const Chi2Result r = bsdf_chi2(m, wo, alpha, ++seed);
    EXPECT_TRUE(r.passed) << describe(m, wo) << ": " << r.message;
  }
}

INSTANTIATE_TEST_SUITE_P(BsdfGlossy, BsdfGlossyChi2, ::testing::Range(0, static_cast<int>(glossy_materials().size())));

TEST(BsdfGlossy, AlbedoAtMostOne) {
  for (const Material& m : glossy_materials())
    for (double t : kThetaOut) {
      const Vec3 wo = spherical_deg(t, 1.1);
      const Albedo a = sampled_albedo(m, wo, 200000, 7);
      for (int c = 0; c < 3; ++c)
        EXPECT_LE(a.mean[c], 1.0f + 4.0f * a.std_error[c])
            << describe(m, wo) << " channel " << c << ": albedo " << a.mean[c] << " +- " << a.std_error[c];
    }
}

TEST(BsdfGlossy, AlbedoMatchesUniformHemisphereEstimate) {
  // Importance-sampled weights must be unbiased: compare with eval / (1 / 2 pi) at uniformly
  // distributed directions (an estimator that does not involve bsdf_sample or bsdf_pdf).
  for (const Material& m : glossy_materials()) {
    if (m.roughness < 0.3f) continue;  // the uniform estimator is hopeless for sharp lobes
    for (double t : kThetaOut) {
      const Vec3 wo = spherical_deg(t, 1.1);
      const int n = 200000;
      const Albedo a = sampled_albedo(m, wo, n, 8);
      Rng rng(9, 0);
      Eigen::Array3d sum = Eigen::Array3d::Zero(), sum2 = Eigen::Array3d::Zero();
      for (int i = 0; i < n; ++i) {
        const Vec2 u = next2(rng);
        const Vec3 wi = SphereGrid::direction(std::acos(u.x()), 2.0 * kPiD * u.y());
        const Eigen::Array3d w = (bsdf_eval(m, wo, wi) * (2.0f * kPi)).cast<double>();
        sum += w;
        sum2 += w * w;
      }
      const Eigen::Array3d mean = sum / n, se = ((sum2 / n - mean * mean).max(0.0) / (n - 1)).sqrt();
      for (int c = 0; c < 3; ++c) {
        const double tol = 4.0 * std::sqrt(se[c] * se[c] + double(a.std_error[c]) * a.std_error[c]);
        EXPECT_NEAR(a.mean[c], mean[c], tol) << describe(m, wo) << " channel " << c;
      }
    }
  }
}

TEST(BsdfGlossy, DiffuseBaseAlbedoIsReflectanceTimesOneMinusFresnel) {
  // For a dielectric (metallic 0) the specular lobe does not depend on the base colour, so the
  // difference of the hemispherical albedos with and without base colour is the diffuse base's:
  // reflectance * (1 - F(cos theta_o)), Schlick's F with f0 = 0.04. Deterministic quadrature.
  SphereGrid g;  // only the total matters: a coarse grid
  g.theta_res = 5;
  g.phi_res = 9;
  g.theta_max = kPiD / 2;
  for (float roughness : {0.3f, 0.9f})
    for (double t : {0.0, 45.0, 80.0, 88.0}) {
      const Material base = glossy(roughness, 0.0f, Rgb(0.9f, 0.5f, 0.1f)), none = glossy(roughness, 0.0f, Rgb::Zero());
      const Vec3 wo = spherical_deg(t, 1.1);
      for (int c = 0; c < 3; ++c) {
        const std::vector<double> cells = fenestra_test::cell_probabilities(
            g, [&](const Vec3& wi) { return bsdf_eval(base, wo, wi)[c] - bsdf_eval(none, wo, wi)[c]; });
        double diff = 0.0;
        for (double x : cells) diff += x;
        const double f = 0.04 + 0.96 * std::pow(1.0 - wo.z(), 5.0);
        // Quadrature and float evaluation: well below 1e-5 of an albedo of order 1.
        EXPECT_NEAR(diff, base.reflectance[c] * (1.0 - f), 1e-4) << describe(base, wo) << " channel " << c;
      }
    }
}

TEST(BsdfGlossy, Reciprocity) {
  uint64_t seed = 20;
  for (const Material& m : glossy_materials()) expect_reciprocal(m, ++seed);
}

// ============================================================================================
// Glass.

TEST(BsdfGlass, FresnelAtNormalIncidence) {
  for (float n : {1.33f, 1.5f, 1.52f, 1.9f, 2.4f}) {
    const float r0 = (n - 1.0f) * (n - 1.0f) / ((n + 1.0f) * (n + 1.0f));
    // Values of order 0.04-0.2 from a few float operations: errors of order 1e-8.
    EXPECT_NEAR(fresnel_dielectric(1.0f, n), r0, 1e-6f) << n;
    EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f / n), r0, 1e-6f) << "1/" << n;
  }
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f), 0.0f, 1e-7f);
}

TEST(BsdfGlass, FresnelGrazingTotalInternalAndReciprocal) {
  EXPECT_NEAR(fresnel_dielectric(0.0f, 1.5f), 1.0f, 1e-6f);
  // From the dense side, beyond the critical angle asin(1 / 1.5) = 41.8 deg: total reflection.
  EXPECT_EQ(fresnel_dielectric(std::cos(45.0f * kPi / 180.0f), 1.0f / 1.5f), 1.0f);
  EXPECT_LT(fresnel_dielectric(std::cos(40.0f * kPi / 180.0f), 1.0f / 1.5f), 1.0f);
  // The same interface crossed either way reflects the same fraction.
  for (float ci = 0.05f; ci <= 1.0f; ci += 0.05f) {
    const float eta = 1.52f;
    const float ct = std::sqrt(1.0f - (1.0f - ci * ci) / (eta * eta));
    EXPECT_NEAR(fresnel_dielectric(ci, eta), fresnel_dielectric(ct, 1.0f / eta), 1e-5f) << ci;
    const float f = fresnel_dielectric(ci, eta);
    EXPECT_GE(f, 0.0f);
    EXPECT_LE(f, 1.0f);
  }
}

TEST(BsdfGlass, ClearThinPaneConservesEnergy) {
  // With a lossless body, whatever a pane does not reflect it transmits, at every angle.
  for (float ior : {1.33f, 1.52f, 2.0f}) {
    const Material m = thin_glass(ior, Rgb::Ones());
    for (float c = 0.02f; c <= 1.0f; c += 0.07f) {
      const Rgb sum = thin_glass_reflectance(m, c) + thin_glass_transmittance(m, c);
      EXPECT_TRUE(((sum - 1.0f).abs() < 1e-5f).all()) << ior << " " << c << ": " << sum.transpose();
    }
  }
}

TEST(BsdfGlass, InternalTransmittanceReproducesTotalTransmittance) {
  for (float ior : {1.45f, 1.52f, 1.7f}) {
    const float r = fresnel_dielectric(1.0f, ior);
    const float max_total = (1.0f - r) * (1.0f - r) / (1.0f - r * r);
    for (float total : {0.005f, 0.01f, 0.05f, 0.2f, 0.5f, 0.8f, 0.9f, max_total}) {
      if (total > max_total) continue;
      const Rgb T(total, 0.5f * total, 0.9f * total);
      const Rgb tau = thin_glass_internal_transmittance(T, ior, "pane");
      EXPECT_TRUE(((tau >= 0.0f) && (tau <= 1.0f)).all()) << tau.transpose();
      const Rgb back = thin_glass_transmittance(thin_glass(ior, tau), 1.0f);
      // Forward model and inverse are a dozen float operations each: ~1e-6 relative.
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(back[c], T[c], 1e-5f * T[c]) << "ior " << ior << ", T " << T[c] << ", tau " << tau[c];
    }
    // The clear-pane maximum needs a lossless body.
    const Rgb tau = thin_glass_internal_transmittance(Rgb::Constant(max_total), ior, "pane");
    EXPECT_TRUE(((tau - 1.0f).abs() < 1e-5f).all()) << tau.transpose();
    EXPECT_TRUE((thin_glass_internal_transmittance(Rgb::Zero(), ior, "pane") == 0.0f).all());
  }
}

TEST(BsdfGlass, InternalTransmittanceRejectsMoreThanAClearPane) {
  const float ior = 1.52f;
  const float r = fresnel_dielectric(1.0f, ior);
  const float max_total = (1.0f - r) * (1.0f - r) / (1.0f - r * r);
  EXPECT_THROW(thin_glass_internal_transmittance(Rgb::Constant(max_total + 1e-3f), ior, "pane"), std::invalid_argument);
  EXPECT_THROW(thin_glass_internal_transmittance(Rgb(0.5f, 0.95f, 0.5f), ior, "pane"), std::invalid_argument);
  EXPECT_THROW(thin_glass_internal_transmittance(Rgb::Ones(), ior, "pane"), std::invalid_argument);
  EXPECT_NO_THROW(thin_glass_internal_transmittance(Rgb::Constant(max_total), ior, "pane"));
}

TEST(BsdfGlass, IsADeltaLobeForEvalAndPdf) {
  const Material m = thin_glass(1.52f, Rgb::Constant(0.9f));
  const Vec3 wo = spherical_deg(30.0, 0.2);
  EXPECT_TRUE((bsdf_eval(m, wo, Vec3(-wo.x(), -wo.y(), wo.z())) == 0.0f).all());
  EXPECT_EQ(bsdf_pdf(m, wo, -wo), 0.0f);
  BsdfSample s;
  ASSERT_TRUE(bsdf_sample(m, wo, Vec2(0.5f, 0.5f), 0.99f, true, &s));
  EXPECT_TRUE(s.specular);
  EXPECT_EQ(s.pdf, 0.0f);
}

}  // namespace
}  // namespace fenestra
