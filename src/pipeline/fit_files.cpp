#include "spdfit/fit_files.hpp"

#include <cstdint>
#include <stdexcept>
#include <string>

#include "factor/reduce.hpp"
#include "io/containers.hpp"
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
  FitResult result = fit(detail::reduce_for(factor, options, method), method);
  attach_read_info(result, info);
  return result;
}

FitResult fit_streamed_bootstrap(Method method, const FitOptions& options, const ResampledFactors& factors,
                                 const std::string& a_path) {
  check_enough_rows_for(method, a_path, factors.total.rows(), factors.total.n(), factors.total.d());
  const Reduction data = reduce(factors.total, options);
  FitResult result = fit(data, method);
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

DataPair read_pair(const std::string& a_path, const std::string& b_path, const io::ReadOptions& options) {
  DataPair data;
  io::Table a = io::read_table(a_path, options);
  data.A = std::move(a.values);
  data.warnings = std::move(a.warnings);
  data.a_names = std::move(a.column_names);
  if (data.A.rows() < data.A.cols()) {
    throw detail::fewer_samples_than_columns(a_path, static_cast<std::uint64_t>(data.A.rows()),
                                             static_cast<std::uint64_t>(data.A.cols()));
  }
  io::Table b = io::read_table(b_path, options);
  data.B = std::move(b.values);
  data.warnings.insert(data.warnings.end(), b.warnings.begin(), b.warnings.end());
  data.b_names = std::move(b.column_names);
  if (data.A.rows() != data.B.rows()) {
    throw detail::unequal_rows(b_path, "B is " + shape(data.B) + " but A (" + a_path + ") is " + shape(data.A));
  }
  return data;
}

FitResult fit_files(const std::string& a_path, const std::string& b_path, Method method, const FitOptions& options,
                    const std::optional<StreamOptions>& stream, const io::ReadOptions& read) {
  std::string error;
  if (!options.is_valid(&error)) throw OptionError(error);
  // A noise model the method cannot use is refused before any file is read.
  if (auto refusal = detail::noise_refusal(options.noise, method)) throw OptionError(*refusal);
  std::optional<StreamOptions> streamed = stream;
  if (streamed) streamed->read = read;  // one way of reading, whichever path
  auto readers = [&] {
    detail::PairReaders pair(a_path, b_path, read);
    // The noise model's sizes against the data's columns, at the first block, not after the pass.
    if (options.noise) {
      pair.check_columns = [noise = &*options.noise](Eigen::Index n, Eigen::Index d) {
        static_cast<void>(noise->resolved(n, d));
      };
    }
    return pair;
  };
  auto in_memory = [&] {
    DataPair data = read_pair(a_path, b_path, read);
    detail::check_method_fits(method, b_path, data.A.cols(), data.B.cols());
    if (options.noise) static_cast<void>(options.noise->resolved(data.A.cols(), data.B.cols()));
    detail::check_enough_rows_for(method, a_path, data.A.rows(), data.A.cols(), data.B.cols());
    FitResult result = fit(data.A, data.B, method, options);
    attach_read_info(result, {std::move(data.warnings), std::move(data.a_names), std::move(data.b_names)});
    return result;
  };
  if (streamed && options.bootstrap > 0) {
    if (streamed->block_rows < 1) throw std::invalid_argument("block_rows must be at least 1");
    // The streaming bootstrap: Poisson counts on fixed row groups, all in the one pass.
    detail::ResampledFactors factors =
        detail::stream_resampled_factors(method, readers(), *streamed, options.bootstrap, options.seed);
    if (factors.groups >= static_cast<std::uint64_t>(detail::kBootstrapMinGroups)) {
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
      throw io::DataError(io::detail::kStdinName, 0, 0,
                          detail::too_few_groups(rows, "standard input is read once, so its rows cannot be "
                                                       "resampled in memory after the streaming pass; save it to a "
                                                       "file, or fit it in memory without streaming"));
    }
    if (bytes > streamed->bootstrap_memory_bytes) {
      throw io::DataError(a_path, 0, 0,
                          detail::too_few_groups(rows, "resampling its rows in memory instead would take " + megabytes +
                                                           ", more than the " + budget +
                                                           " allowed for it; give more rows"));
    }
    FitResult result = in_memory();
    result.warnings.push_back(detail::too_few_groups(rows, "its rows (" + megabytes + ", within the " + budget +
                                                            " allowed) were resampled one at a time in memory instead "
                                                            "(the in-memory bootstrap)"));
    return result;
  }
  if (streamed) {
    if (streamed->block_rows < 1) throw std::invalid_argument("block_rows must be at least 1");
    detail::PairInfo info;
    const TriangularFactor factor = detail::stream_factor_for(method, readers(), *streamed, &info);
    return detail::fit_streamed(method, options, factor, info, a_path);
  }
  return in_memory();
}

}  // namespace spdfit
