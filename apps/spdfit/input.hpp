// Loading the command line's data files, with errors that name the files, read as the global
// options say and with the readers' warnings printed.
#pragma once

#include <string>

#include <Eigen/Core>

#include "cli.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/fit_request.hpp"

namespace spdfit::cli {

/// One matrix (see io::read_table), read as the global options say; the reader's warnings (a
/// first column of row labels dropped) are printed.
Eigen::MatrixXd load_matrix(const std::string& path, const GlobalOptions& global);

/// A and B (see read_pair in spdfit/fit_files.hpp), read as `request.read` says (the global
/// options'), with the readers' warnings printed. With the fit table's a_cols and b_cols
/// (request.a_cols, request.b_cols), A and B are those columns of the one file `a_path`, and `b_path`
/// is empty. Usage errors (UsageError, quoting what was typed): B's file missing without them,
/// one of them alone, a second file with them, a selection the file does not have.
DataPair load_pair(const std::string& a_path, const std::string& b_path, const FitRequest& request,
                   const GlobalOptions& global);

/// The read options of the data of `request` (data_read_options), its usage errors UsageErrors.
io::ReadOptions data_read(const FitRequest& request, const std::string& b_path);

}  // namespace spdfit::cli
