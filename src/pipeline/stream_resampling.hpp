// Internal: streaming for a method known in advance, and the streaming (Poisson) bootstrap's
// factors, read in the one pass of stream_factor.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "spdfit/fit_options.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/method.hpp"
#include "spdfit/row_reader.hpp"
#include "spdfit/stream.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::detail {

/// What the readers of A and B found besides the rows: their warnings (A's, then B's) and their
/// column names.
struct PairInfo {
  std::vector<Warning> warnings;
  std::vector<std::string> a_names, b_names;
  /// A and B from one file: the columns of each (FitResult::a_columns).
  std::string a_columns, b_columns;
};

/// The readers of A and B: of the whole files, or of the same rows [first_row, ...) of each, one
/// process's part of files split among processes (then m >= n is not checked on the part).
/// With an empty b_path, A and B are the two column selections of read.columns in a_path's file,
/// read once by `a` (whose rows hold A's columns, then B's; `b` is empty).
struct PairReaders {
  PairReaders(const std::string& a_path, const std::string& b_path, const io::ReadOptions& read);
  PairReaders(io::RowReader a_part, io::RowReader b_part, std::uint64_t first_row);
  /// One process's part of a single file holding A's and B's columns.
  PairReaders(io::RowReader part, std::uint64_t first_row);
  io::RowReader a;
  std::optional<io::RowReader> b;
  bool whole = true;
  std::uint64_t first_row = 0;
  /// Called with A's and B's column counts at the first block (both files opened and read), to
  /// refuse data that will not fit before the whole pass: the noise model's sizes (fit_files).
  std::function<void(Eigen::Index, Eigen::Index)> check_columns;
  /// Factor [1 A B] (TriangularFactor with an intercept): for FitOptions::offsets Estimate, and
  /// Rest, whose tare is subtracted from the factor after the pass (tared_factor, offsets.hpp).
  bool intercept = false;
};

/// stream_factor for data that `method` (when given) will fit: B with a column count the method
/// does not fit (check_method_fits) is refused at the first block, not after the whole pass.
/// `info`, when given, receives the readers' warnings and column names.
TriangularFactor stream_factor_for(const std::optional<Method>& method, const std::string& a_path,
                                   const std::string& b_path, const StreamOptions& options, PairInfo* info);
TriangularFactor stream_factor_for(const std::optional<Method>& method, PairReaders readers,
                                   const StreamOptions& options, PairInfo* info);

/// The factor of all the rows and of each replicate's resample.
struct ResampledFactors {
  TriangularFactor total{1};
  std::vector<TriangularFactor> replicates;
  std::uint64_t groups = 0;  ///< groups of kBootstrapGroupRows rows (the last may be shorter)
  PairInfo info;             ///< the readers' warnings and column names
};

/// Reads A and B as stream_factor does and cuts the rows into consecutive groups of
/// kBootstrapGroupRows (bootstrap.hpp), whatever the block size; each group's factor is merged
/// into `total` and, counted poisson_count(seed, r, group) times, into replicate r's factor, on
/// options.threads threads. Throws as stream_factor_for does.
ResampledFactors stream_resampled_factors(Method method, const std::string& a_path, const std::string& b_path,
                                          const StreamOptions& options, int replicates, std::uint64_t seed);
/// The same for the rows of `readers`; a part (readers.whole false) starts at a multiple of
/// kBootstrapGroupRows, its groups numbered from first_row / kBootstrapGroupRows, so that the
/// parts' factors merged in order are those of the whole files.
ResampledFactors stream_resampled_factors(Method method, PairReaders readers, const StreamOptions& options,
                                          int replicates, std::uint64_t seed);

/// The estimate from a streamed factor, as fit_files gives it: m >= n (m >= n + d for a
/// non-square tls) checked, naming A's file; the readers' warnings and column names attached.
FitResult fit_streamed(Method method, const FitOptions& options, const TriangularFactor& factor, const PairInfo& info,
                       const std::string& a_path);
/// The same with the streaming bootstrap's replicates refitted (FitResult::bootstrap).
FitResult fit_streamed_bootstrap(Method method, const FitOptions& options, const ResampledFactors& factors,
                                 const std::string& a_path);

}  // namespace spdfit::detail
