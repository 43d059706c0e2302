// fenestra._core: the cost model (docs/cost.md): estimate_cost, check_cost, the memory limit.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>

#include "scene/scene.h"
#include "study/climate_reach.h"
#include "study/cost_model.h"
#include "util/byte_size.h"
#include "util/cost_context.h"
#include "util/memory_limit.h"

namespace py = pybind11;
using namespace fenestra;

namespace {

MemoryLimit limit_of(uint64_t max_memory) {
  if (max_memory > 0) return {max_memory, "allowed by max_memory"};
  return memory_limit();
}

// Sets the memory limit and the command for the scene loads made inside a `with` block, on this thread.
class PyCostScope {
 public:
  PyCostScope(uint64_t max_memory, const std::string& command) : context_{max_memory, cost_command(command)} {}
  void enter() { scope_ = std::make_unique<CostScope>(context_); }
  void exit() { scope_.reset(); }

 private:
  CostContext context_;
  std::unique_ptr<CostScope> scope_;
};

}  // namespace

void bind_cost(py::module_& m) {
  m.def("climate_reach", [](const Scene& scene) { return climate_reach(scene); }, py::arg("scene"),
        "Per sensor, the opening elements its rows of the climate goals' hourly model are estimated to hold "
        "(those it sees with the domain open, times a margin; 0 for sensors no climate goal looks at), "
        "before any path is traced (docs/cost.md).");
  m.def("parse_memory_size", [](const std::string& text) { return parse_byte_size(text, "max_memory"); },
        py::arg("text"), "Bytes from '8G', '512M', '1.5GB', '2GiB' or a plain number (decimal units; Ki, Mi, Gi binary).");
  m.def(
      "available_memory",
      []() {
        const MemoryLimit l = detect_available_memory();
        py::dict d;
        d["bytes"] = l.bytes;
        d["source"] = l.source;
        return d;
      },
      "What this process may still allocate: {'bytes', 'source'} (MemAvailable, ulimit -v / -d, cgroup).");
  m.def(
      "estimate_cost",
      [](const Scene& scene, const std::string& command, uint64_t max_memory, double paths) {
        const CostCommand c = cost_command(command);
        const CostEstimate e = estimate_cost(scene, c, -1.0, paths);
        const MemoryLimit limit = limit_of(max_memory);
        py::dict memory, phases, seconds, limits;
        for (const MemoryItem& item : e.memory) {
          memory[py::str(item.key)] = item.bytes;
          phases[py::str(item.key)] = item.phase;
        }
        for (const TimeItem& t : e.time) {
          seconds[py::str(t.key)] = t.seconds;
          limits[py::str(t.key)] = t.limit_seconds > 0.0 ? py::object(py::float_(t.limit_seconds)) : py::object(py::none());
        }
        py::dict d;
        d["command"] = cost_command_name(c);
        d["sensors"] = e.sensors;
        d["elements"] = e.elements;
        d["triangles"] = e.triangles;
        d["paths_per_sensor"] = e.paths_per_sensor;
        d["bytes_per_path"] = e.bytes_per_path;
        d["memory"] = memory;
        d["memory_phase"] = phases;
        d["kept_bytes"] = e.kept_bytes();
        d["total_bytes"] = e.peak_bytes();
        d["available_bytes"] = limit.bytes;
        d["available_source"] = limit.source;
        d["seconds"] = seconds;
        d["seconds_limit"] = limits;
        try {
          check_cost(scene, c, limit, paths);
          d["fits"] = true;
          d["problem"] = py::none();
        } catch (const CostError& error) {
          d["fits"] = false;
          d["problem"] = std::string(error.what());
        }
        return d;
      },
      py::arg("scene"), py::arg("command") = "solve", py::arg("max_memory") = 0, py::arg("paths") = -1.0,
      "The cost model's estimate for running `command` on the scene (docs/cost.md); `paths` per sensor "
      "replaces the scene's when >= 0.");
  m.def(
      "check_cost",
      [](const Scene& scene, const std::string& command, uint64_t max_memory, double paths) {
        check_cost(scene, cost_command(command), limit_of(max_memory), paths);
      },
      py::arg("scene"), py::arg("command") = "solve", py::arg("max_memory") = 0, py::arg("paths") = -1.0,
      "Raises ValueError when `command` on the scene would not fit in memory or exceed a stage's time limit.");
  py::class_<PyCostScope>(m, "CostScope", "with CostScope(max_memory, command): scene loads on this thread use them.")
      .def(py::init<uint64_t, const std::string&>(), py::arg("max_memory") = 0, py::arg("command") = "any")
      .def("__enter__", [](PyCostScope& s) { s.enter(); })
      .def("__exit__", [](PyCostScope& s, py::args) { s.exit(); });
}
