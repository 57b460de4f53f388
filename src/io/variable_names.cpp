// The names of a square matrix's variables, from its file's header row or index column.
#include <algorithm>
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

std::optional<Eigen::MatrixXd> aligned_by_name(const Eigen::MatrixXd& M, const std::vector<std::string>& names,
                                               const std::vector<std::string>& to, std::string* error) {
  if (names.empty() || to.empty() || names == to) return M;
  std::vector<Eigen::Index> position(to.size());
  bool same = names.size() == to.size() && static_cast<std::size_t>(M.rows()) == to.size() && M.rows() == M.cols();
  for (std::size_t k = 0; same && k < to.size(); ++k) {
    const auto it = std::find(names.begin(), names.end(), to[k]);
    same = it != names.end();
    if (same) position[k] = static_cast<Eigen::Index>(it - names.begin());
  }
  if (!same) {
    if (error) *error = "its names (" + listed(names) + ") are not the matrix's (" + listed(to) + ")";
    return std::nullopt;
  }
  const auto n = static_cast<Eigen::Index>(to.size());
  Eigen::MatrixXd out(n, n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) out(i, j) = M(position[i], position[j]);
  return out;
}

}  // namespace spdfit
