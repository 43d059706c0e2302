// fenestra._core: the native core for Python (and Blender). Long calls release the GIL.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "io/atomic_file.h"
#include "io/image_writer.h"
#include "io/results.h"
#include "io/sky_output.h"
#include "io/solve_result.h"
#include "solve/solver.h"
#include "trace/ray_scene.h"
#include "scene/scene.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"

namespace py = pybind11;
using namespace fenestra;

void bind_daylight(py::module_& m);  // bind_daylight.cpp
void bind_solver(py::module_& m);    // bind_solver.cpp

namespace {

// A read-only NumPy view of an Eigen matrix owned by `owner` (no copy).
py::array view(const Eigen::MatrixXd& m, py::handle owner) {
  py::array a(py::dtype::of<double>(), {m.rows(), m.cols()},
              {static_cast<py::ssize_t>(sizeof(double)), static_cast<py::ssize_t>(sizeof(double) * m.rows())},
              m.data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}
py::array view(const Eigen::VectorXd& v, py::handle owner) {
  py::array a(py::dtype::of<double>(), {v.size()}, {static_cast<py::ssize_t>(sizeof(double))}, v.data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::tuple values_tuple(SensorValues v) {
  return py::make_tuple(py::array_t<double>(v.value.size(), v.value.data()),
                        py::array_t<double>(v.standard_error.size(), v.standard_error.data()));
}

std::vector<Rectangle> rectangles_from(py::array_t<double, py::array::c_style | py::array::forcecast> a) {
  if (a.ndim() == 2 && a.shape(0) == 0) return {};
  if (a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 3)
    throw std::invalid_argument("openings must be an array of shape (n, 4, 3): four corners per rectangle, meters");
  std::vector<Rectangle> out(a.shape(0));
  auto r = a.unchecked<3>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (int c = 0; c < 4; ++c) {
      out[i][c] = Vec3(r(i, c, 0), r(i, c, 1), r(i, c, 2));
      if (!is_finite(out[i][c]))
        throw std::invalid_argument("opening " + std::to_string(i) + " has a non-finite corner");
    }
  return out;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "Fenestra native core: opening-contribution path tracing on Embree.";
  bind_daylight(m);
  bind_solver(m);
  static py::exception<Cancelled> cancelled(m, "Cancelled");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Cancelled& e) {
      cancelled(e.what());
    }
  });

  py::class_<Progress, std::shared_ptr<Progress>>(m, "Progress",
                                                  "Shared progress of a running computation; cancel() stops it.")
      .def(py::init<>())
      .def_property_readonly("fraction", &Progress::fraction, "Fraction of the current stage done, 0..1.")
      .def_property_readonly("status", &Progress::status, "What the computation is doing.")
      .def_property_readonly("cancelled", &Progress::cancelled)
      .def("cancel", &Progress::cancel, "Ask the computation to stop; it raises fenestra.Cancelled.")
      .def("__repr__", [](const Progress& p) {
        return "Progress(" + p.status() + ", " + std::to_string(p.fraction()) + ")";
      });

  py::class_<RenderSettings>(m, "RenderSettings")
      .def_readwrite("paths_per_sensor", &RenderSettings::paths_per_sensor)
      .def_readwrite("max_bounces", &RenderSettings::max_bounces)
      .def_readwrite("seed", &RenderSettings::seed)
      .def_readwrite("threads", &RenderSettings::threads)
      .def("__repr__", &RenderSettings::to_string);

  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene", "A scene read from a Fenestra scene file (JSON + OBJ).")
      .def_static(
          "load",
          [](const std::string& path, std::shared_ptr<Progress> progress) {
            py::gil_scoped_release release;  // a daylight sky takes a while to build
            return std::make_shared<Scene>(load_scene(path, progress.get()));
          },
          py::arg("path"), py::arg("progress") = nullptr,
          "Reads a scene file; raises ValueError naming the file and the problem. A daylight sky's build "
          "reports to `progress` and stops on its cancel() (raises Cancelled).")
      .def_static(
          "from_json",
          [](const std::string& text, const std::string& base_dir, const std::string& name,
             std::shared_ptr<Progress> progress) {
            py::gil_scoped_release release;
            return std::make_shared<Scene>(parse_scene(text, base_dir, name, progress.get()));
          },
          py::arg("text"), py::arg("base_dir") = ".", py::arg("name") = "<json>", py::arg("progress") = nullptr,
          "Parses scene JSON text; relative file names resolve against base_dir.")
      .def_readonly("source", &Scene::source)
      .def_property(
          "render", [](Scene& s) -> RenderSettings& { return s.render; },
          [](Scene& s, const RenderSettings& r) { s.render = r; }, py::return_value_policy::reference_internal)
      .def_property_readonly("sensor_count", [](const Scene& s) { return s.sensors.size(); })
      .def_property_readonly("element_count", [](const Scene& s) { return s.domain.element_count(); })
      .def_property_readonly("triangle_count", [](const Scene& s) { return s.mesh.triangle_count(); })
      .def_property_readonly("element_size", [](const Scene& s) { return s.domain.element_size(); })
      .def_property_readonly("sensor_points",
                             [](const Scene& s) {
                               py::array_t<double> a({static_cast<py::ssize_t>(s.sensors.size()), py::ssize_t(3)});
                               auto w = a.mutable_unchecked<2>();
                               for (size_t i = 0; i < s.sensors.size(); ++i)
                                 for (int k = 0; k < 3; ++k) w(i, k) = s.sensors.points[i][k];
                               return a;
                             })
      .def_property_readonly("goals",
                             [](const Scene& s) -> py::object {
                               if (s.sensors.goals.empty()) return py::none();
                               return py::array_t<double>(s.sensors.goals.size(), s.sensors.goals.data());
                             })
      .def_property_readonly("goal_units", [](const Scene& s) { return s.sensors.goal_units; })
      .def_property_readonly("element_corners",
                             [](const Scene& s) {
                               const auto& el = s.domain.elements();
                               py::array_t<double> a({static_cast<py::ssize_t>(el.size()), py::ssize_t(4), py::ssize_t(3)});
                               auto w = a.mutable_unchecked<3>();
                               for (size_t k = 0; k < el.size(); ++k)
                                 for (int c = 0; c < 4; ++c)
                                   for (int d = 0; d < 3; ++d) w(k, c, d) = el[k].corners[c][d];
                               return a;
                             },
                             "Corners of every element, shape (elements, 4, 3), meters.")
      .def_property_readonly("element_grid",
                             [](const Scene& s) {
                               const auto& el = s.domain.elements();
                               py::array_t<int32_t> a({static_cast<py::ssize_t>(el.size()), py::ssize_t(3)});
                               auto w = a.mutable_unchecked<2>();
                               for (size_t k = 0; k < el.size(); ++k) w(k, 0) = el[k].panel, w(k, 1) = el[k].row, w(k, 2) = el[k].col;
                               return a;
                             },
                             "(panel, row, column) of every element, shape (elements, 3).")
      .def("elements_json", [](const Scene& s) { return elements_json(s).dump(); })
      .def("__repr__", &Scene::to_string);

  py::class_<Contributions, std::shared_ptr<Contributions>>(m, "Contributions",
                                                            "Result of one contribution pass over every sensor.")
      .def_property_readonly("E", [](py::object self) { return view(self.cast<Contributions&>().E, self); })
      .def_property_readonly("E_stderr", [](py::object self) { return view(self.cast<Contributions&>().E_stderr, self); })
      .def_property_readonly("A", [](py::object self) { return view(self.cast<Contributions&>().A, self); })
      .def_property_readonly("T", [](py::object self) { return view(self.cast<Contributions&>().T, self); })
      .def_property_readonly("closed", [](py::object self) { return view(self.cast<Contributions&>().closed.value, self); })
      .def_property_readonly("closed_stderr",
                             [](py::object self) { return view(self.cast<Contributions&>().closed.standard_error, self); })
      .def_property_readonly("all_open",
                             [](py::object self) { return view(self.cast<Contributions&>().all_open.value, self); })
      .def_property_readonly("all_open_stderr",
                             [](py::object self) { return view(self.cast<Contributions&>().all_open.standard_error, self); })
      .def_readonly("paths_per_sensor", &Contributions::paths_per_sensor)
      .def_readonly("seconds", &Contributions::seconds)
      .def_readonly("events", &Contributions::events)
      .def_property_readonly("memory_bytes", &Contributions::memory_bytes)
      .def(
          "evaluate",
          [](const Contributions& c, py::array_t<uint8_t, py::array::c_style | py::array::forcecast> open,
             std::shared_ptr<Progress> progress) {
            if (open.ndim() != 1) throw std::invalid_argument("open mask must be one-dimensional");
            std::vector<uint8_t> mask(open.data(), open.data() + open.size());
            SensorValues v;
            {
              py::gil_scoped_release release;
              v = c.evaluate(mask, progress.get());
            }
            return values_tuple(std::move(v));
          },
          py::arg("open"), py::arg("progress") = nullptr,
          "Exact (value, stderr) per sensor with the elements where open is true open, from the recorded paths.")
      .def("save", [](const Contributions& c, const Scene& s, const std::string& out) { return write_contributions(s, c, out); },
           py::arg("scene"), py::arg("path"), "Writes PATH.npz and PATH.json; returns both paths.")
      .def("__repr__", [](const Contributions& c) {
        return "Contributions(" + std::to_string(c.sensor_count()) + " sensors x " + std::to_string(c.element_count()) +
               " elements, " + std::to_string(c.paths_per_sensor) + " paths per sensor)";
      });

  m.def(
      "compute_contributions",
      [](const Scene& scene, std::shared_ptr<Progress> progress) {
        py::gil_scoped_release release;
        return std::make_shared<Contributions>(compute_contributions(scene, progress.get()));
      },
      py::arg("scene"), py::arg("progress") = nullptr, "One pass of paths per sensor (see Contributions).");
  m.def(
      "evaluate",
      [](const Scene& scene, py::array_t<double, py::array::c_style | py::array::forcecast> openings,
         std::shared_ptr<Progress> progress) {
        const auto rects = rectangles_from(openings);
        SensorValues v;
        {
          py::gil_scoped_release release;
          v = evaluate_openings(scene, rects, progress.get());
        }
        return values_tuple(std::move(v));
      },
      py::arg("scene"), py::arg("openings"), py::arg("progress") = nullptr,
      "Path-traces the scene with rectangles (n, 4, 3) cut; returns (value, stderr) per sensor.");
  m.def(
      "write_image",
      [](const std::string& path, py::array_t<float, py::array::c_style | py::array::forcecast> image) {
        if (image.ndim() != 3) throw std::invalid_argument("image must have shape (height, width, channels)");
        std::vector<float> pixels(image.data(), image.data() + image.size());
        write_image(path, static_cast<int>(image.shape(1)), static_cast<int>(image.shape(0)),
                    static_cast<int>(image.shape(2)), pixels);
      },
      py::arg("path"), py::arg("image"),
      "Writes a linear float image (height, width, channels), top row first, e.g. an environment map (.exr/.hdr).");
  m.def(
      "solve",
      [](const Scene& scene, std::shared_ptr<Contributions> contributions, std::shared_ptr<Progress> progress) {
        std::string text;
        {
          py::gil_scoped_release release;
          const SolveResult r = contributions ? solve_openings(scene, *contributions, progress.get())
                                              : solve_openings(scene, progress.get());
          text = solve_result_json(scene, r).dump();
        }
        return text;
      },
      py::arg("scene"), py::arg("contributions") = nullptr, py::arg("progress") = nullptr,
      "The opening solver; returns the result as JSON text (docs/solver.md).");
  m.def(
      "sky_map",
      [](const Scene& scene) {
        const SkyImage image = sky_image(scene);
        py::array_t<float> a({static_cast<py::ssize_t>(image.height), static_cast<py::ssize_t>(image.width),
                              py::ssize_t(3)});
        float* out = a.mutable_data();
        for (size_t i = 0; i < image.pixels.size(); ++i)
          for (int c = 0; c < 3; ++c) out[3 * i + c] = image.pixels[i][c];
        return a;
      },
      py::arg("scene"),
      "The scene's sky as an equirectangular map (height, width, 3), linear sRGB cd/m^2, top row = zenith.");
  m.def(
      "sky_summary", [](const Scene& scene) { return sky_summary(scene).dump(); }, py::arg("scene"),
      "JSON text: horizontal illuminances (lux) and the sun list of the scene's sky.");
  m.def(
      "write_sky",
      [](const Scene& scene, const std::string& path) {
        check_output_path(path, scene.input_files);  // before the map is made; never over an input
        write_sky_image(path, sky_image(scene));
      },
      py::arg("scene"), py::arg("path"), "Writes the scene's sky map (.exr or .hdr).");
  m.def("rays_traced", &rays_traced, "Rays traced by parallel computations since the module was loaded.");
  m.def("read_openings", [](const std::string& path) {
    const auto rects = read_openings(path);
    py::array_t<double> a({static_cast<py::ssize_t>(rects.size()), py::ssize_t(4), py::ssize_t(3)});
    auto w = a.mutable_unchecked<3>();
    for (size_t i = 0; i < rects.size(); ++i)
      for (int c = 0; c < 4; ++c)
        for (int d = 0; d < 3; ++d) w(i, c, d) = rects[i][c][d];
    return a;
  });
}
