#include "pickle.hpp"

#include <nlohmann/json.hpp>

#include "spdfit/version.hpp"

namespace py = pybind11;

namespace spdfit::python {

void refuse_state(const std::string& message) {
  const py::object error = py::module_::import("pickle").attr("UnpicklingError");
  PyErr_SetString(error.ptr(), message.c_str());
  throw py::error_already_set();
}

py::object checked_payload(const py::tuple& state, const char* what) {
  const std::string start = std::string("cannot unpickle ") + what + ": ";
  const std::string reads = "this spdfit (" + std::string(kVersion) + ") reads format " +
                            std::to_string(kPickleFormat) + " only: recompute it, or unpickle it with the "
                            "spdfit that pickled it";
  // A state with no format number first: format 0, the fields' tuples of the releases before.
  if (state.size() != 2 || !py::isinstance<py::int_>(state[0]) || py::isinstance<py::bool_>(state[0])) {
    refuse_state(start + "it was pickled by another version of spdfit (a state of no pickle format); " + reads);
  }
  const auto format = state[0].cast<long long>();
  if (format != kPickleFormat) {
    refuse_state(start + "it was pickled by another version of spdfit (pickle format " + std::to_string(format) +
                 "); " + reads);
  }
  return state[1];
}

void check_state(const py::tuple& state, std::size_t size, const char* what) {
  if (state.size() != size) {
    refuse_state(std::string("cannot unpickle ") + what + ": expected " + std::to_string(size) + " fields, got " +
                 std::to_string(state.size()));
  }
}

namespace {

// Every class of `module` and of its submodules that pickles (has its own __setstate__).
void add_reduce(const py::module_& module, const py::object& new_object) {
  for (const auto item : module.attr("__dict__").cast<py::dict>()) {
    const py::object value = py::reinterpret_borrow<py::object>(item.second);
    if (py::isinstance<py::module_>(value)) {
      const auto name = value.attr("__name__").cast<std::string>();
      const auto parent = module.attr("__name__").cast<std::string>();
      if (name.rfind(parent + ".", 0) == 0) add_reduce(value.cast<py::module_>(), new_object);
      continue;
    }
    if (!PyType_Check(value.ptr()) || !value.attr("__dict__").contains("__setstate__")) continue;
    value.attr("__reduce__") = py::cpp_function(
        [new_object](const py::object& self) {
          return py::make_tuple(new_object, py::make_tuple(py::type::of(self)), self.attr("__getstate__")());
        },
        py::is_method(value), py::name("__reduce__"),
        "(copyreg.__newobj__, (class,), state): pickles and copies under every protocol");
  }
}

// A JSON value as a Python literal.
std::string literal(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null:
      return "None";
    case nlohmann::json::value_t::boolean:
      return value.get<bool>() ? "True" : "False";
    case nlohmann::json::value_t::string:
      return py::repr(py::str(value.get<std::string>())).cast<std::string>();
    case nlohmann::json::value_t::array: {
      std::string out = "[";
      for (std::size_t i = 0; i < value.size(); ++i) out += (i ? ", " : "") + literal(value[i]);
      return out + "]";
    }
    case nlohmann::json::value_t::object: {
      std::string out = "{";
      bool first = true;
      for (const auto& [key, item] : value.items()) {
        out += (first ? "'" : ", '") + key + "': " + literal(item);
        first = false;
      }
      return out + "}";
    }
    default:
      return value.dump();  // a number: the shortest text that reads back, as Python's repr writes floats
  }
}

}  // namespace

void enable_every_protocol(py::module_& module) {
  // copyreg.__newobj__(cls) is cls.__new__(cls), which protocols 2-5 call too (their NEWOBJ);
  // a function of the standard library, every protocol pickles it by name.
  add_reduce(module, py::module_::import("copyreg").attr("__newobj__"));
}

std::string repr_from_json(const char* name, const std::string& json) {
  std::string out = std::string(name) + "(";
  bool first = true;
  const nlohmann::json document = nlohmann::json::parse(json);
  for (const auto& [key, value] : document.items()) {
    out += (first ? "" : ", ") + key + "=" + literal(value);
    first = false;
  }
  return out + ")";
}

}  // namespace spdfit::python
