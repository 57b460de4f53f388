#include "output.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli.hpp"
#include "spdfit/io.hpp"

namespace spdfit::cli {

using nlohmann::json;

json number_json(double value) {
  if (std::isfinite(value)) return value;
  return nullptr;
}

json vector_json(const Eigen::VectorXd& v) {
  json out = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(number_json(v(i)));
  return out;
}

json matrix_json(const Eigen::MatrixXd& M) {
  json rows = json::array();
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index j = 0; j < M.cols(); ++j) row.push_back(number_json(M(i, j)));
    rows.push_back(std::move(row));
  }
  return rows;
}

std::string with_fields(const std::string& document, const json& fields) {
  json out = json::parse(document);
  out.update(fields);
  return out.dump(2) + "\n";
}

const ReportHints& report_hints() {
  static const ReportHints hints{"add --bootstrap N, e.g. 1000", "--json (interval, bias)"};
  return hints;
}

std::string matrix_csv(const Eigen::MatrixXd& M) {
  std::ostringstream out;
  io::write_csv(out, M);
  return out.str();
}

void emit(const std::string& text, const std::string& path) {
  if (path.empty()) {
    std::cout << text;
    std::cout.flush();
    return;
  }
  io::write_text(path, text);
}

namespace {
// ".npy" or ".mat" (any case) when the path ends so: the binary formats X is written in.
std::string binary_extension(const std::string& path) {
  if (path.size() < 4) return "";
  std::string tail = path.substr(path.size() - 4);
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return std::tolower(c); });
  return tail == ".npy" || tail == ".mat" ? tail : "";
}
}  // namespace

void emit_matrix(const Eigen::MatrixXd& X, const std::string& path) {
  const std::string binary = binary_extension(path);
  if (binary == ".npy") {
    io::write_npy(path, X);
  } else if (binary == ".mat") {
    io::write_mat(path, X);
  } else {
    emit(matrix_csv(X), path);
  }
}

void check_text_output(const std::string& path, const std::string& what) {
  const std::string binary = binary_extension(path);
  if (!binary.empty()) {
    throw UsageError("--output " + path + " names a " + binary + " file, which holds a matrix only, not " + what +
                     ": write " + what + " to another file name, or drop it to save X as " + binary);
  }
}

}  // namespace spdfit::cli
