// A repair's result as JSON (the result part of `spdfit nearest --json`).
#include "render/json_values.hpp"
#include "spdfit/labels.hpp"
#include "spdfit/nearest_request.hpp"

namespace spdfit {

using detail::Json;

namespace {
Json nearest_json(const NearestResult& r, JsonStyle style) {
  Json out;
  out["n"] = r.X.rows();
  out["min_eig"] = detail::number_json(r.min_eig, style);
  out["X"] = detail::matrix_json(r.X, style);
  out["distance"] = detail::number_json(r.distance, style);
  out["clipped"] = r.clipped;
  out["min_eigenvalue_before"] = detail::number_json(r.min_eigenvalue_before, style);
  out["iterations"] = r.iterations;
  out["gradient_norm"] = detail::number_json(r.gradient_norm, style);
  out["converged"] = r.converged;
  out["cholesky"] = r.cholesky_ok;
  detail::put_warnings(out, r.warnings);
  return out;
}
}  // namespace

std::string to_json(const NearestResult& r, JsonStyle style) { return detail::dump(nearest_json(r, style), style); }

std::string to_json(const NearestResult& r, const std::vector<std::string>& names, JsonStyle style) {
  Json out = nearest_json(r, style);
  if (!names.empty()) out["names"] = names;
  return detail::dump(out, style);
}

std::string to_json(const NearestRun& run, JsonStyle style) {
  Json out = nearest_json(run.result, style);
  if (!run.names.empty()) out["names"] = run.names;
  const EigenvalueFloor floor = run.repair.floor();
  // The options the repair ran with.
  out["corr"] = run.repair.corr;
  out["keep_diag"] = run.repair.keep_diag;
  out["via_corr"] = run.repair.via_corr;
  out["min_eig_rel"] = floor.relative ? detail::number_json(floor.value, style) : Json(nullptr);
  out["alpha"] = detail::number_json(run.repair.alpha.value_or(0.0), style);
  return detail::dump(out, style);
}

template <>
NearestResult from_json<NearestResult>(const std::string& text) {
  const std::string type = "NearestResult";
  const Json object = detail::parse_object(text, type);
  const auto number = [&](const char* key) {
    return detail::number_from(detail::field(object, key, type), type + " '" + key + "'");
  };
  NearestResult r;
  r.X = detail::matrix_from(detail::field(object, "X", type), type + " 'X'");
  r.min_eig = number("min_eig");
  r.distance = number("distance");
  r.clipped = detail::value_from<Eigen::Index>(object, "clipped", type);
  r.min_eigenvalue_before = number("min_eigenvalue_before");
  r.iterations = detail::value_from<int>(object, "iterations", type);
  r.gradient_norm = number("gradient_norm");
  r.converged = detail::value_from<bool>(object, "converged", type);
  r.cholesky_ok = detail::value_from<bool>(object, "cholesky", type);
  r.warnings = detail::warnings_from(object, type);
  return r;
}

}  // namespace spdfit
