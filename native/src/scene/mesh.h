#pragma once
// Triangle soup with a material and a group per triangle, as read from the scene's OBJ.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "math/vec.h"
#include "scene/site_frame.h"

namespace fenestra {

struct Mesh {
  std::vector<Vec3> positions;                    // meters
  std::vector<std::array<uint32_t, 3>> triangles;  // indices into positions
  std::vector<int> triangle_material;             // index into the scene's materials
  std::vector<int> triangle_group;                // index into group_names, -1 when ungrouped
  std::vector<std::string> group_names;
  // The UV map, where the model has one: texcoords[triangle_uv[t][k]] at corner k of triangle t;
  // triangle_uv may be shorter than triangles, and -1 marks a triangle without UVs.
  std::vector<Vec2> texcoords;
  std::vector<std::array<int32_t, 3>> triangle_uv;

  size_t triangle_count() const { return triangles.size(); }
  Vec3 vertex(size_t tri, int corner) const { return positions[triangles[tri][corner]]; }
  // Unnormalised normal (v1 - v0) x (v2 - v0): length is twice the area.
  Vec3 area_normal(size_t tri) const {
    return (vertex(tri, 1) - vertex(tri, 0)).cross(vertex(tri, 2) - vertex(tri, 0));
  }
  bool has_uv(size_t tri) const { return tri < triangle_uv.size() && triangle_uv[tri][0] >= 0; }
  Vec2 uv(size_t tri, int corner) const { return texcoords[triangle_uv[tri][corner]]; }
  void append(const Mesh& other);
};

// Reads a Wavefront OBJ (triangulated on load). `usemtl` names are resolved through
// `material_index` (name -> index, -1 if unknown, which is an error naming the file);
// `g`/`o` names become groups. Throws std::invalid_argument with the file name on bad input.
// Vertices are read in double. With `frame`, the loader chooses a local frame around them
// (SiteFrame::around: the origin, or the model's centre in whole meters), stores the positions
// relative to it and returns it there; without, positions are stored as given.
Mesh load_obj(const std::string& path, const std::vector<std::string>& material_names, SiteFrame* frame = nullptr);

}  // namespace fenestra
