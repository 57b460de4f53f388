// X as a labelled CSV table: `spdfit fit --header` and `spdfit nearest --header`.
#include <sstream>
#include <string>
#include <vector>

#include "render/labels.hpp"
#include "spdfit/io.hpp"
#include "spdfit/labels.hpp"

namespace spdfit {

namespace detail {

std::vector<std::string> labels_or_numbers(const std::vector<std::string>& names, Eigen::Index count) {
  if (static_cast<Eigen::Index>(names.size()) == count) return names;
  std::vector<std::string> numbers;
  for (Eigen::Index k = 1; k <= count; ++k) numbers.push_back(std::to_string(k));
  return numbers;
}

}  // namespace detail

std::string labelled_csv(const Eigen::MatrixXd& X, const std::vector<std::string>& row_names,
                         const std::vector<std::string>& column_names) {
  std::ostringstream out;
  io::write_csv(out, X, detail::labels_or_numbers(row_names, X.rows()),
                detail::labels_or_numbers(column_names, X.cols()));
  return out.str();
}

std::string labelled_csv(const FitResult& result) {
  return labelled_csv(result.X, result.row_names, result.column_names);
}

}  // namespace spdfit
