// `linkage analyze`'s option table, workflow and renderings.
#include "spdfit/linkage/analyze_request.hpp"

#include <cstdio>
#include <limits>
#include <sstream>

#include "interface/option_builders.hpp"
#include "render/linkage_render.hpp"
#include "spdfit/linkage/prescribed_function.hpp"
#include "spdfit/linkage/synthesize_request.hpp"

namespace spdfit::linkage {

namespace {

using AnalyzeSpec = OptionSpec<AnalyzeRequest>;

std::vector<AnalyzeSpec> make_analyze_table() {
  std::vector<AnalyzeSpec> table;
  AnalyzeSpec lengths = spdfit::detail::option_entry<AnalyzeRequest>(
      "lengths", "--lengths", "", OptionType::RealList, "A1,A2,A3,A4", "a1,a2,a3,a4: ground, input, coupler, output");
  // Python's lengths (a FourBar or four numbers) and psi (the angles themselves) are its own arguments.
  lengths.required = true;
  lengths.range = {0.0, std::numeric_limits<double>::infinity(), true, false};
  lengths.set = [](AnalyzeRequest& r, const OptionValue& v) { r.lengths = std::get<std::vector<double>>(v); };
  table.push_back(lengths);

  AnalyzeSpec range = spdfit::detail::option_entry<AnalyzeRequest>("psi_range", "--psi-range", "psi_range", OptionType::Range,
                                                                     "LO:HI", "Input angles LO:HI in degrees", "0:360");
  range.set = [](AnalyzeRequest& r, const OptionValue& v) { r.psi_range = std::get<std::string>(v); };
  table.push_back(range);

  table.push_back(spdfit::detail::integer_entry<AnalyzeRequest>("points", "--points", "points", "Number of input angles",
                                                                 "37", {2.0, 1e7}, &AnalyzeRequest::points));

  for (AnalyzeSpec& spec : output_options(&AnalyzeRequest::output, {"json", "output"}, {"Print the analysis as JSON"})) {
    table.push_back(std::move(spec));
  }
  return table;
}

nlohmann::json optional_degrees_json(const std::optional<double>& x) {
  return x ? nlohmann::json(detail::in_degrees(*x)) : nlohmann::json(nullptr);
}

}  // namespace

const std::vector<OptionSpec<AnalyzeRequest>>& analyze_option_table() {
  static const std::vector<AnalyzeSpec> table = make_analyze_table();
  return table;
}

Analysis run_analyze(const AnalyzeRequest& request, const std::vector<std::string_view>& given) {
  if (request.lengths.size() != 4) {
    throw OptionError("`lengths` needs 4 comma-separated numbers, got " + std::to_string(request.lengths.size()),
                      Code::OptionValue, "lengths");
  }
  for (double a : request.lengths) {
    if (!(a > 0.0) || !std::isfinite(a)) {
      throw OptionError("`lengths` must all be positive", Code::OptionValue, "lengths");
    }
  }
  const FourBar bar{request.lengths[0], request.lengths[1], request.lengths[2], request.lengths[3]};
  if (request.psi.size() > 0) {
    for (const std::string_view name : given) {
      if (name == "psi_range" || name == "points") {
        throw OptionError("`" + std::string(name) + "` describes input angles to generate; the angles are given",
                          Code::OptionConflict, std::string(name));
      }
    }
    if (!request.psi.allFinite()) throw OptionError("the input angles must be finite", Code::OptionValue, "psi");
    return analyze(bar, request.psi);
  }
  const auto [lo, hi] = parse_range(request.psi_range, "psi_range");
  if (!(lo < hi)) throw OptionError("`psi_range` must have LO < HI", Code::OptionValue, "psi_range");
  if (request.points < 2) throw OptionError("`points` must be at least 2", Code::OptionValue, "points");
  return analyze(bar, spaced_points(detail::in_radians(lo), detail::in_radians(hi), request.points, Spacing::Uniform));
}

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
