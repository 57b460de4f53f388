// Loading the command line's data files, with errors that name the files, read as the global
// options say and with the readers' warnings printed.
#pragma once

#include <string>

#include <Eigen/Core>

#include "cli.hpp"

namespace spdfit::cli {

/// One matrix (see io::read_table), read as the global options say; the reader's warnings (a
/// first column of row labels dropped) are printed.
Eigen::MatrixXd load_matrix(const std::string& path, const GlobalOptions& global);

}  // namespace spdfit::cli
