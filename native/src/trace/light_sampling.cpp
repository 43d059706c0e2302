#include "trace/light_sampling.h"

#include "daylight/annual_sources.h"
#include "scene/bsdf.h"

namespace fenestra {

void LightSampling::sample_sky(const Vertex& v, const Rgb& beta, const CutterSet* cutters, int count,
                               const PathSamples* samples, Rng& rng, RecordSink& sink) const {
  const bool openings = samples_openings(sink);
  for (int i = 0; i < count; ++i) {
    const Vec2 u = samples && i == 0 ? samples->get2d(PathSamples::kVertexSky) : next2(rng);
    const float u_pick =
        !openings ? 0.0f : samples && i == 0 ? samples->get1d(PathSamples::kVertexPortalPick) : rng.uniform();
    sample_sky_once(v, beta, cutters, count, u, u_pick, sink);
  }
}

void LightSampling::sample_sky_once(const Vertex& v, const Rgb& beta, const CutterSet* cutters, int count,
                                    const Vec2& u, float u_pick, RecordSink& sink) const {
  const Sky& sky = *scene_.sky;
  float light_pdf = 0.0f;
  Vec3 wl;
  if (samples_openings(sink)) {
    if (!sky_through_openings_.sample(v.p, v.n, u, u_pick, &wl, &light_pdf)) return;
  } else {
    wl = sky.sample_toward(u, v.n, &light_pdf);
  }
  if (!(light_pdf > 0.0f) || wl.dot(v.n) <= 0.0f) return;
  const Vec3 wl_local = v.frame.to_local(wl);
  const Rgb f = bsdf_eval(*v.material, v.wo, wl_local);
  if (!(f > 0.0f).any()) return;
  Shadow sh;
  hits_.shadow(offset_origin(v.p, v.ng, wl), wl, cutters, sink.recording() || sink.outside_element(), &sh);
  if (sh.truncated) sink.count_truncated();
  if (!sh.visible) return;
  const float portal = sink.recording() && sh.first_is_element
                           ? portals_.pdf(sh.crossed[0].element, sh.crossed[0].point, v.p, sh.crossed_distance[0], wl)
                           : 0.0f;
  const float w = power_heuristic(count * light_pdf, bsdf_pdf(*v.material, v.wo, wl_local), portal);
  sink.light(beta * f * sky.radiance(wl) * sh.attenuation * (w / (count * light_pdf)), sh.crossed.data(),
             sh.crossed_count, sky_source(wl));
}

void LightSampling::sample_sun(const Vertex& v, const Rgb& beta, const CutterSet* cutters, int count,
                               const PathSamples* samples, Rng& rng, RecordSink& sink) const {
  for (int i = 0; i < count; ++i) {
    const bool stratified = samples && i == 0;
    const float u_pick = stratified ? samples->get1d(PathSamples::kVertexSunPick) : rng.uniform();
    const Vec2 u_disk = stratified ? samples->get2d(PathSamples::kVertexSun) : next2(rng);
    const SunLights::Sample sun = scene_.suns.sample(u_pick, u_disk);
    if (sun.direction.dot(v.n) <= 0.0f) continue;
    const Rgb f = bsdf_eval(*v.material, v.wo, v.frame.to_local(sun.direction));
    if (!(f > 0.0f).any()) continue;
    Shadow sh;
    hits_.shadow(offset_origin(v.p, v.ng, sun.direction), sun.direction, cutters,
                 sink.recording() || sink.outside_element(), &sh);
    if (sh.truncated) sink.count_truncated();
    if (!sh.visible) continue;
    sink.light(beta * f * sun.illuminance * sh.attenuation / static_cast<float>(count), sh.crossed.data(),
               sh.crossed_count, sun_source(sun.index));
  }
}

void LightSampling::sensor_sky(const Vec3& p, const Vec3& n, const PathSamples* samples, Rng& rng,
                               const CutterSet* cutters, bool portals, RecordSink& sink) const {
  // The sensor is a cosine receiver: its "BSDF times cosine" is cos(theta).
  const Sky& sky = *scene_.sky;
  float light_pdf = 0.0f;
  const Vec2 u = samples ? samples->get2d(PathSamples::kSensorSky) : next2(rng);
  Vec3 wl;
  if (samples_openings(sink)) {
    const float u_pick = samples ? samples->get1d(PathSamples::kSensorOpeningPick) : rng.uniform();
    if (!sky_through_openings_.sample(p, n, u, u_pick, &wl, &light_pdf)) return;
  } else {
    wl = sky.sample_toward(u, n, &light_pdf);
  }
  const float cos_l = wl.dot(n);
  if (!(light_pdf > 0.0f && cos_l > 0.0f)) return;
  Shadow sh;
  hits_.shadow(p, wl, cutters, sink.recording(), &sh);
  if (sh.truncated) sink.count_truncated();
  if (sh.visible && !(portals && sh.first_is_element)) {  // through elements: portal samples
    const float w = power_heuristic(light_pdf, cos_l * kInvPi);
    sink.light(sky.radiance(wl) * sh.attenuation * (cos_l * w / light_pdf), sh.crossed.data(), sh.crossed_count,
               sky_source(wl));
  }
}

void LightSampling::sensor_sun(const Vec3& p, const Vec3& n, const PathSamples* samples, Rng& rng,
                               const CutterSet* cutters, RecordSink& sink) const {
  const float u_pick = samples ? samples->get1d(PathSamples::kSensorSunPick) : rng.uniform();
  const Vec2 u_disk = samples ? samples->get2d(PathSamples::kSensorSun) : next2(rng);
  const SunLights::Sample sun = scene_.suns.sample(u_pick, u_disk);
  const float cos_s = sun.direction.dot(n);
  if (!(cos_s > 0.0f)) return;
  Shadow sh;
  hits_.shadow(p, sun.direction, cutters, sink.recording(), &sh);
  if (sh.truncated) sink.count_truncated();
  if (sh.visible)
    sink.light(sun.illuminance * sh.attenuation * cos_s, sh.crossed.data(), sh.crossed_count,
               sun_source(sun.index) | (patches_ ? AnnualSources::kDirect : 0));
}

}  // namespace fenestra
