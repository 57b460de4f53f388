// Outcome codes in Python: the table of codes (spdfit/outcome.hpp), from which spdfit._errors
// makes a warning class per warning code, and the one exception translator, which chooses the
// Python exception from an error's code, never from its text.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <stdexcept>
#include <string>

#include "bindings.hpp"
#include "spdfit/io.hpp"
#include "spdfit/outcome.hpp"
#include "spdfit/spelling.hpp"

namespace py = pybind11;

namespace spdfit::python {

namespace {

const char* tier_name(Tier tier) {
  switch (tier) {
    case Tier::Usage: return "usage";
    case Tier::Data: return "data";
    case Tier::Numerical: return "numerical";
    case Tier::Internal: return "internal";
    case Tier::Warning: return "warning";
  }
  return "internal";
}

// Python's exception class for `code`, from the package (spdfit._errors): DataError and
// NumericalError live there; the built-in ones are Python's own.
py::object exception_class(Code code) {
  const std::string name = python_class(code);
  if (name == "TypeError") return py::reinterpret_borrow<py::object>(PyExc_TypeError);
  if (name == "ValueError") return py::reinterpret_borrow<py::object>(PyExc_ValueError);
  if (name == "MemoryError") return py::reinterpret_borrow<py::object>(PyExc_MemoryError);
  if (name == "RuntimeError") return py::reinterpret_borrow<py::object>(PyExc_RuntimeError);
  return py::module_::import("spdfit._errors").attr(name.c_str());
}

}  // namespace

void bind_warning_class(py::module_& m) {
  py::class_<Warning>(m, "Warning", "A library warning: its code's name, its text and the option or file it concerns.")
      .def_property_readonly("code", [](const Warning& w) { return std::string(code_info(w.code).name); })
      .def_readonly("text", &Warning::text)
      .def_readonly("subject", &Warning::subject)
      .def("__str__", [](const Warning& w) { return w.text; })
      .def("__repr__", [](const Warning& w) {
        return "Warning(code='" + std::string(code_info(w.code).name) + "', text=" +
               std::string(py::repr(py::str(w.text))) + ")";
      });
}

void bind_outcome(py::module_& m) {
  m.def(
      "outcome_codes",
      [] {
        py::list out;
        for (const CodeInfo& info : outcome_codes()) {
          out.append(py::make_tuple(std::string(info.name), tier_name(info.tier), python_class(info.code),
                                    matlab_identifier(info.code), std::string(info.meaning)));
        }
        return out;
      },
      "Every outcome code: (name, tier, Python class, MATLAB identifier, meaning).");
  // Registered last among the module's translators, so tried first: pybind11's own exceptions
  // (a Python error already set, py::type_error, ...) pass on to pybind11's translator.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::error_already_set&) {
      throw;
    } catch (const py::builtin_exception&) {
      throw;
    } catch (const std::exception& e) {
      const Code code = code_of(e);
      const std::string message = spell_options(e.what(), Frontend::Python);
      const py::object cls = exception_class(code);
      PyErr_SetString(cls.ptr(), message.c_str());
    }
  });
}

}  // namespace spdfit::python
