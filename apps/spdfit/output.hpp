// Formatting results for people (tables) and programs (CSV, JSON).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "spdfit/fit_result.hpp"

namespace spdfit::cli {

/// A matrix as nested JSON arrays (rows), values round-tripping exactly; a vector as an array.
nlohmann::json matrix_json(const Eigen::MatrixXd& M);
nlohmann::json vector_json(const Eigen::VectorXd& v);

/// A finite number, or null for +-inf and NaN (JSON has no infinities).
nlohmann::json number_json(double value);

/// {"method", "m", "n", "X", "diagnostics": {...}, "warnings": [...]}: the fit contract.
nlohmann::json result_json(const FitResult& result);

/// The matrix as CSV text (io::write_csv).
std::string matrix_csv(const Eigen::MatrixXd& M);

/// Writes `text` to the file `path`, or to stdout when `path` is empty. Throws io::DataError
/// when the file cannot be written.
void emit(const std::string& text, const std::string& path);

/// Matrices printed side by side under their titles (`digits` decimals), wrapped to `width`.
std::string side_by_side(const std::vector<std::string>& titles, const std::vector<Eigen::MatrixXd>& matrices,
                         int digits = 4, std::size_t width = 120);

}  // namespace spdfit::cli
