#include "input.hpp"

#include "spdfit/io.hpp"

namespace spdfit::cli {

namespace {
std::string shape(const Eigen::MatrixXd& M) {
  return std::to_string(M.rows()) + "x" + std::to_string(M.cols());
}
}  // namespace

Eigen::MatrixXd load_matrix(const std::string& path) { return io::read_matrix(path); }

DataPair load_pair(const std::string& a_path, const std::string& b_path) {
  DataPair data;
  data.A = load_matrix(a_path);
  // Checked before B is read, so that a hostile A (millions of columns) costs one file, not two.
  if (data.A.rows() < data.A.cols()) {
    throw io::fewer_samples_than_columns(a_path, static_cast<std::uint64_t>(data.A.rows()),
                                         static_cast<std::uint64_t>(data.A.cols()));
  }
  data.B = load_matrix(b_path);
  if (data.A.rows() != data.B.rows() || data.A.cols() != data.B.cols()) {
    throw io::DataError(b_path, 0, 0,
                        "B is " + shape(data.B) + " but A (" + a_path + ") is " + shape(data.A) +
                            ": A and B must have the same numbers of rows (samples) and columns");
  }
  return data;
}

}  // namespace spdfit::cli
