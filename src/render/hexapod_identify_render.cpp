// `spdfit hexapod identify`: the identification as JSON and as a report for people.
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "render/fit_result_json.hpp"
#include "render/text_values.hpp"
#include "spdfit/compare.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/render.hpp"

namespace spdfit::hexapod {

using detail::Json;

namespace {

Json method_json(const MethodIdentification& m, JsonStyle style) {
  Json j = detail::fit_result_json(m.result, style);
  if (m.eigenvalues) j["eigenvalues"] = detail::vector_json(*m.eigenvalues, style);
  if (m.modes_hz) j["modes_hz"] = detail::vector_json(*m.modes_hz, style);
  if (m.error_vs_truth) j["error_vs_truth"] = detail::number_json(*m.error_vs_truth, style);
  if (m.modes_uncertainty) j["bootstrap"]["modes_hz"] = detail::spectrum_json(*m.modes_uncertainty, style);
  return j;
}

// Each symmetric estimate's eigenvalues and modes with their bootstrap intervals.
std::string bootstrap_report(const std::vector<MethodIdentification>& methods, const IdentifyOptions& options) {
  std::ostringstream out;
  out << "\nbootstrap: " << options.fit.bootstrap << " resamples of the rows (seed " << options.fit.seed
      << "); value +- standard error   [" << format_percent(options.fit.confidence, Precision::Medium)
      << " interval]; values closer than their standard errors share one interval\n";
  for (const MethodIdentification& m : methods) {
    const auto& b = m.result.bootstrap;
    if (!b || !b->eigenvalues) continue;
    out << to_string(m.result.method) << " (" << b->failed << " of " << b->replicates << " resamples failed)\n"
        << "  eigenvalues (kg)\n"
        << report(*b->eigenvalues, "    ");
    if (m.modes_uncertainty) out << "  modes (Hz)\n" << report(*m.modes_uncertainty, "    ");
  }
  return out.str();
}

}  // namespace

std::string to_json(const MethodIdentification& method, JsonStyle style) {
  return detail::dump(method_json(method, style), style);
}

namespace {

Json identify_json(const std::vector<MethodIdentification>& methods, const IdentifyOptions& options,
                   JsonStyle style) {
  Json out;
  out["m"] = methods.empty() ? Eigen::Index{0} : methods.front().result.diagnostics.m;
  out["n"] = methods.empty() ? Eigen::Index{0} : methods.front().result.diagnostics.n;
  if (options.truth) out["truth"] = detail::matrix_json(*options.truth, style);
  out["stiffness"] = options.stiffness ? detail::matrix_json(*options.stiffness, style) : Json(nullptr);
  out["methods"] = Json::object();
  for (const MethodIdentification& m : methods) out["methods"][std::string(to_string(m.result.method))] = method_json(m, style);
  return out;
}

}  // namespace

std::string to_json(const std::vector<MethodIdentification>& methods, const IdentifyOptions& options,
                    JsonStyle style) {
  return detail::dump(identify_json(methods, options, style), style);
}

std::string to_json(const std::vector<MethodIdentification>& methods, const IdentifyOptions& options,
                    const PhysicalEstimate& physical) {
  Json out = identify_json(methods, options, JsonStyle::Contract);
  out["physical"] = Json::parse(to_json(physical, options));
  return detail::dump(out, JsonStyle::Contract);
}

namespace {

// The report of every estimator but the closing line naming the one closest to the truth.
std::string methods_report(const std::vector<MethodIdentification>& methods, const IdentifyOptions& options) {
  std::ostringstream out;
  const Diagnostics& data = methods.front().result.diagnostics;
  char line[320];
  std::snprintf(line, sizeof line, "data: m = %ld samples of n = %ld struts; cond(A) = %s, cond(B) = %s (rank %ld, %ld)\n\n",
                static_cast<long>(data.m), static_cast<long>(data.n), format_number(data.cond_a).c_str(),
                format_number(data.cond_b).c_str(), static_cast<long>(data.rank_a), static_cast<long>(data.rank_b));
  out << line;
  std::vector<std::string> titles;
  std::vector<Eigen::MatrixXd> matrices;
  if (options.truth) {
    titles.emplace_back("truth");
    matrices.push_back(*options.truth);
  }
  for (const MethodIdentification& m : methods) {
    if (!m.result.ok()) continue;
    titles.emplace_back(to_string(m.result.method));
    matrices.push_back(m.result.X);
  }
  out << "Estimates of M_p\n" << format_side_by_side(titles, matrices);

  std::snprintf(line, sizeof line, "%-11s %-10s %-10s %12s %12s %12s%s\n", "method", "symmetric", "definite",
                "residual", "area", "min eig", options.truth ? "  error ||M_hat - truth||_F" : "");
  out << line;
  for (const MethodIdentification& m : methods) {
    const FitResult& r = m.result;
    const std::string name(to_string(r.method));
    if (!r.ok()) {
      out << name << std::string(12 - std::min<std::size_t>(name.size(), 11), ' ') << "failed: " << r.message
          << '\n';
      continue;
    }
    const Diagnostics& d = r.diagnostics;
    const auto optional_fixed = [](const std::optional<double>& v) { return v ? format_fixed(*v) : "-"; };
    std::snprintf(line, sizeof line, "%-11s %-10s %-10s %12s %12s %12s%s\n", name.c_str(), d.symmetric ? "yes" : "no",
                  d.positive_definite ? "positive" : (d.symmetric ? "no" : "-"), format_fixed(d.residual_norm).c_str(),
                  optional_fixed(d.area_criterion).c_str(), optional_fixed(d.min_eigenvalue).c_str(),
                  m.error_vs_truth ? ("  " + format_fixed(*m.error_vs_truth)).c_str() : "");
    out << line;
  }
  out << "\neigenvalues (kg)" << (options.stiffness ? " and modes sqrt(eig(M_hat^-1 K)) / 2 pi (Hz)" : "") << "\n";
  for (const MethodIdentification& m : methods) {
    if (!m.result.ok()) continue;
    const std::string name(to_string(m.result.method));
    std::snprintf(line, sizeof line, "%-11s ", name.c_str());
    if (!m.eigenvalues) {
      out << line << "not symmetric, so not a mass matrix: no eigenvalues or modes shown\n";
      continue;
    }
    out << line << spdfit::detail::fixed_values(*m.eigenvalues, 4) << '\n';
    if (options.stiffness) {
      out << std::string(12, ' ')
          << (m.modes_hz ? spdfit::detail::fixed_values(*m.modes_hz, 2) + " Hz" : "not positive definite: no modes") << '\n';
    }
  }
  if (options.fit.bootstrap > 0) out << bootstrap_report(methods, options);
  return out.str();
}

// "closest to the truth: NAME (error E)" among the methods and, when given, the physical estimate.
std::string closest_line(const std::vector<MethodIdentification>& methods, const PhysicalEstimate* physical,
                         const IdentifyOptions& options) {
  std::vector<std::optional<double>> errors;
  std::vector<std::string> names;
  for (const MethodIdentification& m : methods) {
    errors.push_back(m.error_vs_truth);
    names.emplace_back(to_string(m.result.method));
  }
  if (physical && physical->ok() && options.truth && options.truth->rows() == 6 &&
      options.truth->cols() == 6) {
    errors.push_back((physical->M_p - *options.truth).norm());
    names.emplace_back("physical");
  }
  const auto best = closest_to_truth(errors);
  if (!best) return "";
  return "\nclosest to the truth: " + names[*best] + " (error " + format_fixed(*errors[*best]) + ")\n";
}

}  // namespace

std::string report(const std::vector<MethodIdentification>& methods, const IdentifyOptions& options) {
  if (methods.empty()) return "no estimates\n";
  return methods_report(methods, options) + closest_line(methods, nullptr, options);
}

std::string report(const std::vector<MethodIdentification>& methods, const IdentifyOptions& options,
                   const PhysicalEstimate& physical, const Geometry& geometry) {
  std::string out = methods.empty() ? std::string("no estimates\n") : methods_report(methods, options);
  return out + "\n" + report(physical, geometry, options) + closest_line(methods, &physical, options);
}

}  // namespace spdfit::hexapod

namespace spdfit {

template <>
hexapod::MethodIdentification from_json<hexapod::MethodIdentification>(const std::string& text) {
  const std::string type = "MethodIdentification";
  const detail::Json object = detail::parse_object(text, type);
  hexapod::MethodIdentification m;
  m.result = detail::fit_result_from(object, type);
  if (const detail::Json* e = detail::optional_field(object, "eigenvalues")) {
    m.eigenvalues = detail::vector_from(*e, type + " 'eigenvalues'");
  }
  if (const detail::Json* modes = detail::optional_field(object, "modes_hz")) {
    m.modes_hz = detail::vector_from(*modes, type + " 'modes_hz'");
  }
  m.error_vs_truth = detail::optional_number_from(object, "error_vs_truth", type);
  if (const detail::Json* b = detail::optional_field(object, "bootstrap")) {
    if (const detail::Json* modes = detail::optional_field(*b, "modes_hz")) {
      m.modes_uncertainty = detail::spectrum_from(*modes, type + " bootstrap modes_hz");
    }
  }
  return m;
}

}  // namespace spdfit
