// One request from the user's options to the fit: the method, the estimators' options, and how
// data files are read, with the table of its options that every front end registers from.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "spdfit/fit_options.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/io.hpp"
#include "spdfit/method.hpp"
#include "spdfit/options.hpp"
#include "spdfit/output_request.hpp"
#include "spdfit/stream.hpp"

namespace spdfit {

/// A noise model's sources as a front end without NoiseModel objects gives them: rows at rest and
/// covariances as files (the command line) or matrices (MATLAB), standard deviations as numbers
/// (the options rest_a and rest_b, noise_std_a and noise_std_b, noise_cov_a and noise_cov_b; the
/// table allows one pair). FitRequest::resolved_options reads them into FitOptions::noise.
struct NoiseInputs {
  MatrixInput rest_a, rest_b;       ///< rows recorded at rest (NoiseModel::from_rest_files, from_rest)
  std::vector<double> std_a, std_b; ///< standard deviations, one or one per column (from_std)
  MatrixInput cov_a, cov_b;         ///< the covariance matrices (from_cov)

  /// Whether no source is given.
  bool empty() const {
    return !rest_a.given() && !rest_b.given() && std_a.empty() && std_b.empty() && !cov_a.given() && !cov_b.given();
  }
};

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
  /// A and B from one file: the columns of each ("acc1:acc6", "2:7", "1,3,5", "1,3:5,F1": header
  /// names and 1-based positions, inclusive ranges, lists; io::ColumnSelection). Both or neither.
  std::string a_cols, b_cols;
  /// One log: the rows of the data files fitted (`rows`) and the rest segment taken from the same
  /// files (`rest_rows`: a noise model, as rest_a and rest_b give one), each a row selection
  /// ("601:", "1:5000,7001:", "3,8:12": 1-based inclusive ranges and lists of the files' data rows;
  /// a_cols and b_cols apply to both). Without `rows`, the rows not in `rest_rows` are fitted. In
  /// memory only (not with `stream`). Empty: every row, no rest segment.
  std::string rows, rest_rows;
  /// The column of the same file (with a_cols and b_cols) holding each row's time: `rows` and
  /// `rest_rows` are then ranges of its values ("12.5:60", ":0.995"), not row numbers. Empty: none.
  std::string time_col;
  /// Told the fraction of A's file read while streaming (StreamOptions::progress); the bootstrap's
  /// progress is options.progress.
  ProgressCallback read_progress;
  /// The noise model in files and numbers, for front ends that give it so (the command line);
  /// others set options.noise. Not together with options.noise.
  NoiseInputs noise_inputs;

  /// `options` with the noise model of noise_inputs (none given: `options` as they are): the rest
  /// files streamed block_rows at a time with `read`, the covariance files read with `read`.
  /// Throws OptionError naming the option for numbers the model refuses (a negative standard
  /// deviation, ...) or for noise_inputs given together with options.noise; io::DataError naming
  /// the file for a file that cannot be read, a covariance that is not square, symmetric or
  /// positive semidefinite, or rest files with too few rows or different row counts. The sizes
  /// are checked against the data by the fit (NoiseModel::resolved). Cost: reading the files.
  FitOptions resolved_options() const;
  /// resolved_options() for data with n columns in A and d in B, the model's sizes checked
  /// (NoiseModel::resolved): a covariance file of another size is an io::DataError naming it.
  FitOptions resolved_options(Eigen::Index n, Eigen::Index d) const;

  /// The options of the stream: block_rows, options.threads, read and read_progress.
  StreamOptions stream_options() const;

  /// True when every option is in its range (the table's, as a front end checks a value given);
  /// otherwise `error` names the option and says why.
  bool is_valid(std::string* error = nullptr) const;
};

/// The options of a FitRequest, in the order help lists them: rank_tolerance, noise_ratio,
/// noise (a NoiseModel: Python), rest_a, rest_b, noise_std_a, noise_std_b, noise_cov_a,
/// noise_cov_b (its sources in files and numbers: the command line), max_iterations, min_eig, bootstrap, confidence, seed, threads, reported_diagnostics, stream,
/// block_rows. The method is not among them (each front end takes it as an argument of its own).
/// The command line registers its options from this table, Python its keyword arguments and
/// MATLAB its name-value pairs; adding an option here (and its field) is all a front end needs.
const std::vector<OptionSpec<FitRequest>>& fit_option_table();

/// The library names of the options about the noise: noise_ratio, noise, and the noise model's
/// sources (rest_a, rest_b, noise_std_a, noise_std_b, noise_cov_a, noise_cov_b). A front end whose
/// function fits every method (compare, hexapod identify) takes these of the table.
const std::vector<std::string_view>& noise_option_names();

/// Checks the options a user gave (`given`: library names) for the request's method: that each
/// applies to it (an option such as noise_ratio given with a method that does not take it) and
/// the table's rules among them (confidence needs bootstrap, ...). Throws OptionError, whose
/// message names options by their library names in backticks (spell_options).
void check_fit_request(const FitRequest& request, const std::vector<std::string_view>& given);

/// The fit of A and B in files (fit_files) as the request says: streamed when request.stream,
/// with the noise model of resolved_options(). A size of a noise model's covariance file that does
/// not fit the data is an io::DataError naming that file. With request.a_cols and b_cols, A and B
/// are those columns of the one file `a_path`, and `b_path` must be empty (OptionError otherwise).
FitResult fit_files(const std::string& a_path, const std::string& b_path, const FitRequest& request);

/// `spdfit fit` as a request: the data's files, the fit's request, the arrays named in .mat and .npz
/// files, and how the result is printed (the command line's; Python's fit_files and MATLAB take
/// the fit's options from fit_option_table directly).
struct FitCommand {
  MatrixInput a;  ///< A's file ("-": standard input)
  MatrixInput b;  ///< B's file; empty with fit.a_cols and fit.b_cols (both from a's file)
  FitRequest fit;
  std::string var_a, var_b;  ///< the variables of A's and B's .mat or .npz files
  OutputRequest output;
};

/// The options of a FitCommand: a, b (positional), the fit's (fit_option_table), var_a and var_b,
/// and the command line's json, report, header and output.
const std::vector<OptionSpec<FitCommand>>& fit_command_table();

/// The paths of A and B that command names: each file with its variable (FILE:NAME, the library's
/// one way of naming an array in a file), B's empty when A and B are columns of one file. Throws
/// OptionError (Code::Argument) for a variable named in standard input or in a file without named
/// arrays (text, .npy), for a variable named twice (FILE:NAME and `var_a`), for A and B both
/// standard input, for B missing without `a_cols` and `b_cols`, and for two variables of one file.
std::pair<std::string, std::string> fit_command_paths(const FitCommand& command);

/// request.read for the data: with request.a_cols and b_cols, their column selections added
/// (options a_cols and b_cols), after checking their syntax (io::ColumnSelectionError) and that
/// they come together and with one file, `b_path` empty (OptionError). Front ends that read the
/// data themselves (compare, hexapod identify) read it so, with read_pair.
io::ReadOptions data_read_options(const FitRequest& request, const std::string& b_path);

}  // namespace spdfit
