#include "scene/surface_chart.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "math/panel_axes.h"
#include "scene/position_key.h"

namespace fenestra {
namespace {

using Vec2d = Eigen::Vector2d;
using Vec3d = Eigen::Vector3d;

template <typename A, typename B>
auto cross2(const A& a, const B& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Where the face is, as the user gave the model (site coordinates: a UTM easting keeps its meters).
std::string face_at(const std::array<Vec3, 3>& c, const SiteFrame& site) {
  const Vec3d m = site.to_site((c[0] + c[1] + c[2]) / 3.0f);
  std::ostringstream s;
  s.precision(site.shifted() ? 10 : 4);
  s << "the face at (" << m.x() << ", " << m.y() << ", " << m.z() << ")";
  return s.str();
}

// Each edge of the piece (by its two end positions) and the (triangle, corner) pairs starting it.
using EdgeKey = std::pair<uint64_t, uint64_t>;
EdgeKey edge_key(const Vec3& a, const Vec3& b) {
  const uint64_t ka = position_key(a), kb = position_key(b);
  return ka < kb ? EdgeKey{ka, kb} : EdgeKey{kb, ka};
}

struct EdgeUse {
  int triangle, corner;  // the edge runs from corner to corner + 1
};

std::map<EdgeKey, std::vector<EdgeUse>> edges_of(const std::vector<std::array<Vec3, 3>>& corners) {
  std::map<EdgeKey, std::vector<EdgeUse>> edges;
  for (size_t i = 0; i < corners.size(); ++i)
    for (int k = 0; k < 3; ++k) edges[edge_key(corners[i][k], corners[i][(k + 1) % 3])].push_back({static_cast<int>(i), k});
  return edges;
}

// Barycentric coordinates of q in the 2-D triangle t.
std::array<float, 3> barycentric(const std::array<Vec2, 3>& t, const Vec2& q) {
  const float area = cross2(t[1] - t[0], t[2] - t[0]);
  const float b1 = cross2(q - t[0], t[2] - t[0]) / area;
  const float b2 = cross2(t[1] - t[0], q - t[0]) / area;
  return {1.0f - b1 - b2, b1, b2};
}

}  // namespace

SurfaceChart SurfaceChart::build(const Mesh& mesh, const std::vector<uint32_t>& triangles, const std::string& label,
                                 const SiteFrame& site) {
  SurfaceChart c;
  c.site_ = site;
  const size_t n = triangles.size();
  c.corners_.resize(n);
  c.flat_.resize(n);
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) c.corners_[i][k] = mesh.vertex(triangles[i], k);
  const size_t with_uv = std::count_if(triangles.begin(), triangles.end(), [&](uint32_t t) { return mesh.has_uv(t); });
  if (with_uv != 0 && with_uv != n)
    throw std::invalid_argument("the curved opening-domain panel of " + label +
                                " has a UV map on some of its faces only: give all of them UVs, or none");

  if (with_uv == n) {
    c.source_ = Source::kUvMap;
    double surface = 0.0, chart = 0.0;
    for (size_t i = 0; i < n; ++i) {
      const uint32_t t = triangles[i];
      surface += 0.5 * mesh.area_normal(t).norm();
      chart += 0.5 * std::abs(cross2(Vec2d((mesh.uv(t, 1) - mesh.uv(t, 0)).cast<double>()),
                                     Vec2d((mesh.uv(t, 2) - mesh.uv(t, 0)).cast<double>())));
    }
    if (!(chart > 0.0))
      throw std::invalid_argument("the UV map of the curved opening-domain panel of " + label +
                                  " is degenerate: its faces cover no area of UV space");
    // UVs are unitless: scaled so that a chart square of a meter's side has on average a square meter.
    const double scale = std::sqrt(surface / chart);
    for (size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) c.flat_[i][k] = (scale * mesh.uv(triangles[i], k).cast<double>()).cast<float>();
  } else {
    c.source_ = Source::kUnrolled;
    // Breadth-first across shared edges: each triangle is hinged flat about an edge of one already
    // laid, keeping its side lengths; computed in double, the flat copy of a developable surface
    // closes on every edge to rounding.
    std::vector<std::array<Vec2d, 3>> flat(n);
    std::vector<bool> placed(n, false);
    const auto edges = edges_of(c.corners_);
    auto p3 = [&](size_t i, int k) { return c.corners_[i][k].cast<double>(); };
    auto place_in_plane = [&](size_t i, const Vec3d& origin, const Vec3d& u, const Vec3d& v, const Vec2d& at) {
      for (int k = 0; k < 3; ++k) flat[i][k] = at + Vec2d((p3(i, k) - origin).dot(u), (p3(i, k) - origin).dot(v));
      placed[i] = true;
    };
    {
      const Vec3d n0 = (p3(0, 1) - p3(0, 0)).cross(p3(0, 2) - p3(0, 0)).normalized();
      Vec3d u, v;
      panel_axes(n0, &u, &v);
      place_in_plane(0, p3(0, 0), u, v, Vec2d::Zero());
    }
    std::deque<size_t> queue{0};
    size_t placed_count = 1;
    while (placed_count < n) {
      while (!queue.empty()) {
        const size_t i = queue.front();
        queue.pop_front();
        for (int k = 0; k < 3; ++k) {
          const auto& uses = edges.at(edge_key(c.corners_[i][k], c.corners_[i][(k + 1) % 3]));
          for (const EdgeUse& use : uses) {
            const size_t j = static_cast<size_t>(use.triangle);
            if (placed[j]) continue;
            // j's edge runs from its corner use.corner to use.corner + 1; match it to i's ends.
            const int ja = use.corner, jb = (use.corner + 1) % 3, jw = (use.corner + 2) % 3;
            const bool same_way = position_key(c.corners_[j][ja]) == position_key(c.corners_[i][k]);
            const Vec2d A = same_way ? flat[i][k] : flat[i][(k + 1) % 3];
            const Vec2d B = same_way ? flat[i][(k + 1) % 3] : flat[i][k];
            const Vec3d e = p3(j, jb) - p3(j, ja), d = p3(j, jw) - p3(j, ja);
            const double along = d.dot(e) / e.squaredNorm();
            const double off = (d - along * e).norm();
            const Vec2d E = B - A;
            const Vec2d left = Vec2d(-E.y(), E.x()).normalized();
            const double side_of_i = left.dot(flat[i][(k + 2) % 3] - A) >= 0.0 ? 1.0 : -1.0;
            flat[j][ja] = A;
            flat[j][jb] = B;
            flat[j][jw] = A + along * E - side_of_i * off * left;  // across the hinge from i
            placed[j] = true;
            ++placed_count;
            queue.push_back(j);
          }
        }
      }
      if (placed_count == n) break;
      // A triangle joined to the laid ones by a corner only lies in the plane of one of them.
      bool found = false;
      for (size_t j = 0; j < n && !found; ++j) {
        if (placed[j]) continue;
        for (size_t i = 0; i < n && !found; ++i) {
          if (!placed[i]) continue;
          for (int a = 0; a < 3 && !found; ++a)
            for (int b = 0; b < 3 && !found; ++b) {
              if (position_key(c.corners_[i][a]) != position_key(c.corners_[j][b])) continue;
              const Vec3d e1 = p3(i, 1) - p3(i, 0), e2 = p3(i, 2) - p3(i, 0);
              const Vec3d u = e1.normalized(), v = e1.cross(e2).normalized().cross(u);
              const Vec2d f1 = flat[i][1] - flat[i][0];
              const Vec2d fu = f1.normalized(), fv(-fu.y(), fu.x());
              for (int k = 0; k < 3; ++k) {
                const Vec3d d = p3(j, k) - p3(i, 0);
                flat[j][k] = flat[i][0] + d.dot(u) * fu + d.dot(v) * fv;
              }
              placed[j] = true;
              ++placed_count;
              queue.push_back(j);
              found = true;
            }
        }
      }
      if (!found) throw std::invalid_argument("the curved opening-domain panel of " + label + " is not connected");
    }
    // Every shared edge must have the same flat ends on both sides, else the surface is not
    // developable (a dome, a twisted face) or closes on itself (a whole cylinder).
    double extent = 0.0;
    for (size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) extent = std::max(extent, flat[i][k].cwiseAbs().maxCoeff());
    const double tolerance = 1e-5 + 1e-5 * extent;
    for (const auto& entry : edges) {
      const auto& uses = entry.second;
      for (size_t a = 1; a < uses.size(); ++a) {
        const EdgeUse& p = uses[0];
        const EdgeUse& q = uses[a];
        const bool same_way = position_key(c.corners_[p.triangle][p.corner]) == position_key(c.corners_[q.triangle][q.corner]);
        const Vec2d& p0 = flat[p.triangle][p.corner];
        const Vec2d& p1 = flat[p.triangle][(p.corner + 1) % 3];
        const Vec2d& q0 = flat[q.triangle][same_way ? q.corner : (q.corner + 1) % 3];
        const Vec2d& q1 = flat[q.triangle][same_way ? (q.corner + 1) % 3 : q.corner];
        if ((p0 - q0).norm() > tolerance || (p1 - q1).norm() > tolerance)
          throw std::invalid_argument(
              "the curved opening-domain panel of " + label +
              " has no UV map and cannot be unrolled flat (it is not developable, like a dome, or it closes on "
              "itself, like a whole cylinder; " + face_at(c.corners_[p.triangle], site) +
              "): give its faces a UV map with one island, or split it");
      }
    }
    for (size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) c.flat_[i][k] = flat[i][k].cast<float>();
  }
  c.finish(mesh, triangles, label);
  return c;
}

void SurfaceChart::finish(const Mesh& mesh, const std::vector<uint32_t>& triangles, const std::string& label) {
  const size_t n = triangles.size();
  const char* what = source_ == Source::kUvMap ? "the UV map of the curved opening-domain panel of "
                                               : "unrolled, the curved opening-domain panel of ";
  normal_.resize(n);
  area_ratio_.resize(n);
  to_chart_.resize(n);
  uint32_t largest = 0;
  for (uint32_t t : triangles) largest = std::max(largest, t);
  local_.assign(static_cast<size_t>(largest) + 1, -1);
  for (size_t i = 0; i < n; ++i) {
    local_[triangles[i]] = static_cast<int32_t>(i);
    const std::array<Vec3, 3>& p = corners_[i];
    const std::array<Vec2, 3>& q = flat_[i];
    const Vec3 area_normal = (p[1] - p[0]).cross(p[2] - p[0]);
    const float chart_area = cross2(q[1] - q[0], q[2] - q[0]);
    // Far from square-ish (a thousandth of the surface's area in the chart): no element could use it.
    if (!(std::abs(chart_area) > 1e-3f * area_normal.norm()))
      throw std::invalid_argument(std::string(what) + label + " is degenerate at " + face_at(p, site_) +
                                  ": its UV triangle has (almost) no area");
    normal_[i] = (chart_area > 0.0f ? 1.0f : -1.0f) * area_normal.normalized();
    area_ratio_[i] = area_normal.norm() / std::abs(chart_area);
    // Chart point = q0 + F G^-1 E^T (p - p0): barycentric coordinates in 3-D, carried to the chart.
    const Eigen::Vector3d e1 = (p[1] - p[0]).cast<double>(), e2 = (p[2] - p[0]).cast<double>();
    Eigen::Matrix<double, 3, 2> E;
    E << e1, e2;
    Eigen::Matrix2d F;
    F << (q[1] - q[0]).cast<double>(), (q[2] - q[0]).cast<double>();
    const Eigen::Matrix<double, 2, 3> M = F * (E.transpose() * E).inverse() * E.transpose();
    to_chart_[i] = {p[0], M.row(0).transpose().cast<float>(), M.row(1).transpose().cast<float>(), q[0]};
  }
  // Neighbours must agree on which side the chart runs counter-clockwise: else it folds over.
  for (const auto& entry : edges_of(corners_)) {
    const auto& uses = entry.second;
    for (size_t a = 1; a < uses.size(); ++a)
      if (normal_[uses[0].triangle].dot(normal_[uses[a].triangle]) < 0.0f)
        throw std::invalid_argument(std::string(what) + label + " folds over at " + face_at(corners_[uses[a].triangle], site_) +
                                    ": neighbouring faces are mirrored in it");
  }
  build_lookup();
  // A triangle's centre inside another triangle: two parts of the surface share chart space.
  for (size_t i = 0; i < n; ++i) {
    const Vec2 centre = (flat_[i][0] + flat_[i][1] + flat_[i][2]) / 3.0f;
    const int bu = std::clamp(static_cast<int>((centre.x() - lower_.x()) / (upper_.x() - lower_.x()) * bins_u_), 0, bins_u_ - 1);
    const int bv = std::clamp(static_cast<int>((centre.y() - lower_.y()) / (upper_.y() - lower_.y()) * bins_v_), 0, bins_v_ - 1);
    for (int j : bins_[static_cast<size_t>(bv) * bins_u_ + bu]) {
      if (static_cast<size_t>(j) == i) continue;
      const auto b = barycentric(flat_[j], centre);
      if (b[0] > 1e-4f && b[1] > 1e-4f && b[2] > 1e-4f)
        throw std::invalid_argument(std::string(what) + label + " overlaps itself: " + face_at(corners_[i], site_) + " and " +
                                    face_at(corners_[j], site_) + " take the same place in it");
    }
  }
}

void SurfaceChart::build_lookup() {
  lower_ = Vec2::Constant(1e30f);
  upper_ = Vec2::Constant(-1e30f);
  for (const auto& t : flat_)
    for (const Vec2& q : t) lower_ = lower_.cwiseMin(q), upper_ = upper_.cwiseMax(q);
  const Vec2 size = (upper_ - lower_).cwiseMax(1e-6f);
  const double cells = std::max<double>(1.0, static_cast<double>(flat_.size()));
  const double aspect = size.x() / size.y();
  bins_u_ = std::clamp(static_cast<int>(std::ceil(std::sqrt(cells * aspect))), 1, 1024);
  bins_v_ = std::clamp(static_cast<int>(std::ceil(cells / bins_u_)), 1, 1024);
  bins_.assign(static_cast<size_t>(bins_u_) * bins_v_, {});
  auto bin_u = [&](float x) { return std::clamp(static_cast<int>((x - lower_.x()) / size.x() * bins_u_), 0, bins_u_ - 1); };
  auto bin_v = [&](float y) { return std::clamp(static_cast<int>((y - lower_.y()) / size.y() * bins_v_), 0, bins_v_ - 1); };
  for (size_t i = 0; i < flat_.size(); ++i) {
    Vec2 lo = flat_[i][0], hi = flat_[i][0];
    for (const Vec2& q : flat_[i]) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    for (int v = bin_v(lo.y()); v <= bin_v(hi.y()); ++v)
      for (int u = bin_u(lo.x()); u <= bin_u(hi.x()); ++u) bins_[static_cast<size_t>(v) * bins_u_ + u].push_back(static_cast<int>(i));
  }
}

void SurfaceChart::translate(const Vec2& offset) {
  for (auto& t : flat_)
    for (Vec2& q : t) q += offset;
  for (Affine& m : to_chart_) m.flat_origin += offset;
  build_lookup();
}

int SurfaceChart::locate(const Vec2& q) const {
  const Vec2 size = (upper_ - lower_).cwiseMax(1e-6f);
  const float fu = (q.x() - lower_.x()) / size.x(), fv = (q.y() - lower_.y()) / size.y();
  if (!(fu >= -1e-6f && fu <= 1.0f + 1e-6f && fv >= -1e-6f && fv <= 1.0f + 1e-6f)) return -1;
  const int bu = std::clamp(static_cast<int>(fu * bins_u_), 0, bins_u_ - 1);
  const int bv = std::clamp(static_cast<int>(fv * bins_v_), 0, bins_v_ - 1);
  for (int i : bins_[static_cast<size_t>(bv) * bins_u_ + bu]) {
    const auto b = barycentric(flat_[i], q);
    if (b[0] >= -1e-5f && b[1] >= -1e-5f && b[2] >= -1e-5f) return i;
  }
  return -1;
}

SurfaceChart::SurfacePoint SurfaceChart::surface_point(const Vec2& q) const {
  SurfacePoint out;
  int i = locate(q);
  out.on_surface = i >= 0;
  if (i < 0) {  // extend the nearest triangle's plane
    float best = 1e30f;
    for (size_t j = 0; j < flat_.size(); ++j) {
      const float d = ((flat_[j][0] + flat_[j][1] + flat_[j][2]) / 3.0f - q).squaredNorm();
      if (d < best) best = d, i = static_cast<int>(j);
    }
  }
  const auto b = barycentric(flat_[i], q);
  out.position = b[0] * corners_[i][0] + b[1] * corners_[i][1] + b[2] * corners_[i][2];
  out.normal = normal_[i];
  out.area_ratio = area_ratio_[i];
  return out;
}

}  // namespace fenestra
