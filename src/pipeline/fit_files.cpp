#include "spdfit/fit_files.hpp"

#include <stdexcept>

#include "pipeline/pair_checks.hpp"
#include "spdfit/fit.hpp"

namespace spdfit {

namespace {
std::string shape(const Eigen::MatrixXd& M) { return std::to_string(M.rows()) + "x" + std::to_string(M.cols()); }
}  // namespace

DataPair read_pair(const std::string& a_path, const std::string& b_path, const io::ReadOptions& options) {
  DataPair data;
  data.A = io::read_matrix(a_path, options);
  if (data.A.rows() < data.A.cols()) {
    throw detail::fewer_samples_than_columns(a_path, static_cast<std::uint64_t>(data.A.rows()),
                                             static_cast<std::uint64_t>(data.A.cols()));
  }
  data.B = io::read_matrix(b_path, options);
  if (data.A.rows() != data.B.rows() || data.A.cols() != data.B.cols()) {
    throw io::DataError(b_path, 0, 0,
                        "B is " + shape(data.B) + " but A (" + a_path + ") is " + shape(data.A) +
                            ": A and B must have the same numbers of rows (samples) and columns");
  }
  return data;
}

FitResult fit_files(const std::string& a_path, const std::string& b_path, Method method, const FitOptions& options,
                    const std::optional<StreamOptions>& stream) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument("fit_files: " + error);
  if (stream) return fit(reduce(stream_factor(a_path, b_path, *stream), options), method);
  const DataPair data = read_pair(a_path, b_path);
  return fit(data.A, data.B, method, options);
}

}  // namespace spdfit
