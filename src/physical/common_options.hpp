// Internal: option-table entries that the physical fits' requests share (regress, payload
// identify and design): the bootstrap's four, the iteration limit and the rank cut-off, each
// declared once for any request type with the fields of that name.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "spdfit/fit_request.hpp"
#include "spdfit/options.hpp"

namespace spdfit::physical::detail {

template <typename Request>
OptionSpec<Request> text_option(std::string_view name, std::string_view cli, std::string_view python,
                                std::string_view value_name, std::string_view help, std::string_view default_text) {
  OptionSpec<Request> spec;
  spec.name = name;
  spec.cli = cli;
  spec.python = python;
  spec.type = OptionType::Text;
  spec.value_name = value_name;
  spec.help = help;
  spec.default_text = default_text;
  return spec;
}

/// An option whose value is one of `choices` (matched without regard to case; the set function
/// receives the table's spelling). The first choice is the default unless `default_text` says.
template <typename Request>
OptionSpec<Request> choice_option(std::string_view name, std::string_view cli, std::string_view python,
                                  std::vector<std::string_view> choices, std::string_view help,
                                  std::string_view default_text) {
  OptionSpec<Request> spec;
  spec.name = name;
  spec.cli = cli;
  spec.python = python;
  spec.type = OptionType::Choice;
  spec.choices = std::move(choices);
  spec.help = help;
  spec.default_text = default_text;
  return spec;
}

/// An option that chooses columns of a table (io::ColumnSelection's syntax).
template <typename Request>
OptionSpec<Request> columns_option(std::string_view name, std::string_view cli, std::string_view python,
                                   std::string_view value_name, std::string_view help) {
  OptionSpec<Request> spec = text_option<Request>(name, cli, python, value_name, help, "");
  spec.type = OptionType::Columns;
  return spec;
}

template <typename Request>
OptionSpec<Request> flag_option(std::string_view name, std::string_view cli, std::string_view python,
                                std::string_view help) {
  OptionSpec<Request> spec;
  spec.name = name;
  spec.cli = cli;
  spec.python = python;
  spec.type = OptionType::Flag;
  spec.help = help;
  spec.nullable = false;
  return spec;
}

/// max_iterations and rank_tolerance, for a Request with `int max_iterations` and
/// `std::optional<double> rank_tolerance`.
template <typename Request>
void add_solver_options(std::vector<OptionSpec<Request>>& table, std::string_view iterations_default) {
  OptionSpec<Request> iterations;
  iterations.name = "max_iterations";
  iterations.cli = "--max-iter";
  iterations.python = "max_iter";
  iterations.type = OptionType::Integer;
  iterations.value_name = "N";
  iterations.help = "Newton steps at most (all barrier stages together)";
  iterations.default_text = iterations_default;
  iterations.range = {1.0, 1e6};
  iterations.set = [](Request& r, const OptionValue& v) { r.max_iterations = int(std::get<std::int64_t>(v)); };
  iterations.get = [](const Request& r) -> std::optional<OptionValue> { return std::int64_t{r.max_iterations}; };
  table.push_back(iterations);

  OptionSpec<Request> rank;
  rank.name = "rank_tolerance";
  rank.cli = "--rank-tol";
  rank.python = "rank_tolerance";
  rank.type = OptionType::Real;
  rank.value_name = "R";
  rank.help = "Relative cut-off of the regressor's numerical rank (its columns scaled to unit norm)";
  rank.default_text = "max(rows, columns) eps";
  rank.range = {0.0, 1.0, false, true};
  rank.set = [](Request& r, const OptionValue& v) { r.rank_tolerance = std::get<double>(v); };
  rank.get = [](const Request& r) -> std::optional<OptionValue> {
    if (!r.rank_tolerance) return std::nullopt;
    return *r.rank_tolerance;
  };
  table.push_back(rank);
}

/// bootstrap, confidence, seed and threads, for a Request with those fields.
template <typename Request>
void add_bootstrap_options(std::vector<OptionSpec<Request>>& table, std::string_view what) {
  OptionSpec<Request> bootstrap;
  bootstrap.name = "bootstrap";
  bootstrap.cli = "--bootstrap";
  bootstrap.python = "bootstrap";
  bootstrap.type = OptionType::Integer;
  bootstrap.value_name = "N";
  bootstrap.help = what;
  bootstrap.default_text = "0";
  bootstrap.range = {0.0, 1e7};
  bootstrap.nullable = false;
  bootstrap.set = [](Request& r, const OptionValue& v) { r.bootstrap = int(std::get<std::int64_t>(v)); };
  bootstrap.get = [](const Request& r) -> std::optional<OptionValue> { return std::int64_t{r.bootstrap}; };
  table.push_back(bootstrap);

  OptionSpec<Request> confidence;
  confidence.name = "confidence";
  confidence.cli = "--confidence";
  confidence.python = "confidence";
  confidence.type = OptionType::Real;
  confidence.value_name = "FRACTION";
  confidence.help = "The bootstrap intervals' level, a fraction";
  confidence.default_text = "0.95";
  confidence.range = {0.0, 1.0, true, true};
  confidence.needs = {"bootstrap"};
  confidence.needs_message = "`confidence` applies to the bootstrap: give `bootstrap` N as well";
  confidence.set = [](Request& r, const OptionValue& v) { r.confidence = std::get<double>(v); };
  confidence.get = [](const Request& r) -> std::optional<OptionValue> { return r.confidence; };
  table.push_back(confidence);

  OptionSpec<Request> seed;
  seed.name = "seed";
  seed.cli = "--seed";
  seed.python = "seed";
  seed.type = OptionType::Integer;
  seed.value_name = "N";
  seed.help = "The bootstrap's seed; the numbers depend on nothing else";
  seed.default_text = "1";
  seed.range = {0.0, double(std::numeric_limits<std::int64_t>::max())};
  seed.needs = {"bootstrap"};
  seed.needs_message = "`seed` applies to the bootstrap: give `bootstrap` N as well";
  seed.set = [](Request& r, const OptionValue& v) { r.seed = std::uint64_t(std::get<std::int64_t>(v)); };
  seed.get = [](const Request& r) -> std::optional<OptionValue> { return static_cast<std::int64_t>(r.seed); };
  table.push_back(seed);

  OptionSpec<Request> threads;
  threads.name = "threads";
  threads.cli = "--threads";
  threads.python = "threads";
  threads.type = OptionType::Integer;
  threads.value_name = "N";
  threads.help = "Threads for the bootstrap (0: one per core); the result does not depend on it";
  threads.default_text = "0";
  threads.range = {0.0, 1024.0};
  threads.nullable = false;
  threads.set = [](Request& r, const OptionValue& v) { r.threads = unsigned(std::get<std::int64_t>(v)); };
  threads.get = [](const Request& r) -> std::optional<OptionValue> { return std::int64_t{r.threads}; };
  table.push_back(threads);
}

/// The fit table's option `name` (its spelling, type, choices, range, default and rules among the
/// fit's own options) for another request: the caller gives what it sets (and may word its help),
/// so that `robust` and `robust_tuning` mean and refuse the same everywhere.
template <typename Request>
OptionSpec<Request> like_fit_option(std::string_view name) {
  const OptionSpec<FitRequest>& fit = *find_option(fit_option_table(), name);
  OptionSpec<Request> spec;
  spec.name = fit.name;
  spec.cli = fit.cli;
  spec.python = fit.python;
  spec.type = fit.type;
  spec.value_name = fit.value_name;
  spec.help = fit.help;
  spec.default_text = fit.default_text;
  spec.nullable = fit.nullable;
  spec.range = fit.range;
  spec.choices = fit.choices;
  spec.needs = fit.needs;
  spec.needs_message = fit.needs_message;
  return spec;
}

}  // namespace spdfit::physical::detail
