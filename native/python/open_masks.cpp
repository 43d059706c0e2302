// Open masks from Python: only 0 (closed) and 1 (open) are read (see open_masks.h).
#include "open_masks.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace py = pybind11;

namespace {

const char* const kAccepted = "an open mask holds bools, or integers or floats that are exactly 0 (closed) or 1 (open)";

// A value as Python shows it, at most about 80 characters.
std::string shown(const py::handle& value) {
  std::string s = py::str(py::repr(value));
  return s.size() > 80 ? s.substr(0, 77) + "..." : s;
}

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// "entry 7" or "mask 2, entry 7" for the flat index i.
std::string entry_text(const py::array& a, py::ssize_t i, bool batch) {
  if (!batch) return "entry " + std::to_string(i);
  const py::ssize_t columns = a.shape(1);
  return "mask " + std::to_string(i / columns) + ", entry " + std::to_string(i % columns);
}

// One entry as given: a bool, or an integer or float (Python's or NumPy's) equal to 0 or 1.
bool zero_or_one(const py::handle& x) {
  const py::array a = py::array::ensure(x);
  if (!a || a.ndim() != 0) return false;
  const char kind = a.dtype().kind();
  if (kind == 'b') return true;
  if (kind != 'i' && kind != 'u' && kind != 'f') return false;
  const double d = py::float_(a.attr("item")());
  return d == 0.0 || d == 1.0;
}

}  // namespace

py::array_t<uint8_t> open_masks(py::handle masks, py::ssize_t elements, bool batch, const std::string& what) {
  py::array a = py::array::ensure(masks);
  if (!a)
    throw std::invalid_argument(what + ": expected an array (or list) of bools or of 0 and 1, got " +
                                shown(masks).substr(0, 80) + ": " + kAccepted);
  const int ndim = batch ? 2 : 1;
  if (a.ndim() != ndim || a.shape(ndim - 1) != elements) {
    if (!batch && a.ndim() == 1)
      throw std::invalid_argument(what + " has " + std::to_string(a.shape(0)) + " entries; the contributions have " +
                                  std::to_string(elements) + " elements");
    throw std::invalid_argument(what + " must have shape " + (batch ? "(sets, " : "(") + std::to_string(elements) +
                                (batch ? ")" : ",)") + ", one entry per element, got " + shape_text(a));
  }
  const char kind = a.dtype().kind();
  if (kind == 'b') return py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(a);
  if (kind != 'i' && kind != 'u' && kind != 'f') {
    // Complex numbers, objects (None, mixed lists), text, times: each entry as given, so that the
    // one named is the culprit (a list [1, 0, 1j] becomes an array of complex numbers throughout).
    py::array given = py::module_::import("numpy").attr("array")(masks, py::arg("dtype") = "object");
    if (given.size() != a.size()) given = a.attr("astype")("object");
    py::array_t<uint8_t> out(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()));
    for (py::ssize_t i = 0; i < given.size(); ++i) {
      const py::object x = given.attr("item")(i);
      if (!zero_or_one(x))
        throw std::invalid_argument(what + " " + entry_text(a, i, batch) + " is " + shown(x) + ": " + kAccepted);
      out.mutable_data()[i] = PyObject_IsTrue(x.ptr()) == 1;
    }
    return out;  // objects that are all bools, 0 and 1
  }
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!values) throw py::error_already_set();
  py::array_t<uint8_t> out(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()));
  const double* v = values.data();
  uint8_t* o = out.mutable_data();
  for (py::ssize_t i = 0; i < values.size(); ++i) {
    if (v[i] != 0.0 && v[i] != 1.0)  // NaN, inf, 0.5, 2, -1: refused
      throw std::invalid_argument(what + " " + entry_text(a, i, batch) + " is " + shown(a.attr("item")(i)) + ": " +
                                  kAccepted);
    o[i] = v[i] == 1.0;
  }
  return out;
}
