// `solve` as one library workflow: classifying and solving A x = b (linear_system.hpp) from files or
// values, with its option table, from which the command line, Python and MATLAB take their options.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "spdfit/io.hpp"
#include "spdfit/linear_system.hpp"
#include "spdfit/options.hpp"
#include "spdfit/outcome.hpp"
#include "spdfit/output_request.hpp"

namespace spdfit {

/// Everything `solve` needs.
struct SolveRequest {
  MatrixInput a;  ///< A (m x n)
  MatrixInput b;  ///< b (m x p; a single row of m values is one column)
  LinearSystemOptions options;
  io::ReadOptions read;  ///< how the files are read
  OutputRequest output;  ///< the command line's: JSON or the report, and where
};

/// The options of a SolveRequest: a, b (positional), threshold (the rank cut-off), rcond_warning,
/// and the command line's json and output.
const std::vector<OptionSpec<SolveRequest>>& solve_option_table();

/// What `solve` found: the result and every warning (the readers', then the solve's).
struct SolveRun {
  LinearSystemResult result;
  std::vector<Warning> warnings;
  /// The solve's numerical failure (thrown by front ends: the command line exits 1), or nothing.
  std::optional<Problem> failure() const;
};

/// Reads A and b (files or values: io::DataError naming a file, InputError naming A or b
/// otherwise), checks their sizes (b's rows are A's; a row of m values is a column; at most
/// options.max_unknowns columns of A) and solves (solve()). Cost: solve()'s.
SolveRun run_solve(const SolveRequest& request);

}  // namespace spdfit
