#include "trace/path_tracer.h"

#include <algorithm>
#include <array>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "sampling/warp.h"
#include "scene/bsdf.h"

namespace fenestra {
namespace {

constexpr float kRayEpsilon = 1e-4f;  // meters: offset of new rays from the surface they leave
constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr int kRouletteDepth = 3;
constexpr int kMaxCrossed = 16;

float power_heuristic(float pdf_a, float pdf_b) {
  const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

Vec3 offset_origin(const Vec3& p, const Vec3& ng, const Vec3& dir) {
  return p + (dir.dot(ng) > 0.0f ? kRayEpsilon : -kRayEpsilon) * ng;
}

std::vector<Vec3> unit_normals(const Mesh& mesh) {
  std::vector<Vec3> n(mesh.triangle_count());
  for (size_t t = 0; t < n.size(); ++t) n[t] = mesh.area_normal(t).normalized();
  return n;
}

}  // namespace

struct PathTracer::PathState {
  Rgb beta;                   // throughput so far (includes the sensor's pi for cosine sampling)
  float prev_pdf = 0.0f;      // BSDF pdf of the direction being followed, for MIS at sky hits
  bool prev_specular = false;
  int depth = 0;              // surface interactions so far
};

struct PathTracer::Surface {
  Vec3 normal;  // unit geometric normal as modelled
  int material = 0;
  int panel = -1;  // opening-domain panel (scene faces only)
};

struct PathTracer::Shadow {
  bool visible = false;
  Rgb attenuation = Rgb::Ones();
  std::array<int32_t, kMaxCrossed> crossed;
  int crossed_count = 0;
};

// Where a path's light goes: summed (closed mode) or recorded as events (recording mode).
class PathTracer::Sink {
 public:
  explicit Sink(SensorRecord* record) : record_(record) {}
  bool recording() const { return record_ != nullptr; }
  void light(const Rgb& c, const int32_t* crossed, int count) {
    const float v = luminance(c);
    if (!(v > 0.0f) || !std::isfinite(v)) return;
    if (!record_) {
      sum_ += v;
      return;
    }
    record_->events.push_back({v, -1, static_cast<uint32_t>(record_->crossed.size()), static_cast<uint32_t>(count)});
    record_->crossed.insert(record_->crossed.end(), crossed, crossed + count);
  }
  void escape(int element, float value) {
    if (!std::isfinite(value)) value = 0.0f;
    record_->events.push_back({value, element, 0, 0});
  }
  float sum() const { return sum_; }

 private:
  SensorRecord* record_;
  float sum_ = 0.0f;
};

PathTracer::PathTracer(const Scene& scene, CutterSet openings, Mesh reveals)
    : scene_(scene), openings_(std::move(openings)), reveals_(std::move(reveals)) {
  scene_normals_ = unit_normals(scene_.mesh);
  reveal_normals_ = unit_normals(reveals_);
  rays_ = std::make_unique<RayScene>(scene_.mesh, reveals_);
}

PathTracer::Surface PathTracer::surface(const Hit& hit) const {
  Surface s;
  if (hit.geometry == RayScene::kRevealGeometry) {
    s.normal = reveal_normals_[hit.primitive];
    s.material = reveals_.triangle_material[hit.primitive];
  } else {
    s.normal = scene_normals_[hit.primitive];
    s.material = scene_.mesh.triangle_material[hit.primitive];
    s.panel = scene_.domain.panel_of_triangle(hit.primitive);
  }
  return s;
}

void PathTracer::shadow(const Vec3& org, const Vec3& dir, const CutterSet* cutters, bool collect, Shadow* out) const {
  out->visible = false;
  out->attenuation = Rgb::Ones();
  out->crossed_count = 0;
  CutterSet crossed_cutters;  // elements crossed so far are cut, through the wall thickness
  float tnear = 0.0f;
  for (int i = 0; i < 64; ++i) {
    const CutterSet* active = collect ? &crossed_cutters : cutters;
    const Hit h = rays_->intersect(org, dir, tnear, kInfinity, active);
    if (!h.valid()) {
      out->visible = true;
      return;
    }
    const Surface s = surface(h);
    tnear = h.t + kRayEpsilon;
    if (collect && s.panel >= 0) {
      const int k = scene_.domain.element_at(s.panel, org + h.t * dir);
      if (k < 0 || out->crossed_count == kMaxCrossed) return;  // the panel's margin is always wall
      out->crossed[out->crossed_count++] = k;
      crossed_cutters.push_back(scene_.domain.element_cutter(k));
      continue;
    }
    const Material& m = scene_.materials[s.material];
    if (!m.is_thin_glass()) return;
    out->attenuation *= thin_glass_transmittance(m, std::abs(dir.dot(s.normal)));
  }
}

void PathTracer::trace(Vec3 org, Vec3 dir, PathState st, const CutterSet* cutters, Rng& rng, Sink& sink) const {
  const Sky& sky = *scene_.sky;
  const int max_bounces = scene_.render.max_bounces;
  const float beta_ref = 1.0f;
  for (;;) {
    const Hit h = rays_->intersect(org, dir, 0.0f, kInfinity, cutters);
    if (!h.valid()) {
      const float w = st.prev_specular ? 1.0f : power_heuristic(st.prev_pdf, sky.pdf(dir));
      sink.light(st.beta * sky.radiance(dir) * w, nullptr, 0);
      return;
    }
    const Vec3 p = org + h.t * dir;
    const Surface s = surface(h);

    if (sink.recording() && s.panel >= 0) {
      const int k = scene_.domain.element_at(s.panel, p);
      if (k >= 0) {
        // What would arrive through k if it were open: the same ray, continued with k cut.
        const CutterSet through{scene_.domain.element_cutter(k)};
        Sink outside(nullptr);
        trace(org, dir, st, &through, rng, outside);
        sink.escape(k, outside.sum());
      }
    }
    if (st.depth >= max_bounces) return;

    const Material& m = scene_.materials[s.material];
    const bool front = dir.dot(s.normal) < 0.0f;
    const Vec3 n = front ? s.normal : Vec3(-s.normal);
    const Frame frame(n);
    const Vec3 wo = frame.to_local(-dir);

    if (!m.is_glass()) {
      float light_pdf = 0.0f;
      const Vec3 wl = sky.sample(Vec2(rng.uniform(), rng.uniform()), &light_pdf);
      if (light_pdf > 0.0f && wl.dot(n) > 0.0f) {
        const Vec3 wl_local = frame.to_local(wl);
        const Rgb f = bsdf_eval(m, wo, wl_local);
        if ((f > 0.0f).any()) {
          Shadow sh;
          shadow(offset_origin(p, s.normal, wl), wl, cutters, sink.recording(), &sh);
          if (sh.visible) {
            const float w = power_heuristic(light_pdf, bsdf_pdf(m, wo, wl_local));
            sink.light(st.beta * f * sky.radiance(wl) * sh.attenuation * (w / light_pdf), sh.crossed.data(),
                       sh.crossed_count);
          }
        }
      }
    } else {
      rng.uniform(), rng.uniform();  // keep the random sequence aligned across materials
    }

    BsdfSample bs;
    const Vec2 u(rng.uniform(), rng.uniform());
    const float u_lobe = rng.uniform();
    if (!bsdf_sample(m, wo, u, u_lobe, front, &bs)) return;
    const Vec3 wi = frame.to_world(bs.wi);
    st.beta *= bs.weight;
    if (!bs.straight) {
      st.prev_pdf = bs.pdf;
      st.prev_specular = bs.specular;
    }
    ++st.depth;
    org = offset_origin(p, s.normal, wi);
    dir = wi;

    if (st.depth >= kRouletteDepth) {
      const float q = std::min(0.95f, st.beta.maxCoeff() / beta_ref);
      if (!(rng.uniform() < q)) return;
      st.beta /= q;
    }
  }
}

void PathTracer::trace_sensor(size_t i, Rng& rng, const CutterSet* cutters, Sink& sink) const {
  const Sky& sky = *scene_.sky;
  const Vec3& n = scene_.sensors.normals[i];
  const Vec3 p = scene_.sensors.points[i] + kRayEpsilon * n;
  const Frame frame(n);

  // The sensor is a cosine receiver: its "BSDF times cosine" is cos(theta).
  float light_pdf = 0.0f;
  const Vec3 wl = sky.sample(Vec2(rng.uniform(), rng.uniform()), &light_pdf);
  const float cos_l = wl.dot(n);
  if (light_pdf > 0.0f && cos_l > 0.0f) {
    Shadow sh;
    shadow(p, wl, cutters, sink.recording(), &sh);
    if (sh.visible) {
      const float w = power_heuristic(light_pdf, cos_l * kInvPi);
      sink.light(sky.radiance(wl) * sh.attenuation * (cos_l * w / light_pdf), sh.crossed.data(), sh.crossed_count);
    }
  }
  const Vec3 local = square_to_cosine_hemisphere(Vec2(rng.uniform(), rng.uniform()));
  PathState st;
  st.beta = Rgb::Constant(kPi);
  st.prev_pdf = square_to_cosine_hemisphere_pdf(local);
  if (st.prev_pdf <= 0.0f) return;
  trace(p, frame.to_world(local), st, cutters, rng, sink);
}

float PathTracer::sensor_sample(size_t sensor, Rng& rng) const {
  Sink sink(nullptr);
  trace_sensor(sensor, rng, &openings_, sink);
  return sink.sum();
}

void PathTracer::record_sensor_path(size_t sensor, Rng& rng, SensorRecord* record) const {
  Sink sink(record);
  trace_sensor(sensor, rng, nullptr, sink);
  record->end_path();
}

void PathTracer::check_sensors() const {
  // A sensor inside a closed solid sees only the back of faces and no opening domain in any direction.
  constexpr int kProbes = 64;
  for (size_t i = 0; i < scene_.sensors.size(); ++i) {
    const Vec3& p = scene_.sensors.points[i];
    bool inside = true;
    for (int k = 0; k < kProbes && inside; ++k) {
      const float z = 1.0f - (2.0f * k + 1.0f) / kProbes;  // Fibonacci sphere
      const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
      const float phi = 2.39996323f * k;
      const Vec3 d(r * std::cos(phi), r * std::sin(phi), z);
      const Hit h = rays_->intersect(p, d, 0.0f, kInfinity, &openings_);
      if (!h.valid()) {
        inside = false;
        break;
      }
      const Surface s = surface(h);
      inside = s.panel < 0 && d.dot(s.normal) > 0.0f;
    }
    if (inside) {
      std::ostringstream m;
      m << "sensor " << i << " at (" << p.transpose() << ") is inside geometry: every direction from it meets the back "
        << "of a face";
      throw std::invalid_argument(m.str());
    }
  }
}

}  // namespace fenestra
