// `spdfit compare`: every estimator's result side by side, as JSON and as a table.
#include <cstdio>
#include <sstream>

#include "render/fit_result_json.hpp"
#include "spdfit/format.hpp"
#include "spdfit/render.hpp"

namespace spdfit {

std::string to_json(const Comparison& comparison, JsonStyle style) {
  detail::Json out;
  out["m"] = comparison.m;
  out["n"] = comparison.n;
  out["d"] = comparison.d;
  out["results"] = detail::Json::array();
  for (std::size_t k = 0; k < comparison.results.size(); ++k) {
    detail::Json j = detail::fit_result_json(comparison.results[k], style);
    if (k < comparison.errors.size() && comparison.errors[k]) {
      j["error_vs_truth"] = detail::number_json(*comparison.errors[k], style);
    }
    out["results"].push_back(std::move(j));
  }
  return detail::dump(out, style);
}

std::string report(const Comparison& comparison) {
  const std::vector<FitResult>& results = comparison.results;
  if (results.empty()) return "no results\n";
  const auto optional_text = [](const std::optional<double>& value) {
    return value ? format_number(*value, Precision::Full) : std::string("-");
  };
  std::ostringstream out;
  const Diagnostics& data = results.front().diagnostics;
  char line[512];
  const std::string d_text = data.d == data.n ? "" : ", d = " + std::to_string(data.d);
  std::snprintf(line, sizeof line,
                "data: m = %ld samples, n = %ld%s; rank(A) = %ld, cond(A) = %s; rank(B) = %ld, cond(B) = %s\n\n",
                static_cast<long>(data.m), static_cast<long>(data.n), d_text.c_str(), static_cast<long>(data.rank_a),
                format_number(data.cond_a).c_str(), static_cast<long>(data.rank_b), format_number(data.cond_b).c_str());
  out << line;
  if (data.d != data.n) out << "(X is " << data.n << " x " << data.d << ": only ls and tls fit a non-square X)\n\n";

  std::vector<std::string> titles;
  std::vector<Eigen::MatrixXd> estimates;
  if (comparison.truth) {
    titles.emplace_back("truth");
    estimates.push_back(*comparison.truth);
  }
  for (const FitResult& r : results) {
    if (!r.ok()) continue;
    titles.emplace_back(to_string(r.method));
    estimates.push_back(r.X);
  }
  out << format_side_by_side(titles, estimates);

  std::snprintf(line, sizeof line, "%-11s %-12s %-12s %-14s %-10s %-10s%s\n", "method", "residual", "area",
                "min eigenvalue", "symmetric", "definite", comparison.truth ? "  error ||X - truth||_F" : "");
  out << line;
  for (std::size_t k = 0; k < results.size(); ++k) {
    const FitResult& r = results[k];
    const std::string name(to_string(r.method));
    if (!r.ok()) {
      out << name << std::string(11 - std::min<std::size_t>(name.size(), 11), ' ') << " failed: " << r.message
          << '\n';
      continue;
    }
    const Diagnostics& d = r.diagnostics;
    const std::optional<double> error = k < comparison.errors.size() ? comparison.errors[k] : std::nullopt;
    std::snprintf(line, sizeof line, "%-11s %-12s %-12s %-14s %-10s %-10s%s\n", name.c_str(),
                  format_number(d.residual_norm, Precision::Full).c_str(), optional_text(d.area_criterion).c_str(),
                  optional_text(d.min_eigenvalue).c_str(), d.symmetric ? "yes" : "no",
                  d.positive_definite ? "positive" : (d.symmetric ? "no" : "-"),
                  comparison.truth ? ("  " + optional_text(error)).c_str() : "");
    out << line;
  }
  return out.str();
}

}  // namespace spdfit
