// The pieces of the _spdfit extension module, one function per area of the library.
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "spdfit/outcome.hpp"
#include "spdfit/render.hpp"

namespace spdfit::python {

/// The getter of a read-only attribute: a copy of the member, so that an Eigen member becomes a
/// NumPy array the caller owns and may write to (as NumPy's own results are), not pybind11's
/// read-only view into the C++ object (def_readonly).
template <typename Class, typename Member>
auto copied(Member Class::*member) {
  return [member](const Class& object) -> Member { return object.*member; };
}

/// The getters of a result's warnings: their texts (a list of str, as before codes) and their
/// codes' names (`warning_codes`, parallel to them), from which Python chooses a warning's class.
template <typename Class>
auto warning_texts(std::vector<Warning> Class::*member) {
  return [member](const Class& object) { return texts(object.*member); };
}
template <typename Class>
auto warning_codes(std::vector<Warning> Class::*member) {
  return [member](const Class& object) {
    std::vector<std::string> out;
    for (const Warning& w : object.*member) out.emplace_back(code_info(w.code).name);
    return out;
  };
}

/// How a report (spdfit/render.hpp) refers to Python's means: the keyword bootstrap=N and the
/// result's interval and bias attributes.
inline const ReportHints& python_report_hints() {
  static const ReportHints hints{"bootstrap=N, e.g. 1000", "the interval and bias attributes"};
  return hints;
}

void bind_results(pybind11::module_& m);
void bind_noise(pybind11::module_& m);
void bind_estimators(pybind11::module_& m);
void bind_io(pybind11::module_& m);
void bind_linear_system(pybind11::module_& m);
void bind_linkage(pybind11::module_& m);
void bind_hexapod(pybind11::module_& m);
void bind_physical(pybind11::module_& m);
void bind_experiment(pybind11::module_& m);
void bind_factor(pybind11::module_& m);
void bind_blas_core(pybind11::module_& m);
/// The outcome codes and the exception translator that maps an error's code to its Python class:
/// bound last, so that its translator is tried first.
void bind_outcome(pybind11::module_& m);
/// spdfit._spdfit.Warning: the functions that return a list of warnings (readers, simulate) return
/// these (bound first, before any function returns one).
void bind_warning_class(pybind11::module_& m);

}  // namespace spdfit::python
