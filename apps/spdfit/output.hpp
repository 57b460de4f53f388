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

/// The bootstrap's uncertainty of sorted values (eigenvalues, modes) as JSON: estimate,
/// standard_errors, lower, upper, clusters (lists of 0-based indices) and failed.
nlohmann::json spectrum_json(const SpectrumUncertainty& s);

/// fit --report: X with its bootstrap standard errors (when there are any), its eigenvalues with
/// their intervals, and the noise estimate, as a table for people.
std::string fit_report(const FitResult& result);

/// Sorted values with their intervals, one line each, clusters marked ("  1  3.6527  [3.61, 3.70]").
std::string spectrum_text(const SpectrumUncertainty& s, const std::string& indent);

/// "%.*f"-style text with `digits` decimals (scientific from 1e5 on), or "-" for NaN.
std::string fixed(double value, int digits = 4);

/// A number in three significant digits ("%.3g"), for messages and prose.
std::string trimmed(double value);

/// A confidence level as a percentage: "95%" for 0.95.
std::string percent_text(double level);

/// The matrix as CSV text (io::write_csv).
std::string matrix_csv(const Eigen::MatrixXd& M);

/// Writes `text` to the file `path`, or to stdout when `path` is empty. Throws io::DataError
/// when the file cannot be written.
void emit(const std::string& text, const std::string& path);

/// Writes the matrix X to `path` in the format its extension names (.npy: float64 NumPy; anything
/// else: CSV), or as CSV to stdout when `path` is empty.
void emit_matrix(const Eigen::MatrixXd& X, const std::string& path);

/// X as CSV with a header row and row labels (fit --header): its rows named by A's columns and
/// its columns by B's (result.row_names, column_names), numbered from 1 where a file had none.
std::string labelled_matrix_csv(const FitResult& result);

/// A usage error when `path` names a binary matrix format (.npy) that cannot hold the text output
/// `what` (e.g. "--json").
void check_text_output(const std::string& path, const std::string& what);

/// Matrices printed side by side under their titles (`digits` decimals), wrapped to `width`.
std::string side_by_side(const std::vector<std::string>& titles, const std::vector<Eigen::MatrixXd>& matrices,
                         int digits = 4, std::size_t width = 120);

}  // namespace spdfit::cli
