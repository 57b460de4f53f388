// The names of a square matrix's variables, from its file's header row or index column.
#include <string>
#include <vector>

#include "spdfit/labels.hpp"

namespace spdfit {

namespace {
// "a, b, c" (the first few, then how many in all).
std::string listed(const std::vector<std::string>& names) {
  constexpr std::size_t kShown = 4;
  std::string text;
  for (std::size_t k = 0; k < names.size() && k < kShown; ++k) text += (k == 0 ? "" : ", ") + names[k];
  if (names.size() > kShown) text += ", ... (" + std::to_string(names.size()) + " in all)";
  return text;
}
}  // namespace

std::vector<std::string> variable_names(const io::LabelledTable& file, const std::string& source,
                                        std::vector<Warning>* warnings) {
  const Eigen::MatrixXd& values = file.table.values;
  const auto n = static_cast<std::size_t>(values.cols());
  const bool header = n > 0 && file.table.column_names.size() == n;
  const bool index = n > 0 && values.rows() == values.cols() && file.row_names.size() == n;
  if (header && index && file.row_names != file.table.column_names && warnings != nullptr) {
    warnings->push_back(Warning(Code::FileNotice, source + ": the row labels (" + listed(file.row_names) + ") differ from the column names (" +
                        listed(file.table.column_names) +
                        "); the result's rows and columns are named by the column names"));
  }
  if (header) return file.table.column_names;
  if (index) return file.row_names;
  return {};
}

}  // namespace spdfit
