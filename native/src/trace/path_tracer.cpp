#include "trace/path_tracer.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "scene/bsdf.h"
#include "sampling/warp.h"

namespace fenestra {
namespace {

constexpr int kRouletteDepth = 3;
constexpr int kOutdoorSkySamples = 4;

}  // namespace

struct PathTracer::PathState {
  Rgb beta;                   // throughput so far (includes the sensor's pi for cosine sampling)
  float prev_pdf = 0.0f;      // BSDF pdf of the direction being followed, for MIS at sky hits
  bool prev_specular = false;
  bool portals = false;        // the vertex that chose this direction also sampled portals
  bool sampled_openings = false;  // ... or, in closed mode, the sky through the openings
  bool from_sensor = false;    // ... and that vertex was the sensor
  Vec3 vertex;                 // that vertex
  Vec3 vertex_normal = Vec3(0, 0, 1);  // its shading normal (sky densities depend on it)
  float portal_pdf = 0.0f;     // portal density of this direction, once known (at an escape)
  int sky_samples = 1;         // sky samples the vertex that chose this direction took
  bool beyond_element = false;  // followed through an element: the next vertex is the first outside
  // Depth at which a segment through a thick wall follows both ways at each tube side it meets (open
  // neighbour: on; closed: its reveal); deeper, one way at random (meet_element_outside).
  int branch_both_depth = -1;
  float must_reach = 0.0f;      // the first segment counts only if nothing is met before this distance
  bool by_portal = false;      // this direction was chosen by portal sampling (else by the BSDF)
  // At the sensor, portal samples alone carry the light that comes through elements: they are
  // stratified over each element, far better than MIS weights computed from densities assume.
  bool portal_exclusive = false;
  int depth = 0;              // surface interactions so far
  // The main path's first vertex draws its sky, sun and bounce decisions from these (then null;
  // branches and sub-paths never see them).
  const PathSamples* samples = nullptr;

  // The direction just chosen at vertex x (shading normal n), with BSDF density `pdf`; `sends_portals`:
  // x also sampled portals (a sensor's own state is set by trace_sensor).
  void chosen_at(const Vec3& x, const Vec3& n, float pdf, bool specular, bool sends_portals) {
    prev_pdf = pdf;
    prev_specular = specular;
    portals = sends_portals;
    from_sensor = false;
    vertex = x;
    vertex_normal = n;
  }
  // Followed through an element: the next vertex is the first outside, and the tube sides a
  // segment through a thick wall meets at this depth are followed both ways.
  PathState beyond_element_at(int at_depth) const {
    PathState next = *this;
    next.beyond_element = true;
    next.branch_both_depth = at_depth;
    return next;
  }
};

PathTracer::PathTracer(const Scene& scene, CutterSet openings, Mesh reveals, const SkyPatches* patches)
    : scene_(scene),
      openings_(std::move(openings)),
      opening_portals_(openings_),
      hits_(scene, std::move(reveals)),
      portals_(scene.domain, scene.render),
      lights_(scene, hits_, portals_, opening_portals_, patches) {}

template <typename BsdfOfDirection>
void PathTracer::sample_portal(const PortalSampler::Aim& aim, const Vec3& x, const Vec3& n, const PathState& st, Rng& rng,
                               BsdfOfDirection f_and_pdf, RecordSink& sink) const {
  const PortalSampler::Point& portal = aim.point;
  const Vec3& y = portal.position;
  if (!is_finite(y)) return;
  Vec3 dir = y - x;
  const float dist = dir.norm();
  if (!(dist > 1e-5f)) return;
  dir /= dist;
  if (dir.dot(n) <= 0.0f) return;
  float bsdf_pdf = 0.0f;
  const Rgb f = f_and_pdf(dir, &bsdf_pdf);
  if (!(f > 0.0f).any()) return;
  const float cos_y = std::abs(dir.dot(portal.normal));
  if (!(cos_y > 1e-6f)) return;
  const float pdf = portals_.sample_pdf(aim, dist, cos_y);  // of the direction, per path
  // Everything that arrives through k along dir: sky, and light from outdoor surfaces.
  PathState through_state = st.beyond_element_at(st.depth);
  through_state.beta = st.beta * f / pdf;
  through_state.chosen_at(x, n, bsdf_pdf, false, false);
  through_state.portal_pdf = pdf;
  through_state.by_portal = true;
  through_state.must_reach = dist;  // portals only reach what lies beyond the element met first
  const int element = aim.portal >= 0 ? aim.portal : scene_.domain.element_at(aim.panel, portal.at);
  if (element < 0) return;
  const CutterSet through{scene_.domain.element_cutter(element)};
  RecordSink outside = RecordSink::outside();
  trace(x, dir, through_state, &through, rng, outside);
  sink.light_through({element, portal.at}, outside);
}

float PathTracer::strategy_weight(const PathState& st, float sky_pdf) {
  if (st.prev_specular) return 1.0f;
  if (st.portal_exclusive && st.portal_pdf > 0.0f) return st.by_portal ? 1.0f : 0.0f;
  return st.by_portal ? power_heuristic(st.portal_pdf, st.prev_pdf, sky_pdf)
                      : power_heuristic(st.prev_pdf, sky_pdf, st.portal_pdf);
}

void PathTracer::record_escape(const Crossing& met, bool inner_face, const Vec3& org, const Vec3& dir, float t, const PathState& st,
                               Rng& rng, RecordSink& sink) const {
  RecordSink outside = RecordSink::outside();
  // From the sensor, portal samples alone carry the light arriving through elements' inner faces.
  if (!(st.portals && st.from_sensor && inner_face)) {
    PathState outside_state = st.beyond_element_at(st.depth);
    if (st.portals && inner_face) {
      const float distance = (org + t * dir - st.vertex).norm();
      outside_state.portal_pdf = portals_.pdf(met.element, met.point, st.vertex, distance, dir);
    }
    // What would arrive through k if it were open: the same ray, continued with k cut.
    const CutterSet through{scene_.domain.element_cutter(met.element)};
    trace(org, dir, outside_state, &through, rng, outside);
  }
  sink.escape(met, outside);
}

void PathTracer::sample_interior_portal(const Vertex& v, const PathState& st, const PathSamples* samples, Rng& rng,
                                        RecordSink& sink) const {
  const float u_pick = samples ? samples->get1d(PathSamples::kVertexPortalPick) : rng.uniform();
  const Vec2 uv = samples ? samples->get2d(PathSamples::kVertexPortal) : next2(rng);
  PathState from_here = st;
  ++from_here.depth;
  sample_portal(portals_.sample(u_pick, uv, v.p, v.n), offset_origin(v.p, v.ng, v.n), v.n, from_here, rng,
                [&](const Vec3& d, float* pdf) {
                  const Vec3 local = v.frame.to_local(d);
                  *pdf = bsdf_pdf(*v.material, v.wo, local);
                  return bsdf_eval(*v.material, v.wo, local);
                },
                sink);
}

bool PathTracer::meet_element_outside(const Crossing& j, bool through_face, const Vec3& org, const Vec3& dir,
                                      const Vec3& at, PathState& st,
                                      const CutterSet* cutters, Rng& rng, RecordSink& sink) const {
  if (!sink.can_pass(through_face)) return sink.reflect_off(j);
  auto pass = [&](const PathState& state) {
    RecordSink passing = sink.passing(j, through_face);
    CutterSet through = cutters ? *cutters : CutterSet{};
    through.push_back(scene_.domain.element_cutter(j.element));
    trace(org, dir, state, &through, rng, passing);
    sink.absorb(passing);
  };
  // Inside a thick wall, after the first vertex beyond the element, both ways would multiply at every
  // tube side: one is followed, chosen at random and weighted by the inverse of its probability, so
  // that the records stay unbiased for every set of open elements. Along one straight line the
  // sides met end where it reflects (a closed cell) or leaves the wall: with m sides left on it,
  // this one included, reflecting here has probability 1 / (m + 1), which makes each of the m + 1
  // ends equally likely and weighs every one m + 1 (an even choice at each side would weigh the
  // last 2^m: heavy tails on fine grids).
  if (!through_face && st.depth != st.branch_both_depth) {
    const int panel = scene_.domain.elements()[j.element].panel;
    const int m = 1 + scene_.domain.lines_ahead(panel, at, dir);
    const float reflect = 1.0f / static_cast<float>(m + 1);
    if (rng.uniform() >= reflect) {
      PathState passing = st;
      passing.beta /= 1.0f - reflect;
      pass(passing);
      return false;
    }
    st.beta /= reflect;
    return sink.reflect_off(j);
  }
  // Were j open, the sub-path would go on through it: follow that too.
  pass(st);
  // Closed, it is wall: what follows needs it closed.
  return sink.reflect_off(j);
}

void PathTracer::trace(Vec3 org, Vec3 dir, PathState st, const CutterSet* cutters, Rng& rng, RecordSink& sink) const {
  const Sky& sky = *scene_.sky;
  for (;;) {
    const PathSamples* samples = st.samples;
    st.samples = nullptr;
    const Hit h = hits_.intersect(org, dir, 0.0f, cutters);
    if (st.must_reach > 0.0f) {
      if (h.valid() && h.t < st.must_reach - kRayEpsilon) return;
      st.must_reach = 0.0f;
    }
    if (!h.valid()) {
      const float w = st.sampled_openings && !st.prev_specular
                          ? power_heuristic(st.prev_pdf,
                                            st.sky_samples * lights_.sky_through_openings_pdf(st.vertex, st.vertex_normal, dir))
                          : strategy_weight(st, st.sky_samples * sky.pdf_toward(dir, st.vertex_normal));
      sink.light(st.beta * sky.radiance(dir) * w, nullptr, 0, lights_.sky_source(dir));
      return;
    }
    const Surface s = hits_.surface(h);
    Vertex v;
    v.p = org + h.t * dir;
    if (sink.recording() || sink.outside_element()) {
      // An element's face (inner or outer), or the side of an open element's tube through a thick
      // wall, which is the reveal of a closed neighbour or the way on into an open one.
      const Crossing met = hits_.crossing_met(s, v.p, dir);
      if (met.element >= 0 && sink.recording()) record_escape(met, s.inner_face(), org, dir, h.t, st, rng, sink);
      const bool through_face = s.reveal_grid_face < 0;
      if (met.element >= 0 && sink.outside_element() &&
          !meet_element_outside(met, through_face, org, dir, v.p, st, cutters, rng, sink))
        return;
    }
    if (st.portal_pdf > 0.0f) {
      // First surface beyond an element: reached by BSDF and portal sampling alike.
      st.beta *= strategy_weight(st, 0.0f);
      st.portal_pdf = 0.0f;
      st.by_portal = false;
    }
    if (st.depth >= scene_.render.max_bounces) return;

    v.material = &scene_.materials[s.material];
    v.ng = s.normal;
    const bool front = dir.dot(s.normal) < 0.0f;
    v.n = front ? s.normal : Vec3(-s.normal);
    v.frame = Frame(v.n);
    v.wo = v.frame.to_local(-dir);
    // The first vertex outside an element carries the light of the outdoors into the room for
    // many paths: it takes several sky samples.
    // (Not a reveal inside a thick wall: it is met by many branches of one path, and lights little.)
    const int sky_samples = st.beyond_element && s.reveal_grid_face < 0 ? kOutdoorSkySamples : 1;
    st.beyond_element = false;
    if (!v.material->is_glass()) {
      lights_.sample_sky(v, st.beta, cutters, sky_samples, samples, rng, sink);
      if (!scene_.suns.empty()) lights_.sample_sun(v, st.beta, cutters, sky_samples, samples, rng, sink);
      if (sink.recording() && !portals_.empty()) sample_interior_portal(v, st, samples, rng, sink);
    }

    BsdfSample bs;
    const Vec2 u = samples ? samples->get2d(PathSamples::kVertexBsdf) : next2(rng);
    const float u_lobe = samples ? samples->get1d(PathSamples::kVertexLobe) : rng.uniform();
    if (!bsdf_sample(*v.material, v.wo, u, u_lobe, front, &bs)) return;
    const Vec3 wi = v.frame.to_world(bs.wi);
    st.beta *= bs.weight;
    if (!bs.straight) {  // thin-glass transmission keeps the direction, and with it the MIS state
      st.chosen_at(v.p, v.n, bs.pdf, bs.specular, sink.recording() && !v.material->is_glass());
      st.sampled_openings = lights_.samples_openings(sink) && !v.material->is_glass();
      st.portal_pdf = 0.0f;
      st.sky_samples = v.material->is_glass() ? 1 : sky_samples;
    }
    ++st.depth;
    org = offset_origin(v.p, s.normal, wi);
    dir = wi;

    if (st.depth >= kRouletteDepth) {
      const float q = std::min(0.95f, st.beta.maxCoeff());  // relative to the sensor's unit weight
      if (!(rng.uniform() < q)) return;
      st.beta /= q;
    }
  }
}

void PathTracer::trace_sensor(size_t i, size_t path, const PathSamples* samples, Rng& rng, const CutterSet* cutters,
                              RecordSink& sink) const {
  const Vec3& n = scene_.sensors.normals[i];
  const Vec3 p = scene_.sensors.points[i] + kRayEpsilon * n;
  const Frame frame(n);

  const bool portals = sink.recording() && !portals_.empty();
  lights_.sensor_sky(p, n, samples, rng, cutters, portals, sink);
  if (!scene_.suns.empty()) lights_.sensor_sun(p, n, samples, rng, cutters, sink);
  PathState st;
  st.beta = Rgb::Constant(kPi);
  st.portals = portals;
  st.from_sensor = true;
  st.sampled_openings = lights_.samples_openings(sink);
  st.vertex = p;
  st.vertex_normal = n;
  if (portals) {
    PathState from_sensor = st;
    from_sensor.beta = Rgb::Ones();
    from_sensor.portal_exclusive = true;
    auto cosine = [&](const Vec3& d, float* pdf) {
      const float c = std::max(0.0f, d.dot(n));
      *pdf = c * kInvPi;
      return Rgb::Constant(c);
    };
    if (samples) {
      // Stratified over the group's samples, aimed by the sensor's view of the elements, and
      // uniform in each element's solid angle.
      if (!portals_.selection_ready(scene_.sensors.size()))
        throw std::logic_error("PathTracer: prepare_portal_selection() must run before recording stratified paths");
      const size_t count = portals_.stratified_sensor_portals();
      for (size_t j = 0; j < count; ++j) {
        const auto [u, v] = samples->portal(j, count);
        sample_portal(portals_.sensor_stratified(i, count, u, v, p, n), p, n, from_sensor, rng, cosine, sink);
      }
    } else {
      PortalSampler::SensorPortal chosen[kSensorPortals];
      portals_.sensor_portals(i, path, chosen);
      for (const PortalSampler::SensorPortal& sp : chosen)
        sample_portal(portals_.aim_at_element(sp.element, sp.uv, sp.samples_per_path, false, p, n), p, n, from_sensor,
                      rng, cosine, sink);
    }
  }
  const Vec3 local =
      square_to_cosine_hemisphere(samples ? samples->get2d(PathSamples::kFirstBounce) : next2(rng));
  st.prev_pdf = square_to_cosine_hemisphere_pdf(local);
  if (st.prev_pdf <= 0.0f) return;
  st.samples = samples;
  trace(p, frame.to_world(local), st, cutters, rng, sink);
}

PathTracer::DirectSun PathTracer::sun_from_sensor(size_t sensor, const Vec3& direction, const CutterSet* cutters,
                                                  bool collect) const {
  DirectSun out;
  const Vec3& n = scene_.sensors.normals[sensor];
  out.cosine = direction.dot(n);
  if (!(out.cosine > 0.0f)) return out;
  Shadow sh;
  hits_.shadow(scene_.sensors.points[sensor] + kRayEpsilon * n, direction, cutters, collect, &sh);
  if (!sh.visible) return out;
  out.visible = true;
  out.attenuation = luminance(sh.attenuation);
  out.crossed.assign(sh.crossed.begin(), sh.crossed.begin() + sh.crossed_count);
  return out;
}

PathTracer::DirectSun PathTracer::direct_sun_through_openings(size_t sensor, const Vec3& direction) const {
  return sun_from_sensor(sensor, direction, &openings_, false);
}

PathTracer::DirectSun PathTracer::direct_sun(size_t sensor, const Vec3& direction) const {
  return sun_from_sensor(sensor, direction, nullptr, true);
}

float PathTracer::sensor_sample(size_t sensor, const PathSamples* samples, Rng& rng) const {
  RecordSink sink = RecordSink::sum();
  trace_sensor(sensor, 0, samples, rng, &openings_, sink);
  return static_cast<float>(sink.total());
}

void PathTracer::sensor_sample_by_source(size_t sensor, const PathSamples* samples, Rng& rng,
                                         std::vector<SourceLight>* out) const {
  RecordSink sink = RecordSink::by_source(out);
  trace_sensor(sensor, 0, samples, rng, &openings_, sink);
}

void PathTracer::record_sensor_path(size_t sensor, size_t path, const PathSamples* samples, Rng& rng,
                                    SensorRecord* record, DropCounts* dropped) const {
  record->path_key = sensor << 32 ^ path;
  RecordSink sink = RecordSink::record(record, &scene_.domain.elements());
  trace_sensor(sensor, path, samples, rng, nullptr, sink);
  record->end_path();
  *dropped += sink.dropped();
}

void PathTracer::prepare_portal_selection(int threads, SensorRange range) {
  portals_.prepare_selection(scene_.sensors, threads, range);
}

void PathTracer::check_sensors(SensorRange range) const {
  // A sensor inside a closed solid sees only the back of faces and no opening domain in any direction.
  constexpr int kProbes = 64;
  range = range.within(scene_.sensors.size());
  for (size_t i = range.begin; i < range.end; ++i) {
    const Vec3& p = scene_.sensors.points[i];
    bool inside = true;
    for (int k = 0; k < kProbes && inside; ++k) {
      const float z = 1.0f - (2.0f * k + 1.0f) / kProbes;  // Fibonacci sphere
      const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
      const float phi = 2.39996323f * k;
      const Vec3 d(r * std::cos(phi), r * std::sin(phi), z);
      const Hit h = hits_.intersect(p, d, 0.0f, &openings_);
      if (!h.valid()) {
        inside = false;
        break;
      }
      const Surface s = hits_.surface(h);
      inside = !s.inner_face() && d.dot(s.normal) > 0.0f;
    }
    if (inside) {
      std::ostringstream m;
      const Vec3d at = scene_.site.to_site(p);  // where the user put it
      m.precision(10);
      m << "sensor " << i << " at (" << at.x() << ", " << at.y() << ", " << at.z() << ") is inside geometry: every direction from it meets the back "
        << "of a face";
      throw std::invalid_argument(m.str());
    }
  }
}

}  // namespace fenestra
