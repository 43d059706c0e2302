// fenestra._core: sensor grids over the rooms' floors (study/sensor_grid.h).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "study/sensor_grid.h"

namespace py = pybind11;
using namespace fenestra;

namespace {

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Indices = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;
using Marks = py::array_t<bool, py::array::c_style | py::array::forcecast>;

// An (n, 3) array named `name` in the message when it is not one.
void require_rows_of_three(const py::array& a, const char* name) {
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw std::invalid_argument(std::string("sensor_grid: ") + name + " must be an (n, 3) array, not one of " +
                                std::to_string(a.ndim()) + " dimensions and " + std::to_string(a.size()) + " values");
}

}  // namespace

void bind_sensor_grid(py::module_& m) {
  m.def(
      "sensor_grid",
      [](const Doubles& vertices, const Indices& triangles, const Marks& floors, double height, double spacing,
         py::object inset) {
        require_rows_of_three(vertices, "vertices");
        require_rows_of_three(triangles, "triangles");
        if (floors.ndim() != 1 || floors.shape(0) != triangles.shape(0))
          throw std::invalid_argument("sensor_grid: floors must mark each of the " + std::to_string(triangles.shape(0)) +
                                      " triangles (a bool array of that length)");
        std::vector<Vec3d> positions(static_cast<size_t>(vertices.shape(0)));
        const auto v = vertices.unchecked<2>();
        for (py::ssize_t i = 0; i < vertices.shape(0); ++i) positions[i] = Vec3d(v(i, 0), v(i, 1), v(i, 2));
        std::vector<std::array<uint32_t, 3>> tris(static_cast<size_t>(triangles.shape(0)));
        const auto t = triangles.unchecked<2>();
        for (py::ssize_t i = 0; i < triangles.shape(0); ++i)
          for (int k = 0; k < 3; ++k) {
            const int64_t index = t(i, k);
            if (index < 0 || index >= vertices.shape(0))
              throw std::invalid_argument("sensor_grid: triangle " + std::to_string(i) + " names vertex " +
                                          std::to_string(index) + ", but there are " +
                                          std::to_string(vertices.shape(0)) + " vertices");
            tris[i][k] = static_cast<uint32_t>(index);
          }
        std::vector<uint8_t> marks(static_cast<size_t>(floors.shape(0)));
        const auto f = floors.unchecked<1>();
        for (py::ssize_t i = 0; i < floors.shape(0); ++i) marks[i] = f(i) ? 1 : 0;
        SensorGridSettings settings;
        settings.height = height;
        settings.spacing = spacing;
        if (!inset.is_none()) settings.inset = inset.cast<double>();
        if (!inset.is_none() && !(settings.inset >= 0.0))
          throw std::invalid_argument("sensor_grid: inset " + std::string(py::str(inset)) +
                                      " m is not a length from 0 m to 100 m");
        SensorGrid grid;
        {
          py::gil_scoped_release release;
          grid = sensor_grid(positions, tris, marks, settings);
        }
        py::list rooms;
        for (const SensorRoom& r : grid.rooms) {
          py::array_t<double> points({static_cast<py::ssize_t>(r.points.size()), py::ssize_t(3)});
          auto p = points.mutable_unchecked<2>();
          for (size_t i = 0; i < r.points.size(); ++i)
            for (int k = 0; k < 3; ++k) p(i, k) = r.points[i][k];
          py::array_t<int64_t> quads({static_cast<py::ssize_t>(r.quads.size()), py::ssize_t(4)});
          auto q = quads.mutable_unchecked<2>();
          for (size_t i = 0; i < r.quads.size(); ++i)
            for (int k = 0; k < 4; ++k) q(i, k) = r.quads[i][k];
          py::dict room;
          room["points"] = points;
          room["floor_z"] = py::array_t<double>(static_cast<py::ssize_t>(r.floor_z.size()), r.floor_z.data());
          room["quads"] = quads;
          rooms.append(room);
        }
        py::dict out;
        out["rooms"] = rooms;
        out["inset"] = grid.inset;
        out["enclosed"] = grid.enclosed;
        return out;
      },
      py::arg("vertices"), py::arg("triangles"), py::arg("floors"), py::arg("height") = 0.8,
      py::arg("spacing") = 0.5, py::arg("inset") = py::none(),
      "Sensor grids over the rooms' floors (docs/sensors.md): `vertices` (n, 3) meters, `triangles` (m, 3) "
      "indices, `floors` (m,) bool marking the faces that may hold sensors. Returns {\"rooms\": [{\"points\" (k, 3) "
      "meters, \"floor_z\" (k,) meters, \"quads\" (q, 4) indices}], \"inset\" meters, \"enclosed\" bool}.");
}
