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

/// estimate, standard_errors, lower, upper, clusters (lists of 0-based indices), failed.
Json spectrum_json(const SpectrumUncertainty& spectrum, JsonStyle style);
SpectrumUncertainty spectrum_from(const Json& object, const std::string& type);

}  // namespace spdfit::detail
