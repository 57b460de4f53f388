// Writing results: CSV, JSON documents the command builds itself (the results' own come from the
// library, spdfit/render.hpp), and files.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "spdfit/fit_result.hpp"
#include "spdfit/render.hpp"

namespace spdfit::cli {

/// A matrix as nested JSON arrays (rows), values round-tripping exactly; a vector as an array.
nlohmann::json matrix_json(const Eigen::MatrixXd& M);
nlohmann::json vector_json(const Eigen::VectorXd& v);

/// A finite number, or null for +-inf and NaN (JSON has no infinities).
nlohmann::json number_json(double value);

/// `document` (a JSON object's text, as the library renders it) with `fields` added, as the
/// command prints it (indented by 2, a final newline): what the command adds to a result, such as
/// the options it ran with.
std::string with_fields(const std::string& document, const nlohmann::json& fields);

/// How fit --report refers to the command line's own options (the library's report, spdfit/render.hpp).
const ReportHints& report_hints();

/// The matrix as CSV text (io::write_csv).
std::string matrix_csv(const Eigen::MatrixXd& M);

/// Writes `text` to the file `path`, or to stdout when `path` is empty. Throws io::DataError
/// when the file cannot be written.
void emit(const std::string& text, const std::string& path);

/// Writes the matrix X to `path` in the format its extension names (.npy: float64 NumPy; anything
/// else: CSV), or as CSV to stdout when `path` is empty.
void emit_matrix(const Eigen::MatrixXd& X, const std::string& path);

/// A usage error when `path` names a binary matrix format (.npy) that cannot hold the text output
/// `what` (e.g. "--json").
void check_text_output(const std::string& path, const std::string& what);

}  // namespace spdfit::cli
