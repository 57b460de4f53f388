#include "input.hpp"

#include "spdfit/io.hpp"

namespace spdfit::cli {

Eigen::MatrixXd load_matrix(const std::string& path) { return io::read_matrix(path); }

}  // namespace spdfit::cli
