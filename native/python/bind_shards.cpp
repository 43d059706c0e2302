// fenestra._core: what a study sharded by sensors (fenestra.distributed) passes between processes:
// a shard's transport entries, T assembled from every shard's, and the whole study's contributions
// assembled from the shards' rows.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "format/atomic_file.h"
#include "format/json_input.h"
#include "format/output_pair.h"
#include "io/results.h"
#include "scene/scene.h"
#include "daylight/sky_figures.h"
#include "trace/contributions.h"
#include "trace/contributions_origin.h"
#include "trace/transport_matrix.h"

namespace py = pybind11;
using namespace fenestra;

namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

template <typename T>
py::array_t<T> array_of(const std::vector<T>& v) {
  return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

// A (rows x cols) array as a column-major Eigen matrix, named in the error when its shape is not.
Eigen::MatrixXd matrix_of(const DoubleArray& a, py::ssize_t rows, py::ssize_t cols, const char* name) {
  if (a.ndim() != 2 || a.shape(0) != rows || a.shape(1) != cols)
    throw std::invalid_argument(std::string(name) + " must have shape (" + std::to_string(rows) + ", " +
                                std::to_string(cols) + ")");
  Eigen::MatrixXd m(rows, cols);
  auto r = a.unchecked<2>();
  for (py::ssize_t i = 0; i < rows; ++i)
    for (py::ssize_t j = 0; j < cols; ++j) m(i, j) = r(i, j);
  return m;
}

Eigen::VectorXd vector_of(const DoubleArray& a, py::ssize_t size, const char* name) {
  if (a.ndim() != 1 || a.shape(0) != size)
    throw std::invalid_argument(std::string(name) + " must have shape (" + std::to_string(size) + ",)");
  return Eigen::Map<const Eigen::VectorXd>(a.data(), size);
}

}  // namespace

void bind_shards(py::module_& m) {
  m.def(
      "transport_entries",
      [](const Contributions& c) {
        TransportEntries t;
        {
          py::gil_scoped_release release;
          t = transport_entries(c.records);
        }
        return py::make_tuple(array_of(t.from), array_of(t.to), array_of(t.value), t.sensors);
      },
      py::arg("contributions"),
      "A shard's part of T, entry by entry in the order T adds them: (from, to, value, sensors).");
  m.def(
      "transport_matrix_from_entries",
      [](const std::vector<py::tuple>& shards, size_t elements, int paths_per_sensor) {
        std::vector<TransportEntries> entries(shards.size());
        for (size_t i = 0; i < shards.size(); ++i) {
          if (shards[i].size() != 4)
            throw std::invalid_argument("shard " + std::to_string(i) + ": expected (from, to, value, sensors)");
          entries[i].from = shards[i][0].cast<std::vector<int32_t>>();
          entries[i].to = shards[i][1].cast<std::vector<int32_t>>();
          entries[i].value = shards[i][2].cast<std::vector<float>>();
          entries[i].sensors = shards[i][3].cast<size_t>();
        }
        if (paths_per_sensor <= 0) throw std::invalid_argument("paths_per_sensor must be positive");
        std::vector<const TransportEntries*> in;
        for (const TransportEntries& e : entries) in.push_back(&e);
        Eigen::MatrixXd T;
        {
          py::gil_scoped_release release;
          T = transport_matrix_from_entries(in, elements, paths_per_sensor, 0, nullptr);
        }
        return T;
      },
      py::arg("shards"), py::arg("elements"), py::arg("paths_per_sensor"),
      "T (elements x elements) from the transport entries of every shard, in sensor order: bit for bit the "
      "single-process T.");
  m.def(
      "contributions_from_arrays",
      [](const Scene& scene, int paths_per_sensor, const DoubleArray& E, const DoubleArray& E_stderr,
         const DoubleArray& A, const DoubleArray& T, const DoubleArray& closed, const DoubleArray& closed_stderr,
         const DoubleArray& all_open, const DoubleArray& all_open_stderr, double seconds, uint64_t events,
         uint64_t dropped_non_finite, uint64_t dropped_truncated_conditions) {
        const py::ssize_t ns = static_cast<py::ssize_t>(scene.sensors.size());
        const py::ssize_t no = static_cast<py::ssize_t>(scene.domain.element_count());
        auto c = std::make_shared<Contributions>();
        c->paths_per_sensor = paths_per_sensor;
        c->E = matrix_of(E, ns, no, "E");
        c->E_stderr = matrix_of(E_stderr, ns, no, "E_stderr");
        c->A = matrix_of(A, ns, no, "A");
        if (T.size() > 0) c->T = matrix_of(T, no, no, "T");  // empty: records traced without T
        c->closed = {vector_of(closed, ns, "closed"), vector_of(closed_stderr, ns, "closed_stderr")};
        c->all_open = {vector_of(all_open, ns, "all_open"), vector_of(all_open_stderr, ns, "all_open_stderr")};
        c->records.resize(static_cast<size_t>(ns));  // none kept here: the shards hold them
        c->seconds = seconds;
        c->events = events;
        c->dropped = {dropped_non_finite, dropped_truncated_conditions};
        c->origin = contributions_origin(scene);
        return c;
      },
      py::arg("scene"), py::arg("paths_per_sensor"), py::arg("E"), py::arg("E_stderr"), py::arg("A"), py::arg("T"),
      py::arg("closed"), py::arg("closed_stderr"), py::arg("all_open"), py::arg("all_open_stderr"),
      py::arg("seconds") = 0.0, py::arg("events") = 0, py::arg("dropped_non_finite") = 0,
      py::arg("dropped_truncated_conditions") = 0,
      "Contributions of the scene from their arrays, without path records (a study whose records stay in its "
      "shards): save() writes them as a single process would.");
  m.def(
      "keep_records_only",
      [](Contributions& c) {
        const Eigen::Index elements = c.E.cols();
        for (Eigen::MatrixXd* m : {&c.E, &c.E_stderr, &c.A}) {
          Eigen::MatrixXd empty(0, elements);  // keeps the element count evaluations check
          m->swap(empty);
        }
      },
      py::arg("contributions"),
      "Frees a shard's E, E_stderr and A (the client keeps them), keeping the records that evaluations read.");
  m.def(
      "check_output_paths",
      [](const std::vector<std::string>& outputs, const std::vector<std::string>& inputs) {
        check_output_paths(outputs, inputs);
      },
      py::arg("outputs"), py::arg("inputs"),
      "Raises ValueError unless every output can be written whole (docs/outputs.md): a regular file or a new "
      "one, not an input, a symbolic link or a device.");
  m.def(
      "npz_json_pair", [](const std::string& out) { return npz_json_pair(out); }, py::arg("out"),
      "(OUT.npz, OUT.json) for OUT or OUT.npz; ValueError when OUT is a device, FIFO, socket or directory.");
  m.def(
      "write_json_text",
      [](const std::string& path, const std::string& text) {
        write_json(path, parse_json_text(text, "the JSON to write to", path));
      },
      py::arg("path"), py::arg("text"),
      "Writes JSON text as the command line writes its results (indented, whole or not at all).");
  m.def(
      "dropped_warning",
      [](const py::dict& dropped) {
        return dropped_warning({dropped["non_finite"].cast<uint64_t>(), dropped["truncated_conditions"].cast<uint64_t>()});
      },
      py::arg("dropped"),
      "The command line's warning for what the tracer dropped (Contributions.dropped, a result's \"dropped\"), or "
      "\"\" when nothing was.");
  m.def(
      "write_evaluation",
      [](const Scene& scene, const DoubleArray& value, const DoubleArray& stderr_, size_t openings,
         const std::string& path) {
        const py::ssize_t ns = static_cast<py::ssize_t>(scene.sensors.size());
        const SensorValues v{vector_of(value, ns, "value"), vector_of(stderr_, ns, "stderr")};
        write_json(path, evaluation_json(v, openings, scene.render.paths_per_sensor,
                                         unobstructed_horizontal_illuminance(*scene.sky, scene.suns, scene.daylight.get())));
      },
      py::arg("scene"), py::arg("value"), py::arg("stderr"), py::arg("openings"), py::arg("path"),
      "Writes an evaluation's JSON as `fenestra evaluate` does.");
}
