#include "input.hpp"

#include "spdfit/io.hpp"

namespace spdfit::cli {

Eigen::MatrixXd load_matrix(const std::string& path, const GlobalOptions& global) {
  io::Table table = io::read_table(path, global.read);
  for (const std::string& w : table.warnings) warn(global, w);
  return std::move(table.values);
}

DataPair load_pair(const std::string& a_path, const std::string& b_path, const GlobalOptions& global) {
  DataPair data = read_pair(a_path, b_path, global.read);
  for (const std::string& w : data.warnings) warn(global, w);
  return data;
}

}  // namespace spdfit::cli
