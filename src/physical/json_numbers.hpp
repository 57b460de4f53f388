// Internal: numbers, vectors and matrices as ordered JSON for the physical fits' renderers
// (regress, payload identify and design): non-finite values as null, the others exactly.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace spdfit::physical::detail {

using OrderedJson = nlohmann::ordered_json;

inline OrderedJson number_json(double value) { return std::isfinite(value) ? OrderedJson(value) : OrderedJson(nullptr); }

inline OrderedJson vector_json(const Eigen::Ref<const Eigen::VectorXd>& v) {
  OrderedJson out = OrderedJson::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(number_json(v(i)));
  return out;
}

inline OrderedJson matrix_json(const Eigen::Ref<const Eigen::MatrixXd>& M) {
  OrderedJson rows = OrderedJson::array();
  for (Eigen::Index i = 0; i < M.rows(); ++i) rows.push_back(vector_json(M.row(i).transpose()));
  return rows;
}

}  // namespace spdfit::physical::detail
