#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "scene/input_limits.h"
#include "scene/mesh.h"
#include "scene/site_frame.h"
#include "util/byte_size.h"
#include "util/cost_error.h"
#include "util/decimal_number.h"
#include "util/memory_limit.h"
#include "util/out_of_memory.h"
#include "util/quoted_text.h"
#include "util/whole_file.h"

namespace fenestra {

void Mesh::append(const Mesh& other) {
  const uint32_t base = static_cast<uint32_t>(positions.size());
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  for (const auto& t : other.triangles) triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  triangle_material.insert(triangle_material.end(), other.triangle_material.begin(), other.triangle_material.end());
  const int group_base = static_cast<int>(group_names.size());
  for (int g : other.triangle_group) triangle_group.push_back(g < 0 ? -1 : g + group_base);
  group_names.insert(group_names.end(), other.group_names.begin(), other.group_names.end());
  if (!other.triangle_uv.empty()) {
    const int32_t uv_base = static_cast<int32_t>(texcoords.size());
    texcoords.insert(texcoords.end(), other.texcoords.begin(), other.texcoords.end());
    triangle_uv.resize(triangles.size() - other.triangles.size(), {-1, -1, -1});
    for (const auto& t : other.triangle_uv)
      triangle_uv.push_back(t[0] < 0 ? t : std::array<int32_t, 3>{t[0] + uv_base, t[1] + uv_base, t[2] + uv_base});
  }
}

namespace {

// Reading an OBJ needs about 12 times its size (its text twice, tinyobjloader's arrays, the
// mesh); measured 6.8x on a 38 MB file of a million triangles, more for files of short lines.
constexpr double kObjBytesPerFileByte = 12.0;

void check_geometry_file_cost(const std::string& path) {
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  if (error || !std::filesystem::is_regular_file(path, error)) return;  // the reader reports it
  const MemoryLimit limit = memory_limit();
  const double need = kObjBytesPerFileByte * static_cast<double>(size);
  if (need > static_cast<double>(limit.bytes))
    throw CostError("geometry '" + quoted_path(path) + "' is " + format_bytes(static_cast<double>(size)) + "; " +
                    memory_refusal("reading it", need, need, limit, "a smaller geometry file (fewer triangles)"));
}

std::string read_text(const std::string& path) {
  check_input_file(path, "geometry file", limits::kMaxGeometryFileBytes);
  check_geometry_file_cost(path);  // before reading: about 12x its size in memory
  return read_whole_file(path, "geometry file");
}

// tinyobjloader resolves `usemtl` only against materials read through `mtllib`; the scene
// file, not an MTL file, defines Fenestra's materials, so we hand it one MTL naming them all.
// Every line tinyobjloader could refuse or misread is checked here first, with its line number:
// tinyobjloader would read "nan", "1e999", "0x10" (as 16) or "1e" as some number.
[[noreturn]] void fail_at(const std::string& path, size_t line_number, const std::string& message) {
  throw std::invalid_argument("geometry '" + quoted_text(path) + "', line " + std::to_string(line_number) + ": " +
                              message);
}

// The numbers of a `v`, `vt` or `vn` line: `least` to `most` of them, each a plain decimal number.
// Vertex coordinates must also lie in the accepted range; they are kept in `vertices` (in double:
// tinyobjloader reads them in float, which keeps only 0.06 m of a coordinate in the millions).
void check_number_line(const std::string& path, size_t line_number, std::istringstream& words,
                       const std::string& keyword, int least, int most, std::vector<Vec3d>* vertices = nullptr) {
  Vec3d p = Vec3d::Zero();
  const std::string what = keyword == "v" ? "vertex coordinate" : keyword == "vt" ? "texture coordinate (vt)"
                                                                                  : "normal (vn) component";
  int count = 0;
  std::string token;
  while (words >> token) {
    if (++count > most)
      fail_at(path, line_number, "a `" + keyword + "` line takes at most " + std::to_string(most) + " numbers");
    if (!is_decimal_number(token))
      fail_at(path, line_number, what + " '" + quoted_text(token) +
                                     "' is not a finite decimal number (such as 1, -0.5 or 2.5e-3)");
    const double v = std::strtod(token.c_str(), nullptr);
    if (!std::isfinite(v)) fail_at(path, line_number, what + " '" + quoted_text(token) + "' is not a finite number");
    if (keyword == "v" && count <= 3 && !coordinate_in_range(v))
      fail_at(path, line_number, what + " " + quoted_text(token) + " is out of range (coordinates " +
                                     coordinate_requirement() + ")");
    if (count <= 3) p[count - 1] = v;
  }
  if (count < least)
    fail_at(path, line_number, "a `" + keyword + "` line needs " + std::to_string(least) + " numbers, got " +
                                   std::to_string(count));
  if (vertices) vertices->push_back(p);
}

// tinyobjloader reads indices with wrapping integer arithmetic (an index past 2^64 silently
// becomes another vertex): every index of a face must be a plain integer naming an existing
// vertex, texture coordinate or normal (1..n, or -1..-n counting back from the last one so far).
// Positive indices are checked against the counts once the whole file is read.
// Counts of the indexed kinds (vertex, texture coordinate, normal) so far, and the largest index
// faces used of each, with its line.
struct IndexedKinds {
  size_t so_far[3] = {0, 0, 0};
  long long largest[3] = {0, 0, 0};
  size_t largest_line[3] = {0, 0, 0};
};

void check_face_line(const std::string& path, size_t line_number, std::istringstream& words, IndexedKinds* kinds_seen) {
  std::string token;
  int corners = 0;
  while (words >> token) {
    ++corners;
    if (std::count(token.begin(), token.end(), '/') > 2)
      fail_at(path, line_number, "face corner '" + quoted_text(token) + "' is not v, v/vt, v//vn or v/vt/vn");
    size_t start = 0;
    for (int field = 0; field < 3 && start <= token.size(); ++field) {
      const size_t slash = token.find('/', start);
      const std::string index = token.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
      start = slash == std::string::npos ? token.size() + 1 : slash + 1;
      if (index.empty() && field > 0) continue;  // "v//vn" or "v/vt"
      const char* kinds[] = {"vertex", "texture coordinate", "normal"};
      auto fail = [&](const std::string& why) {
        fail_at(path, line_number, std::string("face ") + kinds[field] + " index '" + quoted_text(index) + "' " + why);
      };
      const size_t signs = std::min(index.find_first_not_of("-+"), index.size());
      if (index.empty() || signs > 1 || index.size() == signs ||
          index.find_first_not_of("0123456789", signs) != std::string::npos)
        fail("is not an integer");
      if (index.size() - signs > 9) fail("is out of range (at most 999999999)");
      const long long v = std::stoll(index);
      if (v == 0) fail("is 0 (OBJ indices start at 1)");
      const size_t so_far = kinds_seen->so_far[field];
      if (v < 0 && static_cast<size_t>(-v) > so_far)
        fail(std::string("refers back past the first ") + kinds[field] + " (" + std::to_string(so_far) + " so far)");
      if (v > kinds_seen->largest[field]) kinds_seen->largest[field] = v, kinds_seen->largest_line[field] = line_number;
    }
  }
  if (corners < 3)
    fail_at(path, line_number, "a face needs at least 3 corners, got " + std::to_string(corners));
}

// Also returns the vertices in double: tinyobjloader reads them in float, which keeps only 0.06 m of a
// coordinate in the millions (site coordinates).
std::string prepare_obj_text(const std::string& path, const std::string& text, std::set<std::string>* used,
                             std::vector<Vec3d>* vertices) {
  std::istringstream in(text);
  std::ostringstream out;
  // A failed allocation in a stream only sets badbit, which would end the loop below as if the
  // file had ended: the streams throw it instead.
  in.exceptions(std::ios::badbit);
  out.exceptions(std::ios::badbit);
  out << "mtllib fenestra_materials.mtl\n";
  std::string line;
  size_t line_number = 0;
  IndexedKinds kinds;
  while (std::getline(in, line)) {
    ++line_number;
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    // x y z, with an optional w or r g b (tinyobjloader's vertex colours).
    if (keyword == "v") check_number_line(path, line_number, words, keyword, 3, 6, vertices), ++kinds.so_far[0];
    if (keyword == "vt") check_number_line(path, line_number, words, keyword, 1, 3), ++kinds.so_far[1];
    if (keyword == "vn") check_number_line(path, line_number, words, keyword, 3, 3), ++kinds.so_far[2];
    if (keyword == "f") check_face_line(path, line_number, words, &kinds);
    // Lines, points and skin weights light nothing: left out (the line kept, for the numbering).
    if (keyword == "mtllib" || keyword == "l" || keyword == "p" || keyword == "vw") {
      out << "#\n";
      continue;
    }
    if (keyword == "usemtl") {
      std::string name;
      std::getline(words, name);
      name.erase(0, name.find_first_not_of(" \t"));
      name.erase(name.find_last_not_of(" \t\r") + 1);
      used->insert(name);
    }
    out << line << "\n";
  }
  const char* names[] = {"vertex", "texture coordinate", "normal"};
  const char* plurals[] = {"vertices", "texture coordinates (vt)", "normals (vn)"};
  for (int k = 0; k < 3; ++k)
    if (kinds.largest[k] > static_cast<long long>(kinds.so_far[k]))
      fail_at(path, kinds.largest_line[k],
              std::string("face ") + names[k] + " index " + std::to_string(kinds.largest[k]) + " is past the last " +
                  (k == 0 ? "vertex" : names[k]) + " (the file has " + std::to_string(kinds.so_far[k]) + " " +
                  plurals[k] + ")");
  return out.str();
}

// The local frame of the vertices (a site frame around them, or the origin), each vertex checked to
// lie within range of it.
SiteFrame frame_of(const std::string& path, const std::vector<Vec3d>& vertices, bool centre) {
  if (vertices.empty() || !centre) return {};
  Vec3d lo = vertices.front(), hi = vertices.front();
  for (const Vec3d& v : vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const SiteFrame frame = SiteFrame::around(lo, hi);
  for (size_t i = 0; i < vertices.size(); ++i)
    if (!local_coordinates_in_range(frame.to_local_exact(vertices[i])))
      throw std::invalid_argument("geometry '" + quoted_text(path) + "': vertex " + std::to_string(i + 1) + " " +
                                  local_range_problem(frame.origin));
  return frame;
}

Mesh read_obj(const std::string& path, const std::vector<std::string>& material_names, SiteFrame* frame) {
  std::set<std::string> used;
  std::vector<Vec3d> vertices;
  const std::string obj_text = prepare_obj_text(path, read_text(path), &used, &vertices);
  const SiteFrame local = frame_of(path, vertices, frame != nullptr);
  if (frame) *frame = local;
  for (const auto& name : used) {
    if (std::find(material_names.begin(), material_names.end(), name) == material_names.end())
      throw std::invalid_argument("geometry '" + quoted_text(path) + "' uses material '" + quoted_text(name) +
                                  "', which the scene file's \"materials\" does not define");
  }
  std::ostringstream mtl;
  for (const auto& name : used) mtl << "newmtl " << name << "\n";

  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // Every line it could refuse was checked above; its own message, numbering the lines of the
  // text it was given, is not shown.
  if (!reader.ParseFromString(obj_text, mtl.str(), config))
    throw std::invalid_argument("geometry '" + quoted_text(path) + "' could not be read as an OBJ file");
  const auto& attrib = reader.GetAttrib();
  const auto& shapes = reader.GetShapes();
  const auto& mtls = reader.GetMaterials();

  Mesh mesh;
  const size_t vertex_count = vertices.size();
  if (attrib.vertices.size() != 3 * vertex_count)
    throw std::invalid_argument("geometry '" + quoted_text(path) + "': cannot read its vertices (" + std::to_string(vertex_count) +
                                " 'v' lines, " + std::to_string(attrib.vertices.size() / 3) + " vertices read)");
  mesh.positions.reserve(vertex_count);
  for (const Vec3d& v : vertices) mesh.positions.push_back(local.to_local(v));
  const size_t texcoord_count = attrib.texcoords.size() / 2;
  mesh.texcoords.reserve(texcoord_count);
  for (size_t i = 0; i < texcoord_count; ++i) {
    const Vec2 t(attrib.texcoords[2 * i], attrib.texcoords[2 * i + 1]);
    if (!std::isfinite(t.x()) || !std::isfinite(t.y()) || std::abs(t.x()) > 1e6f || std::abs(t.y()) > 1e6f) {
      std::ostringstream s;
      s << "geometry '" << path << "': texture coordinate (vt) " << i + 1 << " is not a finite number within 1e6";
      throw std::invalid_argument(s.str());
    }
    mesh.texcoords.push_back(t);
  }

  std::map<std::string, int> group_index;
  const int default_material = [&] {
    auto it = std::find(material_names.begin(), material_names.end(), "default");
    return it == material_names.end() ? -1 : static_cast<int>(it - material_names.begin());
  }();
  for (const auto& shape : shapes) {
    int group = -1;
    if (!shape.name.empty()) {
      auto it = group_index.find(shape.name);
      if (it == group_index.end()) {
        group = static_cast<int>(mesh.group_names.size());
        group_index[shape.name] = group;
        mesh.group_names.push_back(shape.name);
      } else {
        group = it->second;
      }
    }
    const auto& m = shape.mesh;
    size_t offset = 0;
    for (size_t f = 0; f < m.num_face_vertices.size(); ++f) {
      const int n = m.num_face_vertices[f];
      if (n != 3) {
        offset += n;
        continue;  // lines or points left by the triangulator
      }
      std::array<uint32_t, 3> tri;
      std::array<int32_t, 3> uv;
      for (int k = 0; k < 3; ++k) {
        const int vi = m.indices[offset + k].vertex_index;
        if (vi < 0 || static_cast<size_t>(vi) >= vertex_count)
          throw std::invalid_argument("geometry '" + quoted_path(path) + "': a face refers to a missing vertex");
        tri[k] = static_cast<uint32_t>(vi);
        const int ti = m.indices[offset + k].texcoord_index;
        if (ti >= 0 && static_cast<size_t>(ti) >= texcoord_count)
          throw std::invalid_argument("geometry '" + quoted_path(path) + "': a face refers to a missing texture coordinate (vt)");
        uv[k] = ti;
      }
      if (uv[0] < 0 || uv[1] < 0 || uv[2] < 0) uv = {-1, -1, -1};
      offset += 3;
      int material = default_material;
      const int mid = m.material_ids[f];
      if (mid >= 0) {
        const std::string& name = mtls[mid].name;
        material = static_cast<int>(std::find(material_names.begin(), material_names.end(), name) -
                                    material_names.begin());
      }
      if (material < 0) {
        throw std::invalid_argument("geometry '" + quoted_text(path) + "': faces of group '" + quoted_text(shape.name) +
                                    "' have no material (no usemtl, and no material named \"default\")");
      }
      mesh.triangles.push_back(tri);
      mesh.triangle_uv.push_back(uv);
      mesh.triangle_material.push_back(material);
      mesh.triangle_group.push_back(group);
      const float area2 = mesh.area_normal(mesh.triangles.size() - 1).norm();
      if (!(area2 > 1e-10f)) {
        std::ostringstream s;
        s << "geometry '" << quoted_text(path) << "': face " << f + 1 << " of group '" << quoted_text(shape.name)
          << "' is degenerate (zero area)";
        throw std::invalid_argument(s.str());
      }
    }
  }
  if (mesh.triangles.empty()) throw std::invalid_argument("geometry '" + quoted_path(path) + "' has no faces");
  return mesh;
}

}  // namespace

Mesh load_obj(const std::string& path, const std::vector<std::string>& material_names, SiteFrame* frame) {
  return out_of_memory_while("reading geometry file '" + quoted_path(path) + "'",
                             [&] { return read_obj(path, material_names, frame); });
}

}  // namespace fenestra
