#include "spdfit/linkage/pairs_file.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "io/parse.hpp"
#include "linkage/angles.hpp"

namespace spdfit::linkage {

namespace {

using detail::kRadiansPerDegree;

// A first line "0,1" is pandas' header of an unnamed two-column frame to the general reader, but
// in a pairs file it is as likely the first pair (psi = 0, phi = 1), and the pairs are read without
// the reader's warnings: it stays a pair, as it always was.
bool took_pandas_header(const io::Table& table) {
  return table.column_names == std::vector<std::string>{"0", "1"};
}

io::ReadOptions first_line_is_data() {
  io::ReadOptions options;
  options.header_row = io::HeaderRow::Absent;
  return options;
}

}  // namespace

PrescribedPairs pairs_from_table(const io::Table& table, const std::string& source, const PairsFileOptions& options) {
  const Eigen::MatrixXd& values = table.values;
  if (values.cols() != 2) {
    throw io::DataError(source, 0, 0,
                        "the pairs file has " + std::to_string(values.cols()) +
                            " columns: two are needed, the input angle psi and the output angle phi");
  }
  if (values.rows() < options.min_pairs) {
    const std::string needed = std::to_string(options.min_pairs);
    throw io::DataError(source, 0, 0,
                        std::to_string(values.rows()) + " pair(s): at least " + needed + " are needed (" + needed +
                            " give exact precision-point synthesis)");
  }
  // A file's numbers are finite (the reader refuses the others); values given in memory may not be.
  for (Eigen::Index i = 0; i < values.rows(); ++i) {
    if (!std::isfinite(values(i, 0)) || !std::isfinite(values(i, 1))) {
      throw io::DataError(source, 0, 0, "pair " + std::to_string(i + 1) + " is not finite (NaN or Inf)");
    }
  }
  const double scale = options.radians ? 1.0 : kRadiansPerDegree;
  PrescribedPairs pairs;
  pairs.delta_psi = values.col(0) * scale;
  pairs.delta_phi = values.col(1) * scale;
  return pairs;
}

PrescribedPairs parse_pairs(std::string_view bytes, const std::string& source, const PairsFileOptions& options) {
  io::Table table = io::parse_table(bytes, source);
  if (took_pandas_header(table)) table = io::parse_table(bytes, source, first_line_is_data());
  return pairs_from_table(table, source, options);
}

PrescribedPairs read_pairs(const std::string& path, const PairsFileOptions& options) {
  io::Table table = io::read_table(path);
  if (took_pandas_header(table)) table = io::read_table(path, first_line_is_data());
  return pairs_from_table(table, path, options);
}

Eigen::VectorXd weights_from_matrix(const Eigen::MatrixXd& W, Eigen::Index pairs, const std::string& source) {
  if (W.size() != pairs || (W.rows() != 1 && W.cols() != 1)) {
    throw io::DataError(source, 0, 0,
                        "the weights are " + std::to_string(W.rows()) + "x" + std::to_string(W.cols()) +
                            ": one column of " + std::to_string(pairs) + " weights (one per pair) is needed");
  }
  const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(W.data(), pairs);
  for (Eigen::Index i = 0; i < pairs; ++i) {
    if (!(w(i) > 0.0) || std::isinf(w(i))) {
      throw io::DataError(source, 0, 0,
                          "weight " + std::to_string(i + 1) + " is " + io::format_double(w(i)) +
                              (std::isinf(w(i)) ? ": weights must be finite" : ": weights must be positive"));
    }
  }
  return w;
}

Eigen::VectorXd read_weights(const std::string& path, Eigen::Index pairs) {
  return weights_from_matrix(io::read_matrix(path), pairs, path);
}

}  // namespace spdfit::linkage
