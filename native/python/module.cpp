// fenestra._core: the native core for Python (and Blender). Long calls release the GIL.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "annual/annual_contributions.h"
#include "annual/annual_cut_study.h"
#include "annual/annual_records.h"
#include "annual/annual_study.h"
#include "format/atomic_file.h"
#include "format/image_writer.h"
#include "format/json_input.h"
#include "io/annual_result.h"
#include "io/results.h"
#include "io/sky_output.h"
#include "io/solve_result.h"
#include "number_text.h"
#include "open_masks.h"
#include "scene/input_limits.h"
#include "scene/scene.h"
#include "solve/goals.h"
#include "solve/solver.h"
#include "trace/contributions.h"
#include "trace/contributions_origin.h"
#include "trace/evaluate.h"
#include "trace/ray_scene.h"
#include "util/out_of_memory.h"

namespace py = pybind11;
using namespace fenestra;

void bind_daylight(py::module_& m);  // bind_daylight.cpp
void bind_solver(py::module_& m);    // bind_solver.cpp
void bind_cost(py::module_& m);      // bind_cost.cpp
void bind_shards(py::module_& m);    // bind_shards.cpp
void bind_record_queries(py::module_& m);  // bind_record_queries.cpp
void bind_setup_checks(py::module_& m);    // bind_setup_checks.cpp
void bind_sensor_grid(py::module_& m);     // bind_sensor_grid.cpp
py::tuple annual_parts_tuple(const fenestra::AnnualCoefficients& k, const fenestra::SensorValues& mean);  // bind_record_queries.cpp
// A study's annual parts from its shards, stacked in sensor order (annual_parts_tuple's form), checked
// against `annual`'s sources and sun hours.
fenestra::AnnualRegionParts annual_parts_of(const py::handle& parts, Eigen::Index sensors,
                                            const fenestra::AnnualRecords& annual);  // bind_record_queries.cpp

namespace {

// std::bad_alloc, with what was being done: MemoryError("out of memory while ..."). A reader's
// own OutOfMemory (naming the file) passes through.
template <typename F>
auto while_doing(const std::string& stage, F&& work) {
  return fenestra::out_of_memory_while(stage + ": lower render.paths_per_sensor, the number of sensors or elements "
                                               "(a larger opening_domain.element_size), or the sky's resolution",
                                       std::forward<F>(work));
}

// Native text as a Python str: bytes that are not UTF-8 (e.g. from a file name) are replaced,
// never lost.
py::str text_of(const std::string& s) {
  return py::reinterpret_steal<py::str>(PyUnicode_DecodeUTF8(s.data(), static_cast<py::ssize_t>(s.size()), "replace"));
}

// A Python integer for a render setting, in the same range as the scene file's key; ValueError
// naming the attribute otherwise (TypeError for a non-integer).
long long render_integer(py::handle value, const IntegerRange& range) {
  if (PyBool_Check(value.ptr()) || !PyIndex_Check(value.ptr()))
    throw py::type_error(std::string(range.key) + " must be an integer, got " +
                         std::string(py::str(py::repr(value))));
  const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
  if (!index) throw py::error_already_set();
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
  if (overflow != 0 || !range.contains(v))
    throw std::invalid_argument(std::string(range.key) + " " + range.requirement() + ", got " +
                                std::string(py::str(py::repr(value))));
  return v;
}

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

// None: every sensor; else (begin, end), a block of the scene's sensors.
SensorRange sensor_range_from(const py::object& sensors, const Scene& scene) {
  if (sensors.is_none()) return {};
  const auto pair = sensors.cast<std::pair<py::ssize_t, py::ssize_t>>();
  const size_t count = scene.sensors.size();
  if (pair.first < 0 || pair.second <= pair.first || static_cast<size_t>(pair.second) > count)
    throw std::invalid_argument("sensors (" + std::to_string(pair.first) + ", " + std::to_string(pair.second) +
                                "): expected (begin, end) with 0 <= begin < end <= " + std::to_string(count) +
                                ", the scene's sensor count");
  return {static_cast<size_t>(pair.first), static_cast<size_t>(pair.second)};
}

py::tuple values_tuple(SensorValues v) {
  return py::make_tuple(py::array_t<double>(v.value.size(), v.value.data()),
                        py::array_t<double>(v.standard_error.size(), v.standard_error.data()));
}

// Corners in the scene's input coordinates, returned in its local frame.
std::vector<Rectangle> rectangles_from(py::array_t<double, py::array::c_style | py::array::forcecast> a,
                                       const SiteFrame& frame) {
  if (a.ndim() == 2 && a.shape(0) == 0) return {};
  if (a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 3)
    throw std::invalid_argument("openings must be an array of shape (n, 4, 3): four corners per rectangle, meters");
  std::vector<Rectangle> out(a.shape(0));
  auto r = a.unchecked<3>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (int c = 0; c < 4; ++c) {
      for (int k = 0; k < 3; ++k)
        if (!coordinate_in_range(r(i, c, k))) {
          std::ostringstream s;
          s << "opening " << i << ", corner " << c << ": "
            << (std::isfinite(r(i, c, k)) ? "coordinates " + coordinate_requirement() + ", got "
                                          : std::string("has a non-finite coordinate, "))
            << r(i, c, k);
          throw std::invalid_argument(s.str());
        }
      const Vec3d site(r(i, c, 0), r(i, c, 1), r(i, c, 2));
      if (!local_coordinates_in_range(frame.to_local_exact(site)))
        throw std::invalid_argument("opening " + std::to_string(i) + ", corner " + std::to_string(c) + " " +
                                    local_range_problem(frame.origin));
      out[i][c] = frame.to_local(site);
    }
  return out;
}

// This package's Python API module ("fenestra.api"), set when the module is loaded.
std::string api_module_name;

// Openings from Python: an (n, 4, 3) array of corners, the JSON text of an openings file
// ({"openings": [...]}, with "corners" or "panel" and "parameter_rectangle" each), or any form
// fenestra.api.openings_argument takes (an openings file's dict, a list of openings), turned into
// one of those two by it: every call that takes openings takes the same forms. Corners are in the
// input coordinates of a scene whose local frame is `frame`.
std::vector<OpeningInput> openings_from(const py::object& openings, const SiteFrame& frame) {
  if (!py::isinstance<py::str>(openings) && !py::isinstance<py::array>(openings)) {
    return openings_from(py::module_::import(api_module_name.c_str()).attr("openings_argument")(openings), frame);
  }
  if (py::isinstance<py::str>(openings)) {
    const nlohmann::json j = parse_json_text(openings.cast<std::string>(), "openings", "argument");
    try {
      return parse_openings(j, "argument", frame);
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument("openings 'argument': a value has the wrong type: " + json_error_text(e));
    }
  }
  const auto rects =
      rectangles_from(openings.cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(), frame);
  return std::vector<OpeningInput>(rects.begin(), rects.end());
}

// A sensors x hours float matrix as a C-ordered NumPy array (a copy).
py::array_t<float> float_array(const Eigen::MatrixXf& m) {
  py::array_t<float> a({m.rows(), m.cols()});
  Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(a.mutable_data(), m.rows(), m.cols()) = m;
  return a;
}

// An annual study as a dict of arrays (lux) and its summary (the JSON of `fenestra annual`).
py::dict annual_dict(const AnnualStudy& s) {
  py::dict d;
  d["illuminance"] = float_array(s.illuminance.total);
  d["direct_sun"] = float_array(s.illuminance.direct);
  const size_t hours = s.hours.size();
  py::array_t<int32_t> month(hours), day(hours);
  py::array_t<double> clock(hours);
  py::array_t<bool> occupied(hours);
  for (size_t h = 0; h < hours; ++h) {
    month.mutable_at(h) = s.hours[h].month;
    day.mutable_at(h) = s.hours[h].day;
    clock.mutable_at(h) = s.hours[h].clock_hour;
    occupied.mutable_at(h) = s.occupied[h] != 0;
  }
  d["hour_month"] = month;
  d["hour_day"] = day;
  d["hour_clock"] = clock;
  d["occupied"] = occupied;
  d["summary"] = py::module_::import("json").attr("loads")(
      text_of(annual_json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)));
  return d;
}

// pybind11 before 2.12 reads NumPy arrays by NumPy 1's layout: under NumPy 2 every array crossing
// the module is misread (values repeated, shapes wrong) without an error. Refused at import instead.
void refuse_numpy_it_cannot_read() {
#if PYBIND11_VERSION_MAJOR < 2 || (PYBIND11_VERSION_MAJOR == 2 && PYBIND11_VERSION_MINOR < 12)
  const py::module_ numpy = py::module_::import("numpy");
  const std::string version = py::str(numpy.attr("__version__"));
  if (std::atoi(version.c_str()) < 2) return;
  std::ostringstream m;
  m << "Fenestra's native module reads NumPy 1.x arrays only (it was built with pybind11 " << PYBIND11_VERSION_MAJOR
    << "." << PYBIND11_VERSION_MINOR << "), and this Python has NumPy " << version << " ("
    << std::string(py::str(numpy.attr("__file__"))) << "): install NumPy 1.x in this environment "
    << "(pip install \"numpy>=1.23,<2\"; the wheel's requirement), or use a Python that has it";
  throw py::import_error(m.str());
#endif
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "Fenestra native core: opening-contribution path tracing on Embree.";
  refuse_numpy_it_cannot_read();
  {
    const std::string name = py::str(m.attr("__name__"));  // "fenestra._core"
    api_module_name = name.substr(0, name.rfind('.') + 1) + "api";
  }
  bind_daylight(m);
  bind_solver(m);
  bind_cost(m);
  bind_setup_checks(m);
  bind_sensor_grid(m);
  bind_shards(m);
  bind_record_queries(m);
  static py::exception<Cancelled> cancelled(m, "Cancelled");
  // Every native exception reaches Python with its text, decoded with replacement (pybind11's
  // default translation gives an empty message when the text is not UTF-8, e.g. a file name).
  py::register_exception_translator([](std::exception_ptr p) {
    auto raise = [](PyObject* type, const char* what) {
      PyErr_SetObject(type, text_of(what).ptr());
    };
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::builtin_exception&) {
      throw;  // pybind11's own (TypeError, ...): its default translation
    } catch (const py::error_already_set&) {
      throw;
    } catch (const Cancelled& e) {
      raise(cancelled.ptr(), e.what());
    } catch (const OutOfMemory& e) {
      raise(PyExc_MemoryError, e.what());
    } catch (const std::bad_alloc&) {
      raise(PyExc_MemoryError, "out of memory");
    } catch (const std::out_of_range& e) {
      raise(PyExc_IndexError, e.what());
    } catch (const std::logic_error& e) {  // invalid_argument, domain_error, length_error: bad input
      raise(PyExc_ValueError, e.what());
    } catch (const std::range_error& e) {
      raise(PyExc_ValueError, e.what());
    } catch (const std::overflow_error& e) {
      raise(PyExc_OverflowError, e.what());
    } catch (const std::exception& e) {
      raise(PyExc_RuntimeError, e.what());
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

  // Setters check the scene file's ranges (scene/input_limits.h): ValueError naming the attribute.
  py::class_<RenderSettings>(m, "RenderSettings")
      .def_property(
          "paths_per_sensor", [](const RenderSettings& r) { return r.paths_per_sensor; },
          [](RenderSettings& r, py::handle v) {
            r.paths_per_sensor = static_cast<int>(render_integer(v, limits::kPathsPerSensor));
          })
      .def_property(
          "max_bounces", [](const RenderSettings& r) { return r.max_bounces; },
          [](RenderSettings& r, py::handle v) { r.max_bounces = static_cast<int>(render_integer(v, limits::kMaxBounces)); })
      .def_property(
          "seed", [](const RenderSettings& r) { return r.seed; },
          [](RenderSettings& r, py::handle v) { r.seed = static_cast<uint64_t>(render_integer(v, limits::kSeed)); })
      .def_property(
          "threads", [](const RenderSettings& r) { return r.threads; },
          [](RenderSettings& r, py::handle v) { r.threads = static_cast<int>(render_integer(v, limits::kThreads)); })
      .def_property(
          "sampler", [](const RenderSettings& r) { return std::string(sampler_name(r.sampler)); },
          [](RenderSettings& r, const std::string& name) {
            if (!parse_sampler(name, &r.sampler))
              throw py::value_error("render.sampler: expected 'sobol' or 'independent', got '" + name + "'");
          },
          "'sobol' (stratified first decisions, the default) or 'independent' random numbers")
      .def("__repr__", &RenderSettings::to_string);

  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene", "A scene read from a Fenestra scene file (JSON + OBJ).")
      .def_static(
          "load",
          [](const std::string& path, std::shared_ptr<Progress> progress) {
            py::gil_scoped_release release;  // a daylight sky takes a while to build
            return while_doing("loading scene '" + path + "'",
                               [&] { return std::make_shared<Scene>(load_scene(path, progress.get())); });
          },
          py::arg("path"), py::arg("progress") = nullptr,
          "Reads a scene file; raises ValueError naming the file and the problem. A daylight sky's build "
          "reports to `progress` and stops on its cancel() (raises Cancelled).")
      .def_static(
          "from_json",
          [](const std::string& text, const std::string& base_dir, const std::string& name,
             std::shared_ptr<Progress> progress) {
            py::gil_scoped_release release;
            return while_doing("loading scene '" + name + "'",
                               [&] { return std::make_shared<Scene>(parse_scene(text, base_dir, name, progress.get())); });
          },
          py::arg("text"), py::arg("base_dir") = ".", py::arg("name") = "<json>", py::arg("progress") = nullptr,
          "Parses scene JSON text; relative file names resolve against base_dir.")
      .def_property_readonly(
          "source",
          [](const Scene& s) {  // a file name: undecodable bytes kept as surrogates, as os.fsdecode does
            return py::reinterpret_steal<py::str>(
                PyUnicode_DecodeFSDefaultAndSize(s.source.data(), static_cast<py::ssize_t>(s.source.size())));
          })
      .def_property(
          "render", [](Scene& s) -> RenderSettings& { return s.render; },
          [](Scene& s, const RenderSettings& r) { s.render = r; }, py::return_value_policy::reference_internal)
      .def_property_readonly("has_climate_goals", [](const Scene& s) { return !s.sensors.climate_goals.empty(); },
                             "Whether the scene has goals.climate (sDA, ASE, EN 17037, UDI, annual mean).")
      .def_property_readonly(
          "climate_goal_sensors",
          [](const Scene& s) {
            std::vector<int> out;
            for (const ClimateGoal& g : s.sensors.climate_goals.goals) out.insert(out.end(), g.sensors.begin(), g.sensors.end());
            std::sort(out.begin(), out.end());
            out.erase(std::unique(out.begin(), out.end()), out.end());
            return out;
          },
          "The sensors any climate goal looks at (ascending indices): the climate goals' hourly model's rows.")
      .def_property_readonly("has_climate", [](const Scene& s) { return s.climate != nullptr; },
                             "Whether the sky is \"climate\" (a weather file): annual studies need it.")
      .def_property_readonly("solver_paths", [](const Scene& s) { return s.solver.paths_per_sensor; },
                             "solver.paths: paths per sensor of the solver's contributions (0: render.paths_per_sensor).")
      .def_property_readonly("sensor_count", [](const Scene& s) { return s.sensors.size(); })
      .def_property_readonly("element_count", [](const Scene& s) { return s.domain.element_count(); })
      .def_property_readonly("triangle_count", [](const Scene& s) { return s.mesh.triangle_count(); })
      .def_property_readonly("element_size", [](const Scene& s) { return s.domain.element_size(); })
      .def_property_readonly("site_origin",
                             [](const Scene& s) { return py::make_tuple(s.site.origin.x(), s.site.origin.y(), s.site.origin.z()); },
                             "The local frame's origin in the input's coordinates (meters, whole): (0, 0, 0) for a model "
                             "near the origin; positions in and out are in the input's coordinates.")
      .def_property_readonly("sensor_points",
                             [](const Scene& s) {
                               py::array_t<double> a({static_cast<py::ssize_t>(s.sensors.size()), py::ssize_t(3)});
                               auto w = a.mutable_unchecked<2>();
                               for (size_t i = 0; i < s.sensors.size(); ++i) {
                                 const Vec3d p = s.site.to_site(s.sensors.points[i]);
                                 for (int k = 0; k < 3; ++k) w(i, k) = p[k];
                               }
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
                                   for (int d = 0; d < 3; ++d) w(k, c, d) = s.site.to_site(el[k].corners[c])[d];
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
      .def("constraints_json", [](const Scene& s) { return constraints_json(s.solver.constraints).dump(); },
           "The solver.constraints in force (JSON): the keys that limit something, and \"automatic\", the "
           "keys that took their automatic value.")
      .def("__repr__", [](const Scene& s) { return text_of(s.to_string()); });

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
      .def_property_readonly(
          "dropped",
          [](const Contributions& c) {
            py::dict d;
            d["non_finite"] = c.dropped.non_finite;
            d["truncated_conditions"] = c.dropped.truncated_conditions;
            return d;
          },
          "What the tracer left out while recording: {\"non_finite\": light values that were NaN or infinite, "
          "\"truncated_conditions\": light values or sub-paths past the limit of conditions}; both 0 in a sound scene.")
      .def_property_readonly("memory_bytes", &Contributions::memory_bytes)
      .def_readwrite("warnings", &Contributions::warnings,
                     "The setup checks' warnings (fenestra.contributions sets them; save() writes them).")
      .def(
          "evaluate",
          [](const Contributions& c, const py::object& open, std::shared_ptr<Progress> progress) {
            const auto checked = open_masks(open, static_cast<py::ssize_t>(c.element_count()), false, "open mask");
            const std::vector<uint8_t> mask(checked.data(), checked.data() + checked.size());
            SensorValues v;
            {
              py::gil_scoped_release release;
              v = while_doing("evaluating the contributions", [&] { return c.evaluate(mask, progress.get()); });
            }
            return values_tuple(std::move(v));
          },
          py::arg("open"), py::arg("progress") = nullptr,
          "Exact (value, stderr) per sensor with the elements where open is true open, from the recorded paths.")
      .def(
          "evaluate_openings",
          [](const Contributions& c, const Scene& scene, const py::object& openings, std::shared_ptr<Progress> progress,
             const py::object& sensors) {
            if (sensors.is_none()) {
              check_contributions_match(scene, c, "evaluate_openings");
            } else {  // a shard's contributions: its block of the scene's sensors
              const SensorRange range = sensor_range_from(sensors, scene);
              if (range.size() != c.sensor_count() || c.element_count() != scene.domain.element_count())
                throw std::invalid_argument("evaluate_openings: the shard's contributions (" +
                                            std::to_string(c.sensor_count()) + " sensors x " +
                                            std::to_string(c.element_count()) + " elements) are not sensors " +
                                            std::to_string(range.begin) + ".." + std::to_string(range.end) +
                                            " of this scene");
            }
            const OpenRegion region = region_of_openings(scene, openings_from(openings, scene.site));
            SensorValues v;
            {
              py::gil_scoped_release release;
              v = while_doing("evaluating the contributions", [&] { return c.evaluate(region, progress.get()); });
            }
            return values_tuple(std::move(v));
          },
          py::arg("scene"), py::arg("openings"), py::arg("progress") = nullptr, py::arg("sensors") = py::none(),
          "Exact (value, stderr) per sensor with the openings open (an (n, 4, 3) array of corners, or the JSON "
          "text of an openings file), their edges anywhere on their panels (in thick walls on the element grid's "
          "lines), from the recorded paths.")
      .def_property_readonly("has_annual", [](const Contributions& c) { return c.annual != nullptr; })
      .def(
          "annual",
          [](const Contributions& c, const py::object& open, std::shared_ptr<Progress> progress) {
            const auto checked = open_masks(open, static_cast<py::ssize_t>(c.element_count()), false, "open mask");
            const std::vector<uint8_t> mask(checked.data(), checked.data() + checked.size());
            AnnualStudy study;
            {
              py::gil_scoped_release release;
              study = while_doing("computing the annual illuminance", [&] { return annual_study(c, mask, progress.get()); });
            }
            return annual_dict(study);
          },
          py::arg("open"), py::arg("progress") = nullptr,
          "Every sensor's illuminance at every hour of the weather file's year with the elements where open is "
          "true open (contributions of a \"climate\" scene): a dict of arrays (lux) and the metrics summary.")
      .def(
          "annual_openings",
          [](const Contributions& c, const Scene& scene, const py::object& openings, std::shared_ptr<Progress> progress) {
            const OpenRegion region = region_of_openings(scene, openings_from(openings, scene.site));
            AnnualStudy study;
            {
              py::gil_scoped_release release;
              study = while_doing("computing the annual illuminance",
                                  [&] { return annual_study(scene, c, region, progress.get()); });
            }
            return annual_dict(study);
          },
          py::arg("scene"), py::arg("openings"), py::arg("progress") = nullptr,
          "The annual study of openings (as for evaluate_openings).")
      .def(
          "annual_parts",
          [](const Contributions& c, const Scene& scene, const py::object& openings) {
            const OpenRegion region = region_of_openings(scene, openings_from(openings, scene.site));
            AnnualRegionParts parts;
            {
              py::gil_scoped_release release;
              parts = while_doing("computing the annual coefficients", [&] { return annual_region_parts(c, region); });
            }
            return annual_parts_tuple(parts.coefficients, parts.occupied_mean);
          },
          py::arg("scene"), py::arg("openings"),
          "What annual_openings is made of, for these contributions' sensors (a shard's on a cluster): (sources, "
          "direct, mean, stderr), the daylight coefficients per sensor and source and per sun hour, and the occupied "
          "hours' mean illuminance with its standard error (lux).")
      .def("save_annual",
           [](const Contributions& c, const Scene& scene, const py::object& openings, const std::string& out) {
             const OpenRegion region = region_of_openings(scene, openings_from(openings, scene.site));
             py::gil_scoped_release release;
             return write_annual(scene, annual_study(scene, c, region), out);
           },
           py::arg("scene"), py::arg("openings"), py::arg("path"),
           "Writes the annual study of openings as PATH.npz and PATH.json (as `fenestra annual`); returns both paths.")
      .def("save", [](const Contributions& c, const Scene& s, const std::string& out) { return write_contributions(s, c, out); },
           py::arg("scene"), py::arg("path"), "Writes PATH.npz and PATH.json; returns both paths.")
      .def("__repr__", [](const Contributions& c) {
        return "Contributions(" + std::to_string(c.sensor_count()) + " sensors x " + std::to_string(c.element_count()) +
               " elements, " + std::to_string(c.paths_per_sensor) + " paths per sensor)";
      });

  m.def(
      "compute_contributions",
      [](const Scene& scene, std::shared_ptr<Progress> progress, const py::object& sensors) {
        const SensorRange range = sensor_range_from(sensors, scene);
        const bool whole = sensors.is_none();
        py::gil_scoped_release release;
        auto c = while_doing("computing the contributions of scene '" + scene.source + "'", [&] {
          // A shard leaves T to the client (transport_entries): elements^2 doubles per worker otherwise.
          return std::make_shared<Contributions>(compute_contributions(scene, progress.get(), whole, range));
        });
        c->origin = contributions_origin(scene);  // solve() and save() refuse it for another scene
        return c;
      },
      py::arg("scene"), py::arg("progress") = nullptr, py::arg("sensors") = py::none(),
      "One pass of paths per sensor (see Contributions). `sensors`: (begin, end), only those of the "
      "scene's sensors (a shard; their rows equal the whole pass's bit for bit, and T is left empty: "
      "see transport_entries).");
  m.def(
      "evaluate",
      [](const Scene& scene, const py::object& openings, std::shared_ptr<Progress> progress, const py::object& sensors,
         int paths_per_sensor, uint64_t stream) {
        const auto rects = openings_from(openings, scene.site);
        const SensorRange range = sensor_range_from(sensors, scene);
        if (paths_per_sensor < 0 || paths_per_sensor > limits::kPathsPerSensor.hi)
          throw std::invalid_argument("paths_per_sensor must be 0 (the scene's render.paths_per_sensor) or from 1 to " +
                                      std::to_string(limits::kPathsPerSensor.hi) + ", got " + std::to_string(paths_per_sensor));
        SensorValues v;
        {
          py::gil_scoped_release release;
          v = while_doing("evaluating scene '" + scene.source + "'",
                          [&] { return evaluate_openings(scene, rects, progress.get(), paths_per_sensor, range, stream); });
        }
        return values_tuple(std::move(v));
      },
      py::arg("scene"), py::arg("openings"), py::arg("progress") = nullptr, py::arg("sensors") = py::none(),
      py::arg("paths_per_sensor") = 0, py::arg("stream") = 0,
      "Path-traces the scene with the openings cut (an (n, 4, 3) array of corners, or the JSON text of an "
      "openings file); returns (value, stderr) per sensor (with `sensors` = (begin, end), of those only; "
      "paths_per_sensor 0: the scene's render.paths_per_sensor; `stream`: random numbers of their own, 0 "
      "for the scene's evaluation's).");
  m.def(
      "annual_with_cutters",
      [](const Scene& scene, const py::object& openings, int paths, std::shared_ptr<Progress> progress,
         const std::string& output) {
        const auto given = openings_from(openings, scene.site);
        AnnualStudy study;
        {
          py::gil_scoped_release release;
          study = while_doing("computing the annual study of scene '" + scene.source + "' with the openings cut",
                              [&] { return annual_study_with_cutters(scene, given, progress.get(), paths); });
          if (!output.empty()) write_annual(scene, study, output);
        }
        return annual_dict(study);
      },
      py::arg("scene"), py::arg("openings"), py::arg("paths") = 0, py::arg("progress") = nullptr,
      py::arg("output") = "",
      "The annual study of openings (as for evaluate) from paths traced with them really cut, no records "
      "kept: the same dict as Contributions.annual_openings. `paths` per sensor, 0 for the scene's "
      "render.paths_per_sensor. With `output`, also writes OUTPUT.npz and OUTPUT.json.");
  m.def(
      "check_openings",
      [](const Scene& scene, const py::object& openings) { region_of_openings(scene, openings_from(openings, scene.site)); },
      py::arg("scene"), py::arg("openings"),
      "Raises ValueError, naming the opening, unless every opening (as for evaluate) lies on the scene's domain as "
      "an annual study needs it (on its elements; in thick walls on the element grid's lines).");
  m.def(
      "annual_from_shards",
      [](const Scene& scene, const py::tuple& parts, int paths_per_sensor, bool cutters, uint64_t dropped_non_finite,
         uint64_t dropped_truncated_conditions, const std::vector<std::string>& warnings, const std::string& output,
         double seconds) {
        const auto start = std::chrono::steady_clock::now();
        if (!scene.climate)
          throw std::invalid_argument("scene '" + scene.source + "': an annual study needs a sky of type \"climate\"");
        std::shared_ptr<const AnnualRecords> annual = prepare_annual(scene);
        AnnualRegionParts whole = annual_parts_of(parts, static_cast<Eigen::Index>(scene.sensors.size()), *annual);
        AnnualStudy study;
        {
          py::gil_scoped_release release;
          if (cutters) {  // as annual_study_with_cutters assembles its one pass
            AnnualCutCoefficients k{std::move(whole.coefficients), std::move(whole.occupied_mean), paths_per_sensor, annual};
            study = annual_cut_study_of(scene, std::move(k));
          } else {  // as annual_study assembles the records' coefficients
            study = annual_study_of(whole.coefficients, annual, whole.occupied_mean);
            study.paths_per_sensor = paths_per_sensor;
            study.dropped = {dropped_non_finite, dropped_truncated_conditions};
          }
          study.warnings = warnings;
          study.seconds = seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          if (!output.empty()) write_annual(scene, study, output);
        }
        return annual_dict(study);
      },
      py::arg("scene"), py::arg("parts"), py::arg("paths_per_sensor"), py::arg("cutters"),
      py::arg("dropped_non_finite") = 0, py::arg("dropped_truncated_conditions") = 0,
      py::arg("warnings") = std::vector<std::string>(), py::arg("output") = "", py::arg("seconds") = 0.0,
      "The annual study of a study sharded by sensors, from its shards' parts stacked in sensor order (as "
      "Contributions.annual_parts or annual_cut_coefficients give them): the dict annual_openings returns. With "
      "`output`, also writes OUTPUT.npz and OUTPUT.json (as `fenestra annual`). `seconds`: what the parts took, added "
      "to the study's own seconds (its year's time).");
  m.def(
      "annual_cut_coefficients",
      [](const Scene& scene, const py::object& openings, std::shared_ptr<Progress> progress, const py::object& sensors,
         int paths) {
        const auto given = openings_from(openings, scene.site);
        const SensorRange range = sensor_range_from(sensors, scene);
        AnnualCutCoefficients k;
        {
          py::gil_scoped_release release;
          k = while_doing("tracing the year of scene '" + scene.source + "' with the openings cut",
                          [&] { return annual_cut_coefficients(scene, given, progress.get(), paths, range); });
        }
        py::tuple parts = annual_parts_tuple(k.coefficients, k.occupied_mean);
        return py::make_tuple(parts[0], parts[1], parts[2], parts[3], k.paths_per_sensor);
      },
      py::arg("scene"), py::arg("openings"), py::arg("progress") = nullptr, py::arg("sensors") = py::none(),
      py::arg("paths") = 0,
      "annual_with_cutters' parts for the sensors (begin, end) (a shard of a study on a cluster): (sources, "
      "direct, mean, stderr, paths per sensor), the coefficients per sensor and source and per sun hour, and the "
      "occupied hours' mean illuminance with its standard error (lux).");
  m.def(
      "constraint_violations",
      [](const Scene& scene, const py::object& openings) {
        std::vector<PanelRectangle> rects;
        for (const OpeningInput& o : openings_from(openings, scene.site)) rects.push_back(to_panel_rectangle(scene.domain, o));
        return solved_constraint_violations(scene, rects);
      },
      py::arg("scene"), py::arg("openings"),
      "What the openings (as for evaluate) break of the scene's solver.constraints: one line each, empty "
      "when they meet every one.");
  m.def(
      "write_image",
      [](const std::string& path, py::array_t<float, py::array::c_style | py::array::forcecast> image) {
        if (image.ndim() != 3) throw std::invalid_argument("image must have shape (height, width, channels)");
        std::vector<float> pixels(image.data(), image.data() + image.size());
        write_image(path, static_cast<int>(image.shape(1)), static_cast<int>(image.shape(0)),
                    static_cast<int>(image.shape(2)), pixels);
      },
      py::arg("path"), py::arg("image"),
      "Writes a linear float image (height, width, channels), top row first, e.g. an environment map: .exr or .hdr "
      "(formats that keep the values; others are refused).");
  m.def(
      "solve",
      [](const Scene& scene, std::shared_ptr<Contributions> contributions, std::shared_ptr<Progress> progress) {
        std::string text;
        {
          py::gil_scoped_release release;
          text = while_doing("solving scene '" + scene.source + "'", [&] {
            const SolveResult r = contributions ? solve_openings(scene, *contributions, progress.get())
                                                : solve_openings(scene, progress.get());
            return solve_result_json(scene, r).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
          });
        }
        return text;
      },
      py::arg("scene"), py::arg("contributions") = nullptr, py::arg("progress") = nullptr,
      "The opening solver; returns the result as JSON text (docs/solver.md).");
  m.def(
      "sky_map",
      [](const Scene& scene) {
        const SkyImage image = sky_image(*scene.sky, scene.daylight.get());
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
        check_value_image_path(path);                 // a format that keeps cd/m^2
        write_sky_image(path, sky_image(*scene.sky, scene.daylight.get()));
      },
      py::arg("scene"), py::arg("path"), "Writes the scene's sky map (.exr or .hdr).");
  m.def(
      "check_image_path", [](const std::string& path) { encode_image(path, 1, 1, 3, {0.0f, 0.0f, 0.0f}); },
      py::arg("path"), "Raises ValueError unless an image can be written to path in the format its extension names.");
  m.def(
      "write_sky_outputs",
      [](const Scene& scene, const std::string& path, py::array_t<float, py::array::c_style | py::array::forcecast> map,
         const std::string& summary_text, const std::string& json_path) {
        if (map.ndim() != 3 || map.shape(2) != 3) throw std::invalid_argument("map must have shape (height, width, 3)");
        const nlohmann::json summary = parse_json_text(summary_text, "the sky summary for", json_path);
        const std::vector<float> flat(map.data(), map.data() + map.size());
        std::string bytes;
        {
          py::gil_scoped_release release;
          bytes = encode_image(path, static_cast<int>(map.shape(1)), static_cast<int>(map.shape(0)), 3, flat);
          // The map and the summary appear together or not at all, as `fenestra sky` writes them.
          std::vector<OutputFile> files = {
              {path, [&](std::ostream& o) { o.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); }}};
          if (!json_path.empty())
            files.push_back({json_path, [&](std::ostream& o) {
                               o << summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
                             }});
          write_files_atomically(files, scene.input_files);
        }
        return sky_report(summary);
      },
      py::arg("scene"), py::arg("path"), py::arg("map"), py::arg("summary"), py::arg("json_path") = "",
      "Writes a sky map (sky_map's array) and, with json_path, its summary (sky_summary's JSON text) as `fenestra "
      "sky` writes them, together or not at all; returns the lines it prints about the sky.");
  m.def(
      "sky_warnings",
      [](const Scene& scene) {
        py::list out;
        for (const std::string& w : sky_warnings(scene.daylight.get())) out.append(text_of(w));
        return out;
      },
      py::arg("scene"),
      "What the sky's weather file says against itself or the scene (a place far from its station), one "
      "sentence each.");
  m.def(
      "dark_sky_warning", [](const Scene& scene) { return text_of(dark_sky_warning(*scene.sky, scene.daylight.get())); }, py::arg("scene"),
      "A sentence when the scene's daylight sky gives no light at all (the sun never up), else \"\".");
  m.def(
      "goal_error",
      [](const Eigen::VectorXd& goals, const Eigen::VectorXd& values, std::optional<Eigen::VectorXd> weights) {
        if (values.size() != goals.size() || (weights && weights->size() != goals.size()))
          throw std::invalid_argument("goal_error: goals, values (and weights) must have one entry per sensor");
        // NaN is a sensor without a goal (a scene file's null), as is a negative goal; anything else
        // that is not a finite number would make the measure NaN or silently 0.
        // Past 1e12 lux (as goals in a scene file) the squares overflow and the measure reads 0 or inf.
        const double most = limits::kMaxIlluminance;
        for (Eigen::Index i = 0; i < goals.size(); ++i)
          if (!std::isnan(goals[i]) && !(std::abs(goals[i]) <= most))
            throw std::invalid_argument("goal_error: goals[" + std::to_string(i) + "] is " + number_text(goals[i]) +
                                        ": a goal is a number of lux up to 1e12, or NaN (or negative) for a sensor "
                                        "without one");
        for (Eigen::Index i = 0; i < values.size(); ++i)
          if (!(std::abs(values[i]) <= most))
            throw std::invalid_argument("goal_error: values[" + std::to_string(i) + "] is " + number_text(values[i]) +
                                        ": every value must be a finite number of lux, at most 1e12 in size");
        SolverGoals g;
        g.target = goals;
        g.weight = weights ? *weights : Eigen::VectorXd::Ones(goals.size());
        for (Eigen::Index i = 0; i < goals.size(); ++i) {
          if (!(g.weight[i] >= 0.0 && g.weight[i] <= limits::kMaxWeight))
            throw std::invalid_argument("goal_error: weights[" + std::to_string(i) + "] is " + number_text(g.weight[i]) +
                                        ": a weight is a number from 0 to 1e6, as sensors.weights");
          if (std::isnan(goals[i]) || goals[i] < 0.0) g.weight[i] = 0.0;  // no goal
        }
        if (!(g.weight.array() > 0.0).any())
          throw std::invalid_argument("goal_error: no sensor has a goal (every goal is NaN or negative, or its weight 0): "
                                      "there is nothing to measure");
        const GoalError e = goal_error(g, values);
        py::dict d;
        d["relative_rms"] = e.relative_rms;
        d["max_relative"] = e.max_relative;
        d["worst_sensor"] = e.worst_sensor;
        return d;
      },
      py::arg("goals"), py::arg("values"), py::arg("weights") = py::none(),
      "The solver's error measure of values against goals (lux; NaN or negative: no goal): relative RMS "
      "sqrt(sum w (v - g)^2 / sum w g^2), the largest relative error and its sensor. Raises ValueError for "
      "a goal or value that is not finite or beyond 1e12 lux (NaN goals aside), a weight outside [0, 1e6], or no "
      "sensor with a goal.");
  m.def(
      "check_open_masks",
      [](const py::object& masks, py::ssize_t elements, bool batch) {
        return open_masks(masks, elements, batch, batch ? "masks" : "open mask");
      },
      py::arg("masks"), py::arg("elements"), py::arg("batch") = false,
      "An open mask (shape (elements,)), or with batch=True masks (sets, elements), as a uint8 array of 0 and 1; "
      "ValueError naming the first entry that is not a bool, or an integer or float equal to 0 or 1.");
  m.def("rays_traced", &rays_traced, "Rays traced by parallel computations since the module was loaded.");
  m.def("read_openings", [](const std::string& path) -> py::object {
    // Corners as the file gives them (site coordinates too): read into a frame near them, then back.
    SiteFrame frame;
    const auto openings = read_openings_in_own_frame(path, &frame);
    const bool by_parameter = std::any_of(openings.begin(), openings.end(), [](const OpeningInput& o) { return o.parameter.has_value(); });
    if (by_parameter) {  // the file's openings as dicts, checked
      py::list list;
      for (const OpeningInput& o : openings) {
        py::dict d;
        if (o.parameter) {
          d["panel"] = o.parameter->panel;
          py::dict r;
          r["u0"] = o.parameter->u0, r["u1"] = o.parameter->u1, r["v0"] = o.parameter->v0, r["v1"] = o.parameter->v1;
          d["parameter_rectangle"] = r;
        } else {
          py::list corners;
          for (const Vec3& local : o.corners) {
            const Vec3d c = frame.to_site(local);
            corners.append(py::make_tuple(c.x(), c.y(), c.z()));
          }
          d["corners"] = corners;
        }
        list.append(d);
      }
      return std::move(list);
    }
    py::array_t<double> a({static_cast<py::ssize_t>(openings.size()), py::ssize_t(4), py::ssize_t(3)});
    auto w = a.mutable_unchecked<3>();
    for (size_t i = 0; i < openings.size(); ++i)
      for (int c = 0; c < 4; ++c)
        for (int d = 0; d < 3; ++d) w(i, c, d) = frame.to_site(openings[i].corners[c])[d];
    return std::move(a);
  }, py::arg("path"), "The openings of an openings file: an (n, 4, 3) array of corners, or, when the file gives "
                      "any by \"parameter_rectangle\", a list of opening dicts; evaluate() takes either.");
}
