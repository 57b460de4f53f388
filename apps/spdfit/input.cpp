#include "input.hpp"

#include "spdfit/io.hpp"

namespace spdfit::cli {

Eigen::MatrixXd load_matrix(const std::string& path, const GlobalOptions& global) {
  io::Table table = io::read_table(path, global.read);
  for (const auto& w : table.warnings) warn(global, w);
  return std::move(table.values);
}

}  // namespace spdfit::cli
