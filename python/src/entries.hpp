// Which of the library's options (fit_option_table, nearest_option_table, physical_option_table) each Python
// function takes as keyword arguments: the one list that the module binds, the docstrings document and the
// type stubs declare (python/stubgen.cpp writes them from it at build time).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "spdfit/experiment/experiment_request.hpp"
#include "spdfit/method.hpp"
#include "spdfit/options.hpp"

namespace spdfit::python {

/// A keyword argument of a Python function, from its table entry.
struct Keyword {
  std::string_view name;     ///< the library's name
  std::string_view python;   ///< the keyword
  OptionType type = OptionType::Real;
  std::string help;          ///< the table's help, options spelled for Python
  std::string_view default_text;
  /// The default the signature shows: None for a nullable option (None stands for the library's
  /// default), else the library's default value.
  std::optional<OptionValue> default_value;
  bool nullable = true;  ///< OptionSpec::nullable: None accepted
};

/// A Python function whose options come from a table: the table, the options it implies (given
/// without being passed: fit_files streams, nearest_correlation repairs to a correlation), and
/// those it cannot take (an in-memory fit does not stream, fit_all does not bootstrap).
struct Entry {
  std::string_view name;   ///< the Python function ("fit", "fit_files", "Factor.fit", ...)
  /// "fit", "nearest", "physical" (hexapod::physical_option_table), "payload"
  /// (payload::identify_option_table), "payload_design" or "regress" (physical::regress_option_table)
  std::string_view table;
  std::vector<std::string_view> implied;
  std::vector<std::string_view> unavailable;
};

/// Every Python function whose keywords come from a table.
const std::vector<Entry>& entries();

/// The entry named `name`; std::invalid_argument when there is none.
const Entry& entry(std::string_view name);

/// The experiment whose table an entry takes ("experiment:paper-2x2"), or nothing.
std::optional<experiment::ExperimentKind> experiment_kind(const Entry& entry);

/// The keywords `entry` takes, in the table's order: every option with a Python spelling that is
/// not unavailable, not implied, and whose `needs` (if any) can be met there. With a `method`
/// (a fit entry only), those that apply to it (the per-method functions: spde, psd_least_squares).
std::vector<Keyword> keywords(const Entry& entry, std::optional<Method> method = std::nullopt);

/// The keywords of the entry named `name`, or for "fit:METHOD" of fit's entry those that apply to
/// METHOD. std::invalid_argument for a name that is neither.
std::vector<Keyword> keywords(std::string_view name);

/// The stub's annotation of a keyword: "Optional[float]" for a nullable real option, "int" for
/// a count, ...
std::string annotation(const Keyword& keyword);

}  // namespace spdfit::python
