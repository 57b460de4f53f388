// Internal: the labels of a matrix's rows or columns in the renderings (labelled CSV, reports).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace spdfit::detail {

/// `names` when there is one per row (or column), else "1", "2", ..., `count`.
std::vector<std::string> labels_or_numbers(const std::vector<std::string>& names, Eigen::Index count);

}  // namespace spdfit::detail
