// Internal: FitResult and its parts as nlohmann::json objects, for the documents that hold them
// (compare's, hexapod identify's) and for to_json / from_json.
#pragma once

#include <string>

#include "render/json_values.hpp"
#include "spdfit/fit_result.hpp"

namespace spdfit::detail {

/// cli.md's fit contract (Contract), or every field (Exact); see to_json(const FitResult&).
Json fit_result_json(const FitResult& result, JsonStyle style);
/// The result that fit_result_json wrote; std::invalid_argument naming `type` and the field.
FitResult fit_result_from(const Json& object, const std::string& type);

/// A noise model: source ("std", "cov", "rest"), cov_a and cov_b (when resolved), std_a and std_b
/// (standard deviations), rest_rows, rest_mean_a and rest_mean_b, rest_a_path and rest_b_path (rest
/// rows), warnings; each when it has a value (render/noise_model_json.cpp).
Json noise_model_json(const NoiseModel& model, JsonStyle style);

/// A robust fit's report (FitResult::robust, PhysicalEstimate::robust): method, tuning, scale,
/// rows_downweighted (1-based), rows_downweighted_count, weights_min, iterations, converged.
Json robust_json(const RobustReport& report, JsonStyle style);
/// The same for people: "robust: huber (k = 1.869), 19 rows down-weighted below 0.5 (...)\n".
std::string robust_line(const RobustReport& report);
/// What robust_json wrote; std::invalid_argument naming `what` and the field.
RobustReport robust_from(const Json& object, const std::string& what);
NoiseModel noise_model_from(const Json& object, const std::string& type);

/// estimate, standard_errors, lower, upper, clusters (lists of 0-based indices), failed.
Json spectrum_json(const SpectrumUncertainty& spectrum, JsonStyle style);
SpectrumUncertainty spectrum_from(const Json& object, const std::string& type);

}  // namespace spdfit::detail
