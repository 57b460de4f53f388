#include "keywords.hpp"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>

#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/noise_model.hpp"

namespace py = pybind11;

namespace spdfit::python {

namespace {

std::string type_name(const py::handle& value) { return py::str(py::type::of(value).attr("__name__")); }

// (Imported at each call, from sys.modules: a static Python object would outlive the interpreter.)
bool is_instance(const py::handle& value, const char* abc) {
  return py::isinstance(value, py::module_::import("numbers").attr(abc));
}

[[noreturn]] void wrong_type(const Keyword& keyword, const char* expected, const py::handle& value) {
  throw py::type_error(std::string(keyword.python) + " must be " + expected + ", got " + type_name(value));
}

const char* type_text(OptionType type) {
  switch (type) {
    case OptionType::Flag:
    case OptionType::Boolean:
      return "bool";
    case OptionType::Integer:
      return "int";
    case OptionType::Real:
      return "float";
    case OptionType::Text:
      return "str";
    case OptionType::Names:
      return "str or list of str";
    case OptionType::Range:
      return "(float, float) or str";
    case OptionType::RealList:
      return "float or sequence of float";
    case OptionType::Vector:
      return "array_like";
    case OptionType::Noise:
      return "NoiseModel";
    case OptionType::Choice:
      return "str";
    case OptionType::File:
      return "str or os.PathLike";
    case OptionType::Matrix:
      return "array_like";
    case OptionType::Columns:
    case OptionType::Rows:
      return "str";
    case OptionType::Geometry:
      return "Geometry, str or os.PathLike";
  }
  return "object";
}

// A str or an os.PathLike (pathlib.Path): a file's name.
bool is_path(const py::handle& value) {
  return py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__");
}
std::string path_text(const py::handle& value) {
  return py::module_::import("os").attr("fspath")(value).cast<std::string>();
}

// A real matrix (a 1-D array is one column).
Eigen::MatrixXd matrix_value(const Keyword& keyword, const py::handle& value) {
  py::array array = py::module_::import("numpy").attr("asarray")(value);
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b') {
    throw py::type_error(std::string(keyword.python) + " must be a matrix of real numbers, got dtype " +
                         std::string(py::str(array.dtype())));
  }
  if (array.ndim() > 2) throw py::value_error(std::string(keyword.python) + " must be a matrix (at most 2-D)");
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  const Eigen::Index rows = array.ndim() == 0 ? 1 : array.shape(0);
  const Eigen::Index cols = array.ndim() == 2 ? array.shape(1) : 1;
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(values.data(), rows,
                                                                                                  cols);
}

std::vector<double> real_vector(const Keyword& keyword, const py::handle& value) {
  py::array array = py::module_::import("numpy").attr("asarray")(value);
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw py::value_error(std::string(keyword.python) + " must be real numbers, got dtype " +
                          std::string(py::str(array.dtype())));
  }
  if (array.ndim() > 2 || (array.ndim() == 2 && array.shape(0) != 1 && array.shape(1) != 1)) {
    throw py::value_error(std::string(keyword.python) + " must be a vector (one row or one column)");
  }
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  return std::vector<double>(values.data(), values.data() + values.size());
}

}  // namespace

OptionValue keyword_value(const Keyword& keyword, const py::handle& value) {
  switch (keyword.type) {
    case OptionType::Flag:
    case OptionType::Boolean:
      if (!py::isinstance<py::bool_>(value) && type_name(value) != "bool_") wrong_type(keyword, "a bool", value);
      return value.cast<bool>();
    case OptionType::Integer:
      if (py::isinstance<py::bool_>(value) || type_name(value) == "bool_" || !is_instance(value, "Integral")) {
        wrong_type(keyword, "an int", value);
      }
      try {
        return py::int_(py::reinterpret_borrow<py::object>(value)).cast<std::int64_t>();
      } catch (const py::cast_error&) {
        throw OptionError("`" + std::string(keyword.name) + "` must be an integer that fits in 64 bits, got " +
                          std::string(py::str(value)));
      }
    case OptionType::Real:
      if (py::isinstance<py::bool_>(value) || type_name(value) == "bool_" || !is_instance(value, "Real")) {
        wrong_type(keyword, "a real number", value);
      }
      return py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
    case OptionType::Text:
      if (!py::isinstance<py::str>(value)) wrong_type(keyword, "a str", value);
      return value.cast<std::string>();
    case OptionType::Names: {
      if (py::isinstance<py::str>(value)) return value.cast<std::string>();
      if (!py::isinstance<py::sequence>(value)) wrong_type(keyword, "a str or a list of str", value);
      std::string names;
      for (const py::handle item : py::reinterpret_borrow<py::sequence>(value)) {
        if (!py::isinstance<py::str>(item)) wrong_type(keyword, "a str or a list of str", value);
        names += (names.empty() ? "" : ",") + item.cast<std::string>();
      }
      return names;
    }
    case OptionType::Range: {
      // (lo, hi), or the command line's text "LO:HI".
      if (py::isinstance<py::str>(value)) return value.cast<std::string>();
      const std::vector<double> ends = real_vector(keyword, value);
      if (ends.size() != 2) wrong_type(keyword, "a pair of numbers (lo, hi) or a str 'LO:HI'", value);
      return range_text(ends[0], ends[1]);
    }
    case OptionType::RealList:
      if (is_instance(value, "Real") && !py::isinstance<py::bool_>(value)) {
        return std::vector<double>{py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>()};
      }
      return real_vector(keyword, value);
    case OptionType::Vector:
      return real_vector(keyword, value);
    case OptionType::Noise:
      if (!py::isinstance<NoiseModel>(value)) wrong_type(keyword, "a spdfit.NoiseModel", value);
      return std::make_shared<const NoiseModel>(value.cast<const NoiseModel&>());
    case OptionType::Choice:
    case OptionType::Columns:
    case OptionType::Rows:
      if (!py::isinstance<py::str>(value)) wrong_type(keyword, "a str", value);
      return value.cast<std::string>();
    case OptionType::File:
      if (!is_path(value)) wrong_type(keyword, "a str or os.PathLike", value);
      return path_text(value);
    case OptionType::Matrix: {
      if (is_path(value)) return path_text(value);
      MatrixInput input;
      input.values = matrix_value(keyword, value);
      return input;
    }
    case OptionType::Geometry: {
      if (is_path(value)) return GeometryInput{path_text(value), nullptr};
      if (!py::isinstance<hexapod::Geometry>(value)) {
        wrong_type(keyword, "a spdfit.hexapod.Geometry, str or os.PathLike", value);
      }
      return GeometryInput{{}, std::make_shared<const hexapod::Geometry>(value.cast<const hexapod::Geometry&>())};
    }
  }
  wrong_type(keyword, "a value", value);
}

FitRequest fit_request(std::string_view entry_name, const py::dict& kwargs, FitRequest request,
                       std::vector<std::string_view>& given) {
  return request_from(fit_option_table(), entry(entry_name), kwargs, std::move(request), given);
}

NearestRequest nearest_request(std::string_view entry_name, const py::dict& kwargs,
                               std::vector<std::string_view>& given) {
  return request_from(nearest_option_table(), entry(entry_name), kwargs, NearestRequest{}, given);
}

hexapod::PhysicalOptions physical_request(std::string_view entry_name, const py::dict& kwargs,
                                          std::vector<std::string_view>& given) {
  return request_from(hexapod::physical_option_table(), entry(entry_name), kwargs, hexapod::PhysicalOptions{},
                      given);
}

payload::IdentifyRequest payload_request(std::string_view entry_name, const py::dict& kwargs,
                                         std::vector<std::string_view>& given) {
  return request_from(payload::identify_option_table(), entry(entry_name), kwargs, payload::IdentifyRequest{}, given);
}

payload::DesignRequest design_request(std::string_view entry_name, const py::dict& kwargs,
                                      std::vector<std::string_view>& given) {
  return request_from(payload::design_option_table(), entry(entry_name), kwargs, payload::DesignRequest{}, given);
}

physical::RegressRequest regress_request(std::string_view entry_name, const py::dict& kwargs,
                                         std::vector<std::string_view>& given) {
  return request_from(physical::regress_option_table(), entry(entry_name), kwargs, physical::RegressRequest{}, given);
}

hexapod::SimulateRequest simulate_request(std::string_view entry_name, const py::dict& kwargs,
                                          std::vector<std::string_view>& given) {
  return request_from(hexapod::simulate_option_table(), entry(entry_name), kwargs, hexapod::SimulateRequest{}, given);
}

InertiaRepairRequest inertia_repair_request(std::string_view entry_name, const py::dict& kwargs,
                                            std::vector<std::string_view>& given) {
  return request_from(inertia_repair_option_table(), entry(entry_name), kwargs, InertiaRepairRequest{}, given);
}

experiment::ExperimentRequest experiment_request_from(std::string_view entry_name, const py::dict& kwargs,
                                                      std::vector<std::string_view>& given) {
  const Entry& e = entry(entry_name);
  const std::optional<experiment::ExperimentKind> kind = experiment_kind(e);
  if (!kind) throw std::invalid_argument("'" + std::string(entry_name) + "' is not an experiment's entry");
  return request_from(experiment::experiment_option_table(*kind), e, kwargs, experiment::experiment_request(*kind),
                      given);
}

Method method_from(const py::handle& method) {
  std::string known;
  for (Method m : kSelectableMethods) known += (known.empty() ? "" : ", ") + std::string(to_string(m));
  if (!py::isinstance<py::str>(method)) {
    throw py::type_error("method must be a str (one of " + known + "), got " + type_name(method));
  }
  const std::string name = method.cast<std::string>();
  if (const auto parsed = parse_method(name)) return *parsed;
  throw OptionError("unknown method '" + name + "' (methods: " + known + ")");
}

py::dict keyword_table() {
  py::dict out;
  const auto add = [&out](const std::string& name, const std::vector<Keyword>& keywords) {
    py::list list;
    for (const Keyword& k : keywords) {
      py::object value = py::none();
      if (k.default_value) {
        value = std::visit(
            [](const auto& v) -> py::object {
              using T = std::decay_t<decltype(v)>;
              if constexpr (std::is_same_v<T, std::shared_ptr<const NoiseModel>> || std::is_same_v<T, MatrixInput> ||
                            std::is_same_v<T, GeometryInput>) {
                return py::none();  // objects, matrices and files have no default but None
              } else {
                return py::cast(v);
              }
            },
            *k.default_value);
      }
      list.append(
          py::make_tuple(std::string(k.python), type_text(k.type), k.help, std::string(k.default_text), value));
    }
    out[py::str(name)] = list;
  };
  for (const Entry& e : entries()) add(std::string(e.name), keywords(e));
  // fit's keywords that apply to each method, for the functions of one method (spde, ...).
  for (Method m : kSelectableMethods) {
    const std::string name = "fit:" + std::string(to_string(m));
    add(name, keywords(name));
  }
  return out;
}

}  // namespace spdfit::python
