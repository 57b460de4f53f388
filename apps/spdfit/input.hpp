// Loading the command line's data files, with errors that name the files.
#pragma once

#include <string>

#include <Eigen/Core>

namespace spdfit::cli {

/// A and B read from their files, checked to have the same shape and at least as many rows as
/// columns. Throws io::DataError naming the file(s) otherwise.
struct DataPair {
  Eigen::MatrixXd A, B;
};
DataPair load_pair(const std::string& a_path, const std::string& b_path);

/// One matrix (see io::read_matrix).
Eigen::MatrixXd load_matrix(const std::string& path);

}  // namespace spdfit::cli
