// `linkage analyze`'s result as JSON and as a report for people.
#include <cstdio>
#include <optional>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "render/json_values.hpp"
#include "render/linkage_render.hpp"
#include "spdfit/linkage/analyze_request.hpp"

namespace spdfit::linkage {

namespace {

nlohmann::json optional_degrees_json(const std::optional<double>& x) {
  return x ? nlohmann::json(detail::in_degrees(*x)) : nlohmann::json(nullptr);
}

}  // namespace

std::string to_json(const Analysis& r) {
  using detail::in_degrees;
  nlohmann::json out;
  out["lengths"] = {{"a1", r.bar.a1}, {"a2", r.bar.a2}, {"a3", r.bar.a3}, {"a4", r.bar.a4}};
  out["k"] = spdfit::detail::vector_json(r.k);
  out["grashof"] = to_string(r.grashof);
  out["input_fully_rotates"] = r.input_fully_rotates;
  nlohmann::json dead = nlohmann::json::array();
  for (double d : r.dead_points) dead.push_back(in_degrees(d));
  out["dead_points_deg"] = dead;
  out["transmission_angle_deg"] = r.transmission ? detail::span_json(*r.transmission) : nlohmann::json(nullptr);
  nlohmann::json samples = nlohmann::json::array();
  for (const AnalysisSample& s : r.samples) {
    samples.push_back({{"psi_deg", in_degrees(s.psi)},
                       {"phi_plus_deg", optional_degrees_json(s.phi_plus)},
                       {"phi_minus_deg", optional_degrees_json(s.phi_minus)},
                       {"transmission_angle_deg", optional_degrees_json(s.transmission_angle)}});
  }
  out["samples"] = samples;
  return out.dump(2) + "\n";
}

std::string report(const Analysis& r) {
  using detail::four_decimals;
  using detail::full_g;
  using detail::in_degrees;
  const FourBar& bar = r.bar;
  std::ostringstream out;
  out << "four-bar a1 = " << full_g(bar.a1) << " (ground), a2 = " << full_g(bar.a2)
      << " (input), a3 = " << full_g(bar.a3) << " (coupler), a4 = " << full_g(bar.a4) << " (output)\n";
  out << "Freudenstein parameters k = [" << full_g(r.k(0)) << ", " << full_g(r.k(1)) << ", " << full_g(r.k(2))
      << "]\n";
  out << "Grashof type: " << to_string(r.grashof) << "; the input "
      << (r.input_fully_rotates ? "turns fully" : "cannot turn fully") << "\n";
  out << "dead points (input angle, deg):";
  if (r.dead_points.empty()) out << " none";
  for (double d : r.dead_points) out << " " << four_decimals(in_degrees(d));
  out << "\ntransmission angle over the range (deg): "
      << (r.transmission
              ? four_decimals(in_degrees(r.transmission->min)) + " .. " + four_decimals(in_degrees(r.transmission->max))
              : std::string("- (cannot be assembled)"))
      << "\n\n";
  char line[160];
  std::snprintf(line, sizeof line, "%12s %16s %16s %20s\n", "psi (deg)", "phi branch +1", "phi branch -1",
                "transmission (deg)");
  out << line;
  const auto cell = [](const std::optional<double>& x) {
    return x ? four_decimals(in_degrees(*x)) : std::string("-");
  };
  for (const AnalysisSample& s : r.samples) {
    std::snprintf(line, sizeof line, "%12.4f %16s %16s %20s\n", in_degrees(s.psi), cell(s.phi_plus).c_str(),
                  cell(s.phi_minus).c_str(), cell(s.transmission_angle).c_str());
    out << line;
  }
  return out.str();
}

}  // namespace spdfit::linkage
