// The pieces of the _spdfit extension module, one function per area of the library.
#pragma once

#include <pybind11/pybind11.h>

namespace spdfit::python {

void bind_estimators(pybind11::module_& m);
void bind_io(pybind11::module_& m);
void bind_linear_system(pybind11::module_& m);
void bind_linkage(pybind11::module_& m);
void bind_hexapod(pybind11::module_& m);
void bind_experiment(pybind11::module_& m);

}  // namespace spdfit::python
