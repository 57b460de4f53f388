#include "spdfit/fit_files.hpp"

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "factor/reduce.hpp"
#include "io/containers.hpp"
#include "io/kept_text.hpp"
#include "io/parse.hpp"
#include "pipeline/log_rows.hpp"
#include "pipeline/sentinels.hpp"
#include "pipeline/offsets.hpp"
#include "pipeline/units.hpp"
#include "pipeline/pair_checks.hpp"
#include "spdfit/options.hpp"
#include "pipeline/stream_resampling.hpp"
#include "spdfit/fit.hpp"
#include "uncertainty/bootstrap.hpp"

namespace spdfit {

namespace {
// The readers' warnings first, then the fit's; the files' column names as X's row and column names.
void attach_read_info(FitResult& result, const detail::PairInfo& info) {
  result.warnings.insert(result.warnings.begin(), info.warnings.begin(), info.warnings.end());
  result.row_names = info.a_names;
  result.column_names = info.b_names;
  result.a_columns = info.a_columns;
  result.b_columns = info.b_columns;
}

// "313 KiB", "38 MiB", "6 GiB": rounded up, for messages.
std::string bytes_text(std::uint64_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
  int unit = 0;
  while (unit < 4 && bytes >= (std::uint64_t{1} << 10)) {
    bytes = (bytes + 1023) >> 10;
    ++unit;
  }
  return std::to_string(bytes) + " " + units[unit];
}

std::string shape(const Eigen::MatrixXd& M) { return std::to_string(M.rows()) + "x" + std::to_string(M.cols()); }
}  // namespace

namespace detail {

FitResult fit_streamed(Method method, const FitOptions& options, const TriangularFactor& factor, const PairInfo& info,
                       const std::string& a_path) {
  check_enough_rows_for(method, a_path, factor.rows(), factor.n(), factor.d());
  if (const std::optional<Units> units = units_of(options, factor.n(), factor.d())) {
    return fit_streamed(method, options_in_units(options, *units), factor_in_units(factor, *units), info, a_path);
  }
  if (options.offsets == Offsets::Rest) {
    const Tare tare = rest_tare(options, factor.n(), factor.d());
    FitResult result = fit_streamed(method, options_after_tare(options), tared_factor(factor, tare), info, a_path);
    result.offsets = offsets_of(result, factor, options, &tare);
    return result;
  }
  FitResult result = fit(detail::reduce_for(factor, options, method), method);
  result.offsets = offsets_of(result, factor, options, nullptr);
  attach_read_info(result, info);
  return result;
}

FitResult fit_streamed_bootstrap(Method method, const FitOptions& options, const ResampledFactors& factors,
                                 const std::string& a_path) {
  check_enough_rows_for(method, a_path, factors.total.rows(), factors.total.n(), factors.total.d());
  if (const std::optional<Units> units = units_of(options, factors.total.n(), factors.total.d())) {
    ResampledFactors scaled{factor_in_units(factors.total, *units), {}, factors.groups, factors.info};
    scaled.replicates.reserve(factors.replicates.size());
    for (const TriangularFactor& replicate : factors.replicates) scaled.replicates.push_back(factor_in_units(replicate, *units));
    return fit_streamed_bootstrap(method, options_in_units(options, *units), scaled, a_path);
  }
  if (options.offsets == Offsets::Rest) {
    const Tare tare = rest_tare(options, factors.total.n(), factors.total.d());
    ResampledFactors tared{tared_factor(factors.total, tare), {}, factors.groups, factors.info};
    tared.replicates.reserve(factors.replicates.size());
    for (const TriangularFactor& replicate : factors.replicates) tared.replicates.push_back(tared_factor(replicate, tare));
    FitResult result = fit_streamed_bootstrap(method, options_after_tare(options), tared, a_path);
    result.offsets = offsets_of(result, factors.total, options, &tare);
    return result;
  }
  const Reduction data = reduce(factors.total, options);
  FitResult result = fit(data, method);
  result.offsets = offsets_of(result, factors.total, options, nullptr);
  attach_read_info(result, factors.info);
  if (!result.ok()) return result;
  const std::vector<detail::Replicate> replicates =
      detail::run_replicates(factors.replicates.size(), options,
                             [&](std::size_t r) { return detail::refit(factors.replicates[r], options, result); });
  detail::attach_bootstrap(result, replicates, options, data);
  result.bootstrap->scheme = "poisson_groups";
  result.bootstrap->group_rows = detail::kBootstrapGroupRows;
  result.bootstrap->groups = static_cast<Eigen::Index>(factors.groups);
  return result;
}

}  // namespace detail

namespace {
// read_pair, with standard input's text taken from `standard_input` when it is given (kept from
// the streaming pass, which read it already).
DataPair read_pair_from(const std::string& a_path, const std::string& b_path, const io::ReadOptions& options,
                        const std::string* standard_input) {
  const auto read = [&](const std::string& path) {
    if (path == "-" && standard_input != nullptr) return io::parse_table(*standard_input, io::detail::kStdinName, options);
    return io::read_table(path, options);
  };
  DataPair data;
  if (detail::checked_pair_read(b_path, options).columns.size() == 2) {
    // One file: read once, its selected columns A's then B's.
    io::Table table = read(a_path);
    const auto n = static_cast<Eigen::Index>(table.selected_columns.at(0).size());
    data.A = table.values.leftCols(n);
    data.B = table.values.rightCols(table.values.cols() - n);
    data.warnings = std::move(table.warnings);
    detail::SelectionSplit split = detail::split_selection(a_path, table.column_names, table.selected_columns);
    data.a_names = std::move(split.a_names);
    data.b_names = std::move(split.b_names);
    data.a_columns = std::move(split.a_columns);
    data.b_columns = std::move(split.b_columns);
    if (data.A.rows() < data.A.cols()) {
      throw detail::fewer_samples_than_columns(a_path, static_cast<std::uint64_t>(data.A.rows()),
                                               static_cast<std::uint64_t>(data.A.cols()));
    }
    return data;
  }
  io::Table a = read(a_path);
  data.A = std::move(a.values);
  data.warnings = std::move(a.warnings);
  data.a_names = std::move(a.column_names);
  if (data.A.rows() < data.A.cols()) {
    throw detail::fewer_samples_than_columns(a_path, static_cast<std::uint64_t>(data.A.rows()),
                                             static_cast<std::uint64_t>(data.A.cols()));
  }
  io::Table b = read(b_path);
  data.B = std::move(b.values);
  data.warnings.insert(data.warnings.end(), b.warnings.begin(), b.warnings.end());
  data.b_names = std::move(b.column_names);
  if (data.A.rows() != data.B.rows()) {
    throw detail::unequal_rows(b_path, "B is " + shape(data.B) + " but A (" + a_path + ") is " + shape(data.A));
  }
  return data;
}
}  // namespace

DataPair read_pair(const std::string& a_path, const std::string& b_path, const io::ReadOptions& options) {
  return read_pair_from(a_path, b_path, options, nullptr);
}

namespace detail {

FitResult fit_pair_in_memory(DataPair data, const std::string& a_path, const std::string& b_path, Method method,
                             const FitOptions& options, const RowNumbers& numbers) {
  check_method_fits(method, b_path.empty() ? a_path : b_path, data.A.cols(), data.B.cols());
  if (options.noise) static_cast<void>(options.noise->resolved(data.A.cols(), data.B.cols()));
  check_enough_rows_for(method, a_path, data.A.rows(), data.A.cols(), data.B.cols());
  FitResult result = fit_numbered(data.A, data.B, method, options, numbers);
  attach_read_info(result, {std::move(data.warnings), std::move(data.a_names), std::move(data.b_names),
                            std::move(data.a_columns), std::move(data.b_columns)});
  return result;
}

}  // namespace detail

FitResult fit_files(const std::string& a_path, const std::string& b_path, Method method, const FitOptions& options,
                    const std::optional<StreamOptions>& stream, const io::ReadOptions& read) {
  std::string error;
  if (!options.is_valid(&error)) throw OptionError(error);
  // A noise model the method cannot use is refused before any file is read.
  if (auto refusal = detail::noise_refusal(options.noise, method)) {
    detail::throw_noise_refusal(*refusal, method, options.noise);
  }
  std::optional<StreamOptions> streamed = stream;
  if (streamed) streamed->read = read;  // one way of reading, whichever path
  // Standard input is read once: with a streaming bootstrap its text is kept while it is streamed
  // (up to the in-memory budget), so that too few groups for the Poisson scheme can still be
  // resampled in memory from it, as a file's rows are.
  std::shared_ptr<io::detail::KeptText> kept_input;
  if (streamed && options.bootstrap > 0 && (a_path == "-") != (b_path == "-")) {
    kept_input = std::make_shared<io::detail::KeptText>();
    kept_input->at_most = static_cast<std::size_t>(streamed->bootstrap_memory_bytes);
  }
  auto readers = [&] {
    const auto reader = [&](const std::string& path) {
      return path == "-" && kept_input ? io::detail::standard_input_reader(read, kept_input) : io::RowReader(path, read);
    };
    detail::PairReaders pair = !kept_input     ? detail::PairReaders(a_path, b_path, read)
                               : b_path.empty() ? detail::PairReaders(reader(a_path), 0)  // A and B in one file
                                                : detail::PairReaders(reader(a_path), reader(b_path), 0);
    pair.whole = true;
    pair.intercept = options.offsets != Offsets::None;  // estimate: centred; rest: tared after the pass
    // The noise model's sizes against the data's columns, at the first block, not after the pass.
    if (options.noise) {
      pair.check_columns = [noise = &*options.noise](Eigen::Index n, Eigen::Index d) {
        static_cast<void>(noise->resolved(n, d));
      };
    }
    return pair;
  };
  auto in_memory = [&] {
    return detail::fit_pair_in_memory(read_pair_from(a_path, b_path, read, kept_input ? &kept_input->text : nullptr),
                                      a_path, b_path, method, options);
  };
  if (streamed && options.robust != RobustLoss::None) {
    throw OptionError("`robust` reweighs every row at each of its iterations, which one pass over the files cannot: "
                      "fit the rows in memory (without `stream`; in Python spdfit.fit on the arrays read)",
                      Code::OptionConflict, "robust");
  }
  if (streamed && options.bootstrap > 0) {
    if (streamed->block_rows < 1) throw std::invalid_argument("block_rows must be at least 1");
    // The streaming bootstrap: Poisson counts on fixed row groups, all in the one pass.
    detail::ResampledFactors factors =
        detail::stream_resampled_factors(method, readers(), *streamed, options.bootstrap, options.seed);
    if (factors.groups >= static_cast<std::uint64_t>(detail::kBootstrapMinGroups)) {
      if (std::optional<Warning> w = detail::streamed_sentinel_warning(factors.total)) {
        factors.info.warnings.push_back(std::move(*w));
      }
      return detail::fit_streamed_bootstrap(method, options, factors, a_path);
    }
    // Too few groups for the Poisson scheme: the rows resampled one at a time in memory, when
    // they are small enough to hold and can be read again.
    const auto rows = static_cast<std::uint64_t>(factors.total.rows());
    const auto values = static_cast<std::uint64_t>(factors.total.n() + factors.total.d());
    const std::uint64_t bytes = rows * values * sizeof(double);
    const std::string megabytes = bytes_text(bytes);
    const std::string budget = bytes_text(streamed->bootstrap_memory_bytes);
    if (a_path == "-" || b_path == "-") {
      // Kept only while it fit the budget (and never when both are standard input).
      if (!kept_input || kept_input->overflowed) {
        throw io::DataError(io::detail::kStdinName, 0, 0,
                            detail::too_few_groups(rows, "standard input is read once, and its text was more than "
                                                         "the " + budget +
                                                         " kept to resample its rows in memory after the streaming "
                                                         "pass; save it to a file, or fit it in memory without "
                                                         "streaming"));
      }
    }
    if (bytes > streamed->bootstrap_memory_bytes) {
      throw io::DataError(a_path, 0, 0,
                          detail::too_few_groups(rows, "resampling its rows in memory instead would take " + megabytes +
                                                           ", more than the " + budget +
                                                           " allowed for it; give more rows"));
    }
    FitResult result = in_memory();
    const std::string which = kept_input ? "its rows (" + megabytes + ", within the " + budget +
                                               " allowed; standard input's text kept from the streaming pass)"
                                         : "its rows (" + megabytes + ", within the " + budget + " allowed)";
    result.warnings.push_back(Warning(Code::BootstrapNotice, detail::too_few_groups(
        rows, which + " were resampled one at a time in memory instead (the in-memory bootstrap)")));
    return result;
  }
  if (streamed) {
    if (streamed->block_rows < 1) throw std::invalid_argument("block_rows must be at least 1");
    detail::PairInfo info;
    const TriangularFactor factor = detail::stream_factor_for(method, readers(), *streamed, &info);
    if (std::optional<Warning> w = detail::streamed_sentinel_warning(factor)) info.warnings.push_back(std::move(*w));
    return detail::fit_streamed(method, options, factor, info, a_path);
  }
  return in_memory();
}

}  // namespace spdfit
