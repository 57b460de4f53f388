// Loading the command line's data files, with errors that name the files (pairs A, B: read_pair
// in spdfit/fit_files.hpp).
#pragma once

#include <string>

#include <Eigen/Core>

namespace spdfit::cli {

/// One matrix (see io::read_matrix).
Eigen::MatrixXd load_matrix(const std::string& path);

}  // namespace spdfit::cli
