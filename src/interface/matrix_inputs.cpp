#include "interface/matrix_inputs.hpp"

#include <utility>

namespace spdfit::detail {

Eigen::MatrixXd values_of(const MatrixInput& input, const io::ReadOptions& read, std::vector<Warning>& warnings) {
  if (!input.from_file()) return input.values;
  io::Table table = io::read_table(input.path, read);
  warnings.insert(warnings.end(), table.warnings.begin(), table.warnings.end());
  return std::move(table.values);
}

void shape_problem(const MatrixInput& input, const std::string& subject, const std::string& problem) {
  if (input.from_file()) throw io::DataError(input.path, 0, 0, problem, Code::DataShape);
  throw InputError(problem, Code::DataShape, subject);
}

void check_b_given(bool b_given, const std::string& a_cols, const std::string& b_cols) {
  if (!b_given && a_cols.empty() && b_cols.empty()) {
    throw OptionError("B's file is missing: give the files of A and B, or one file with `a_cols` and `b_cols` "
                      "choosing their columns",
                      Code::Argument, "b");
  }
}

}  // namespace spdfit::detail
