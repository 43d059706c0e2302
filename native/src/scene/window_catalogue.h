#pragma once
// Window catalogues: the sizes an opening may take (solver.constraints.catalogue). On walls a
// size is width (horizontal, along the panel's u axis) x height; on roofs a skylight may lie
// either way round. Built-in catalogues are known by name.
#include <string>
#include <vector>

namespace fenestra {

struct Panel;

struct CatalogueSize {
  double width = 0.0, height = 0.0;  // meters
  bool operator==(const CatalogueSize& o) const { return width == o.width && height == o.height; }
};

struct WindowCatalogue {
  std::string name;  // a built-in's name, or "custom"
  // Sizes for walls and for roofs; a list left empty leaves that kind of panel free.
  std::vector<CatalogueSize> walls, roofs;

  bool empty() const { return walls.empty() && roofs.empty(); }
  // The sizes an opening on `panel` may take (roofs: both ways round), or none when it is free.
  std::vector<CatalogueSize> sizes_for(const Panel& panel) const;
  // Whether width x height is one of the panel's sizes, to kSizeTolerance.
  bool allows(const Panel& panel, double width, double height) const;
};

constexpr double kCatalogueSizeTolerance = 1e-4;  // meters

// Built-in catalogues: "residential" (the default one: walls 0.6-1.8 m wide x 1.2-2.1 m high,
// common roof-window sizes) and "commercial" (larger bays).
std::vector<std::string> catalogue_names();
// Throws std::invalid_argument listing the names when `name` is none of them.
WindowCatalogue builtin_catalogue(const std::string& name);

}  // namespace fenestra
