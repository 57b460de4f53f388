// Binding a request from a Python call's keyword arguments, by name, through the library's option
// tables (entries.hpp lists which keywords each function takes).
#pragma once

#include <pybind11/pybind11.h>

#include <string_view>
#include <vector>

#include "entries.hpp"
#include "spdfit/fit_request.hpp"
#include "spdfit/hexapod/physical_request.hpp"
#include "spdfit/experiment/experiment_request.hpp"
#include "spdfit/hexapod/simulate_request.hpp"
#include "spdfit/inertia_repair.hpp"
#include "spdfit/method.hpp"
#include "spdfit/nearest_request.hpp"
#include "spdfit/payload/design.hpp"
#include "spdfit/payload/identify.hpp"
#include "spdfit/physical/regress.hpp"

namespace spdfit::python {

/// The value of keyword `keyword` for an option of its type, checked as a Python user expects:
/// a TypeError naming the keyword for a value of the wrong type ("max_iter must be an int, got
/// float"; bool is not an int, an integer is a real number, NumPy scalars count as theirs).
OptionValue keyword_value(const Keyword& keyword, const pybind11::handle& value);

/// The request of a call to Python function `entry` (entries.hpp) with keyword arguments
/// `kwargs`, set by name on `request`: a TypeError for a keyword the function does not take or a
/// value of the wrong type, an OptionError (a ValueError, options spelled for Python) for a value
/// the library refuses; None leaves the default. The entry's implied options are set too.
/// `given` receives the library names of the options set (for check_fit_request and
/// check_nearest_request).
/// The request of a call to Python function `entry` with keyword arguments `kwargs`, through
/// `table` (any command's): see fit_request.
template <typename Request>
Request request_from(const std::vector<OptionSpec<Request>>& table, const Entry& entry, const pybind11::dict& kwargs,
                     Request request, std::vector<std::string_view>& given) {
  const std::vector<Keyword> accepted = keywords(entry);
  for (const auto& [key, value] : kwargs) {
    const std::string name = pybind11::str(key);
    const Keyword* keyword = nullptr;
    for (const Keyword& k : accepted) {
      if (k.python == name) keyword = &k;
    }
    if (keyword == nullptr) {
      throw pybind11::type_error(std::string(entry.name) + "() got an unexpected keyword argument '" + name + "'");
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

FitRequest fit_request(std::string_view entry, const pybind11::dict& kwargs, FitRequest request,
                       std::vector<std::string_view>& given);
NearestRequest nearest_request(std::string_view entry, const pybind11::dict& kwargs,
                               std::vector<std::string_view>& given);
hexapod::PhysicalOptions physical_request(std::string_view entry, const pybind11::dict& kwargs,
                                          std::vector<std::string_view>& given);
payload::IdentifyRequest payload_request(std::string_view entry, const pybind11::dict& kwargs,
                                         std::vector<std::string_view>& given);
payload::DesignRequest design_request(std::string_view entry, const pybind11::dict& kwargs,
                                      std::vector<std::string_view>& given);
physical::RegressRequest regress_request(std::string_view entry, const pybind11::dict& kwargs,
                                         std::vector<std::string_view>& given);
hexapod::SimulateRequest simulate_request(std::string_view entry, const pybind11::dict& kwargs,
                                          std::vector<std::string_view>& given);
InertiaRepairRequest inertia_repair_request(std::string_view entry, const pybind11::dict& kwargs,
                                            std::vector<std::string_view>& given);
/// An experiment's request from `kwargs`, starting from the experiment's defaults.
/// (its kind is the entry's table's, experiment_kind).
experiment::ExperimentRequest experiment_request_from(std::string_view entry, const pybind11::dict& kwargs,
                                                      std::vector<std::string_view>& given);

/// The method a Python call names; an OptionError (a ValueError) listing the methods for a name
/// that is none of them, a TypeError for a value that is not a str.
Method method_from(const pybind11::handle& method);

/// The keywords of every entry and their documentation, for spdfit's Python code: {entry name:
/// [(keyword, type name, help, default text, default value or None)]} with type names "bool", "int", "float", "str",
/// "float or sequence of float", "array_like"; and "fit:METHOD" for fit's keywords that apply to
/// METHOD (the functions of one method, such as spde).
pybind11::dict keyword_table();

}  // namespace spdfit::python
