// One request for a covariance or correlation repair (the `nearest` command, Python's
// nearest_spd and nearest_correlation, MATLAB's spdfit.nearest), with the table of its options.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "spdfit/nearest_correlation.hpp"
#include "spdfit/nearest_low_rank.hpp"
#include "spdfit/nearest_spd.hpp"
#include "spdfit/io.hpp"
#include "spdfit/nearest_structured.hpp"
#include "spdfit/options.hpp"
#include "spdfit/output_request.hpp"
#include "spdfit/render.hpp"

namespace spdfit {

/// What a repair needs besides the matrix: which repair, and its options.
struct NearestRequest {
  /// The nearest correlation matrix (unit diagonal; nearest_correlation).
  bool corr = false;
  /// Keep the input's diagonal (nearest_keep_diagonal); with corr the diagonal is the unit one.
  bool keep_diag = false;
  /// statsmodels' cov_nearest route: to a correlation, repaired, scaled back (nearest_via_correlation).
  bool via_corr = false;
  /// The floor: absolute, relative to the largest eigenvalue, or NAG's alpha (a unit diagonal's
  /// floor); none given: the relative EigenvalueFloor::kRepairDefault (EigenvalueFloor::chosen).
  std::optional<double> min_eig, min_eig_rel, alpha;
  /// The Newton methods' diagonal weights (n numbers; NearestCorrelationOptions::weights; the
  /// rank repair's too) given as values, or as a file that the command's workflow (run_nearest)
  /// reads into values first.
  MatrixInput weights;
  /// Nothing given: each method's default (NearestCorrelationOptions' for the Newton and
  /// augmented Lagrangian methods, NearestLowRankOptions' for `rank` and `factors`).
  std::optional<int> max_iterations;
  std::optional<double> tolerance;
  /// Entries kept exactly (NearestStructure::fixed): an n x n mask, or k (i, j) pairs as a k x 2
  /// matrix counted from `fixed_index_base`; values, or a file run_nearest reads (a labelled mask
  /// is aligned to X's names). Not given: none.
  MatrixInput fixed;
  /// 1 for the command line's and MATLAB's pairs, 0 for Python's arrays (set by the front end, not
  /// an option); pairs read from a file count from 1 (run_nearest).
  int fixed_index_base = 1;
  /// Elementwise weights H (NearestStructure::h_weights), as values or a file (as `fixed`). Not given: none.
  MatrixInput h_weights;
  /// The rank at most K of the nearest correlation matrix (nearest_correlation_rank); 0: no limit.
  int rank = 0;
  /// The number of factors K of a factor-structured correlation matrix (nearest_correlation_factors); 0: none.
  int factors = 0;
  /// With `factors`: F only, X not formed (no n x n matrix besides C).
  bool factors_only = false;
  /// Variances (diagonal entries) below it are raised to it before the repair, with a warning.
  std::optional<double> min_diag;

  /// Whether the repair fixes a diagonal (corr, keep_diag or via_corr): Qi and Sun's Newton method.
  bool newton() const { return corr || keep_diag || via_corr; }
  /// Whether it keeps entries or weights them elementwise (fixed, h_weights).
  bool structured() const { return fixed.given() || h_weights.given(); }
  /// The floor the options give (EigenvalueFloor::chosen).
  EigenvalueFloor floor() const;
  /// The Newton methods' options. InputError for weights that are not one row or one column
  /// (std::invalid_argument for weights still in a file: run_nearest reads them).
  NearestCorrelationOptions correlation_options() const;
  /// The rank and factor repairs' options.
  NearestLowRankOptions low_rank_options() const;
  /// What the repair does with the diagonal: Unit with `corr`, Kept with `keep_diag`, else Free.
  DiagonalRule diagonal_rule() const;
};

/// The options of a NearestRequest, in the order help lists them: corr, keep_diag, via_corr,
/// min_eig, min_eig_rel, alpha, weights, fixed, h_weights, rank, factors, factors_only, min_diag,
/// max_iterations, tolerance.
const std::vector<OptionSpec<NearestRequest>>& nearest_option_table();

/// Checks the options a user gave (library names) against the table's rules (weights, max_iterations
/// and tolerance need a Newton repair, alpha a unit diagonal, the floors exclude each other).
/// Throws OptionError; its list of what an option needs leaves out the options in `unavailable`
/// (those a front-end function cannot take).
void check_nearest_request(const std::vector<std::string_view>& given,
                           const std::vector<std::string_view>& unavailable = {});

/// The repair the request names: nearest_correlation, nearest_keep_diagonal,
/// nearest_via_correlation or nearest_spd, with fixed entries or elementwise weights
/// (nearest_structured), a rank (nearest_correlation_rank) or factors (nearest_correlation_factors);
/// `min_diag` raises low variances first (raise_variances). Throws std::invalid_argument on bad
/// input (the data's: a mask or weights of the wrong size, a rank above n, infeasible fixed
/// entries), as they do, and std::invalid_argument for a matrix option still in a file
/// (run_nearest reads them).
NearestResult nearest(const Eigen::Ref<const Eigen::MatrixXd>& C, const NearestRequest& request);

/// `spdfit nearest` as one workflow: the matrix to repair (a file, with its variables' names, or
/// values), the repair's options, and how the result is printed.
struct NearestCommand {
  MatrixInput matrix;   ///< X (n x n)
  NearestRequest repair;
  io::ReadOptions read;  ///< how the files (X, the weights) are read
  OutputRequest output;  ///< the command line's: JSON or a labelled table, and where
};

/// The options of a NearestCommand: x (positional), the repair's (nearest_option_table), and the
/// command line's json, header and output.
const std::vector<OptionSpec<NearestCommand>>& nearest_command_table();

/// What `spdfit nearest` found: the repair, the names of its variables (from X's file: its header
/// row or index column), the floor it applied, and every warning (the reader's, the names', the
/// repair's).
struct NearestRun {
  NearestResult result;
  std::vector<std::string> names;
  NearestRequest repair;  ///< the options it ran with
  std::vector<Warning> warnings;
};

/// Reads X (a file with its labels: io::read_labelled_table; or values) and the files of the
/// weights, the kept entries and the elementwise weights (a labelled mask or H aligned to X's
/// names), checks that X is square (a DataError naming the file, and a first row that looks like a
/// header of numbers) and each matrix option's size and entries (a DataError naming its file), and
/// repairs it (nearest); the repair's refusals (NaN, a bad diagonal, infeasible kept entries) are
/// io::DataError naming X's file, InputError otherwise. Cost: the repair's. The command is taken by
/// value: a caller that moves it in (std::move) lends its matrix to the repair without a copy.
NearestRun run_nearest(NearestCommand command);

/// The run as `spdfit nearest --json` prints it: the repair's JSON with the variables' names and
/// the options it ran with (corr, keep_diag, via_corr, min_eig_rel, alpha).
std::string to_json(const NearestRun& run, JsonStyle style = JsonStyle::Contract);

}  // namespace spdfit
