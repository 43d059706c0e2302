#pragma once
// Next-event estimation toward the sky and the sun disks: a direction drawn from the sky's own
// importance about the receiver's normal (weighed by MIS against BSDF sampling and, where the
// shadow ray meets an element first, portal sampling) or from the suns (nothing else finds them),
// a shadow ray, and the light handed to the path's sink with the elements it crossed. The sky's
// and the suns' sample / pdf pairs live with them (scene/sky.h, scene/sun_lights.h) and are
// tested there; this is what the tracer does with them. In an annual pass each light names its
// source: the sky patch or the sun cluster (AnnualSources).
#include <cstdint>

#include "daylight/sky_patches.h"
#include "scene/scene.h"
#include "trace/opening_portals.h"
#include "trace/path_samples.h"
#include "trace/portal_sampler.h"
#include "trace/record_sink.h"
#include "trace/scene_hits.h"
#include "trace/sky_through_openings.h"
#include "util/rng.h"

namespace fenestra {

// Power heuristic for the strategy with density `pdf` against two others.
inline float power_heuristic(float pdf, float other, float third = 0.0f) {
  const float a = pdf * pdf, sum = a + other * other + third * third;
  return sum > 0.0f ? a / sum : 0.0f;
}

// Two uniforms in a fixed order (the order of function arguments is unspecified).
inline Vec2 next2(Rng& rng) {
  const float a = rng.uniform();
  return Vec2(a, rng.uniform());
}

class LightSampling {
 public:
  // `patches`: an annual pass (the scene's sky is unit and its suns are the sun clusters).
  // `openings`: the openings cut (closed mode), through which a path that is not recording also
  // samples the sky (samples_openings).
  LightSampling(const Scene& scene, const SceneHits& hits, const PortalSampler& portals,
                const OpeningPortals& openings, const SkyPatches* patches)
      : scene_(scene),
        hits_(hits),
        portals_(portals),
        sky_through_openings_(scene.sky.get(), openings),
        patches_(patches) {}

  // From a vertex of a path whose throughput is `beta`: `count` samples of the sky, of the suns.
  // `samples` (the main path's first vertex): the first sample is stratified.
  void sample_sky(const Vertex& v, const Rgb& beta, const CutterSet* cutters, int count, const PathSamples* samples,
                  Rng& rng, RecordSink& sink) const;
  void sample_sun(const Vertex& v, const Rgb& beta, const CutterSet* cutters, int count, const PathSamples* samples,
                  Rng& rng, RecordSink& sink) const;
  // The sensor's own samples (a cosine receiver at p, normal n) of the sky, weighed against its
  // first bounce, and, with `portals`, not through elements (the portal samples carry that) ...
  void sensor_sky(const Vec3& p, const Vec3& n, const PathSamples* samples, Rng& rng, const CutterSet* cutters,
                  bool portals, RecordSink& sink) const;
  // ... and of the suns, through elements too (no other strategy finds them); in an annual pass
  // the light is marked as the sun seen directly (AnnualSources::kDirect).
  void sensor_sun(const Vec3& p, const Vec3& n, const PathSamples* samples, Rng& rng, const CutterSet* cutters,
                  RecordSink& sink) const;

  // Whether a path feeding `sink` samples the sky through the openings (closed mode with openings
  // as portals): its sky samples then come from sky_through_openings.h's mixture ...
  bool samples_openings(const RecordSink& sink) const {
    return sky_through_openings_.has_openings() && !sink.recording() && !sink.outside_element();
  }
  // ... whose density toward `dir` from x (normal n), per sky sample, this is.
  float sky_through_openings_pdf(const Vec3& x, const Vec3& n, const Vec3& dir) const {
    return sky_through_openings_.pdf(x, n, dir);
  }

  // The source of light from the sky along dir, and of sun `index` (0 outside an annual pass).
  uint16_t sky_source(const Vec3& dir) const {
    return patches_ ? static_cast<uint16_t>(patches_->patch_of(dir)) : 0;
  }
  uint16_t sun_source(int index) const { return patches_ ? static_cast<uint16_t>(patches_->count() + index) : 0; }

 private:
  void sample_sky_once(const Vertex& v, const Rgb& beta, const CutterSet* cutters, int count, const Vec2& u,
                       float u_pick, RecordSink& sink) const;

  const Scene& scene_;
  const SceneHits& hits_;
  const PortalSampler& portals_;
  SkyThroughOpenings sky_through_openings_;
  const SkyPatches* patches_;
};

}  // namespace fenestra
