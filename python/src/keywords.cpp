#include "keywords.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>

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
    case OptionType::RealList:
      return "float or sequence of float";
    case OptionType::Vector:
      return "array_like";
    case OptionType::Noise:
      return "NoiseModel";
  }
  return "object";
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

template <typename Request>
Request request_from(const std::vector<OptionSpec<Request>>& table, const Entry& entry, const py::dict& kwargs,
                     Request request, std::vector<std::string_view>& given) {
  const std::vector<Keyword> accepted = keywords(entry);
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    const Keyword* keyword = nullptr;
    for (const Keyword& k : accepted) {
      if (k.python == name) keyword = &k;
    }
    if (keyword == nullptr) {
      throw py::type_error(std::string(entry.name) + "() got an unexpected keyword argument '" + name + "'");
    }
    if (value.is_none() && keyword->nullable) continue;
    const OptionValue checked = keyword_value(*keyword, value);
    set_option(request, *find_option(table, keyword->name), checked);
    // A flag set to False is not given (keep_diag=False is every repair's default).
    if (keyword->type == OptionType::Flag && !std::get<bool>(checked)) continue;
    given.push_back(keyword->name);
  }
  for (std::string_view implied : entry.implied) {
    set_option(request, *find_option(table, implied), OptionValue{true});
    given.push_back(implied);
  }
  return request;
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
              if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::shared_ptr<const NoiseModel>>) {
                return py::none();  // a noise model has no default but None
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
