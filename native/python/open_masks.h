#pragma once
// Open masks given from Python (Contributions.evaluate and annual, the distributed contributions'
// evaluate and evaluate_batch): one check, so that a value that is neither closed nor open is
// refused everywhere rather than read as one of them.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

// `masks` as a C-ordered uint8 array of 0 and 1: bools, or integers or floats holding only 0 and 1
// exactly, of shape (elements,) when !batch or (sets, elements) when batch. Anything else is
// std::invalid_argument (ValueError) naming `what`, and for a bad value its first entry and value.
pybind11::array_t<uint8_t> open_masks(pybind11::handle masks, pybind11::ssize_t elements, bool batch,
                                      const std::string& what);
