#include "raw_embree.h"

#include <pmmintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "trace/ray_scene.h"

namespace bench {

namespace {

constexpr size_t kRawRayCount = size_t(1) << 20;
constexpr double kRawMinSeconds = 1.5;

// The tracer's workers flush denormals (Embree's advice); the raw measurement does the same.
void flush_denormals() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

struct Ray {
  fenestra::Vec3 org, dir;
};

// Incoherent rays: origins uniform in the room's box [0,6]x[0,6]x[0,3], directions uniform on the sphere.
std::vector<Ray> random_rays(size_t count) {
  std::mt19937_64 gen(12345);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Ray> rays(count);
  for (Ray& r : rays) {
    r.org = fenestra::Vec3(6.0f * u(gen), 6.0f * u(gen), 3.0f * u(gen));
    const float z = 1.0f - 2.0f * u(gen), phi = 2.0f * fenestra::kPi * u(gen);
    const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    r.dir = fenestra::Vec3(s * std::cos(phi), s * std::sin(phi), z);
  }
  return rays;
}

// Repeats `trace_all` (which traces every ray once and returns its hits) for at least
// kRawMinSeconds; returns rays per second and the hit fraction of the last pass.
template <typename TraceAll>
std::pair<double, double> rays_per_second(size_t ray_count, TraceAll trace_all) {
  const auto start = Clock::now();
  size_t traced = 0, hits = 0;
  double seconds = 0.0;
  do {
    hits = trace_all();
    traced += ray_count;
    seconds = seconds_since(start);
  } while (seconds < kRawMinSeconds);
  return {static_cast<double>(traced) / seconds, static_cast<double>(hits) / static_cast<double>(ray_count)};
}

}  // namespace

RawThroughput raw_embree_throughput(const Scene& scene) {
  const fenestra::RayScene embree(scene.mesh, fenestra::Mesh{});
  const std::vector<Ray> rays = random_rays(kRawRayCount);
  const float inf = std::numeric_limits<float>::infinity();
  auto trace_range = [&](size_t begin, size_t end) {
    size_t hits = 0;
    for (size_t i = begin; i < end; ++i) hits += embree.intersect(rays[i].org, rays[i].dir, 0.0f, inf, nullptr).valid();
    return hits;
  };
  RawThroughput raw;
  flush_denormals();
  raw.one_thread = rays_per_second(rays.size(), [&] { return trace_range(0, rays.size()); }).first;
  const auto all = rays_per_second(rays.size(), [&] {
    std::atomic<size_t> hits{0};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
      flush_denormals();
      hits += trace_range(r.begin(), r.end());
    });
    return hits.load();
  });
  raw.all_threads = all.first;
  raw.hit_fraction = all.second;
  return raw;
}

json raw_json(const RawThroughput& raw) {
  return {{"rays_per_second_1_thread", raw.one_thread},
          {"rays_per_second_all_threads", raw.all_threads},
          {"hit_fraction", raw.hit_fraction}};
}

void print_raw(const RawThroughput& raw) {
  std::printf("[1] Raw Embree throughput: RayScene::intersect, scene mesh, incoherent rays (origins uniform in\n"
              "    [0,6]x[0,6]x[0,3], directions uniform), closest hit, %.0f%% of rays hit\n",
              100.0 * raw.hit_fraction);
  std::printf("    1 thread:    %8.2f Mrays/s\n", raw.one_thread * 1e-6);
  std::printf("    all threads: %8.2f Mrays/s\n\n", raw.all_threads * 1e-6);
}

}  // namespace bench
