#include "trace/ray_scene.h"

#include <atomic>
#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

namespace fenestra {
namespace {

// Context extension: Embree hands the context to the filter, so per-ray cutters need no globals.
struct CutterContext {
  RTCIntersectContext base;
  const CutterSet* cutters;
};

void embree_error(void*, RTCError code, const char* message) {
  std::fprintf(stderr, "fenestra: Embree error %d: %s\n", static_cast<int>(code), message ? message : "");
}

void check_device(const char* what) {
  const RTCError err = rtcGetDeviceError(embree_device());
  if (err != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree failed to ") + what + " (error " + std::to_string(err) + ")");
}

// Stateless: decides from the hit position alone, so it may be called repeatedly in any order.
void cutter_filter(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const CutterContext*>(args->context);
  if (!ctx->cutters || ctx->cutters->empty()) return;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const float t = RTCRayN_tfar(args->ray, args->N, i);
    const Vec3 org(RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
                   RTCRayN_org_z(args->ray, args->N, i));
    const Vec3 dir(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                   RTCRayN_dir_z(args->ray, args->N, i));
    if (any_cuts(*ctx->cutters, org + t * dir, RTCHitN_primID(args->hit, args->N, i))) args->valid[i] = 0;
  }
}

// Which sides of a face at the hit are inside a cutter: bit 0 along the face normal, bit 1 against it.
int cut_sides(const RTCFilterFunctionNArguments* args, unsigned i, const CutterSet& cutters) {
  constexpr float kSide = 2e-4f;  // meters: the points tested either side of the face
  const float t = RTCRayN_tfar(args->ray, args->N, i);
  const Vec3 p(RTCRayN_org_x(args->ray, args->N, i) + t * RTCRayN_dir_x(args->ray, args->N, i),
               RTCRayN_org_y(args->ray, args->N, i) + t * RTCRayN_dir_y(args->ray, args->N, i),
               RTCRayN_org_z(args->ray, args->N, i) + t * RTCRayN_dir_z(args->ray, args->N, i));
  const Vec3 n = Vec3(RTCHitN_Ng_x(args->hit, args->N, i), RTCHitN_Ng_y(args->hit, args->N, i),
                      RTCHitN_Ng_z(args->hit, args->N, i))
                     .normalized();
  return (any_contains(cutters, p + kSide * n) ? 1 : 0) | (any_contains(cutters, p - kSide * n) ? 2 : 0);
}

// A cutter's reveal is no wall where another cutter continues the opening beyond it.
void reveal_filter(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const CutterContext*>(args->context);
  if (!ctx->cutters || ctx->cutters->empty()) return;
  for (unsigned i = 0; i < args->N; ++i)
    if (args->valid[i] != 0 && cut_sides(args, i, *ctx->cutters) == 3) args->valid[i] = 0;
}

// An element tube's side is a wall only between an open cell and a closed one.
void reveal_grid_filter(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const CutterContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const int sides = ctx->cutters ? cut_sides(args, i, *ctx->cutters) : 0;
    if (sides != 1 && sides != 2) args->valid[i] = 0;
  }
}

}  // namespace

RTCGeometry embree_triangles(const Mesh& mesh) {
  RTCGeometry g = rtcNewGeometry(embree_device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), mesh.positions.size()));
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) v[3 * i + k] = mesh.positions[i][k];
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), mesh.triangles.size()));
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) idx[3 * i + k] = mesh.triangles[i][k];
  return g;
}

namespace {
std::atomic<uint64_t> g_rays_traced{0};
}

uint64_t& thread_ray_count() {
  thread_local uint64_t count = 0;
  return count;
}
uint64_t rays_traced() { return g_rays_traced.load(); }
void add_rays_traced(uint64_t n) { g_rays_traced += n; }

RTCDevice embree_device() {
  static RTCDevice device = [] {
    RTCDevice d = rtcNewDevice(nullptr);
    if (!d) throw std::runtime_error("cannot create an Embree device");
    rtcSetDeviceErrorFunction(d, embree_error, nullptr);
    return d;
  }();
  return device;
}

RayScene::RayScene(const Mesh& mesh, const Mesh& reveals, const Mesh& reveal_grid) {
  scene_ = rtcNewScene(embree_device());
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  const auto attach = [&](const Mesh& m, RTCFilterFunctionN filter, uint32_t id) {
    RTCGeometry g = embree_triangles(m);
    rtcSetGeometryIntersectFilterFunction(g, filter);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene_, g, id);
    rtcReleaseGeometry(g);
  };
  attach(mesh, cutter_filter, kSceneGeometry);
  if (!reveals.triangles.empty()) attach(reveals, reveal_filter, kRevealGeometry);
  if (!reveal_grid.triangles.empty()) attach(reveal_grid, reveal_grid_filter, kRevealGridGeometry);
  rtcCommitScene(scene_);
  check_device("build the scene");
}

RayScene::~RayScene() {
  if (scene_) rtcReleaseScene(scene_);
}

Hit RayScene::intersect(const Vec3& org, const Vec3& dir, float tnear, float tfar, const CutterSet* cutters) const {
  CutterContext ctx;
  rtcInitIntersectContext(&ctx.base);
  ctx.cutters = cutters;
  RTCRayHit rh;
  rh.ray.org_x = org.x(), rh.ray.org_y = org.y(), rh.ray.org_z = org.z();
  rh.ray.dir_x = dir.x(), rh.ray.dir_y = dir.y(), rh.ray.dir_z = dir.z();
  rh.ray.tnear = tnear;
  rh.ray.tfar = tfar;
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xFFFFFFFF;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx.base, &rh);
  ++thread_ray_count();
  Hit hit;
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
    hit.t = rh.ray.tfar;
    hit.geometry = rh.hit.geomID;
    hit.primitive = rh.hit.primID;
  }
  return hit;
}

}  // namespace fenestra
