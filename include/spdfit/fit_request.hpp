// One request from the user's options to the fit: the method, the estimators' options, and how
// data files are read, with the table of its options that every front end registers from.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "spdfit/fit_options.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/io.hpp"
#include "spdfit/method.hpp"
#include "spdfit/options.hpp"
#include "spdfit/stream.hpp"

namespace spdfit {

/// Everything a fit needs besides the data: the method, the estimators' options (with the one
/// thread count, FitOptions::threads, which the stream and the bootstrap share), and for data in
/// files whether they are streamed and how they are read.
struct FitRequest {
  Method method = Method::Auto;
  FitOptions options;
  /// Read the files a block of rows at a time (fit_files): memory
  /// O(threads * block_rows * (n + d) + (n + d)^2) whatever the number of rows.
  bool stream = false;
  /// Rows per block when streaming (StreamOptions::block_rows).
  Eigen::Index block_rows = StreamOptions{}.block_rows;
  /// How the data files are read (both paths).
  io::ReadOptions read;
  /// Told the fraction of A's file read while streaming (StreamOptions::progress); the bootstrap's
  /// progress is options.progress.
  ProgressCallback read_progress;

  /// The options of the stream: block_rows, options.threads, read and read_progress.
  StreamOptions stream_options() const;

  /// True when every option is in its range (the table's, as a front end checks a value given);
  /// otherwise `error` names the option and says why.
  bool is_valid(std::string* error = nullptr) const;
};

/// The options of a FitRequest, in the order help lists them: rank_tolerance, noise_ratio,
/// max_iterations, min_eig, bootstrap, confidence, seed, threads, reported_diagnostics, stream,
/// block_rows. The method is not among them (each front end takes it as an argument of its own).
/// The command line registers its options from this table, Python its keyword arguments and
/// MATLAB its name-value pairs; adding an option here (and its field) is all a front end needs.
const std::vector<OptionSpec<FitRequest>>& fit_option_table();

/// Checks the options a user gave (`given`: library names) for the request's method: that each
/// applies to it (an option such as noise_ratio given with a method that does not take it) and
/// the table's rules among them (confidence needs bootstrap, ...). Throws OptionError, whose
/// message names options by their library names in backticks (spell_options).
void check_fit_request(const FitRequest& request, const std::vector<std::string_view>& given);

/// The fit of A and B in files (fit_files) as the request says: streamed when request.stream.
FitResult fit_files(const std::string& a_path, const std::string& b_path, const FitRequest& request);

}  // namespace spdfit
