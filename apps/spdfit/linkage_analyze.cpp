// spdfit linkage analyze: a four-bar's output angle on both branches, transmission angle, dead points.
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "cli.hpp"
#include "linkage_arguments.hpp"
#include "linkage_commands.hpp"
#include "output.hpp"
#include "spdfit/io.hpp"
#include "spdfit/linkage/analysis.hpp"
#include "spdfit/linkage/prescribed_function.hpp"

namespace spdfit::cli {

using namespace spdfit::linkage;

namespace {

nlohmann::json optional_degrees(const std::optional<double>& x) {
  return x ? nlohmann::json(degrees(*x)) : nlohmann::json(nullptr);
}

}  // namespace

void run_analyze(const AnalyzeOptionsCli& o) {
  const std::vector<double> a = parse_list(o.lengths, 4, "--lengths");
  for (double x : a) {
    if (!(x > 0.0)) throw UsageError("--lengths must all be positive");
  }
  const FourBar bar{a[0], a[1], a[2], a[3]};
  const auto [lo, hi] = parse_range(o.psi_range, "psi_range");
  if (!(lo < hi)) throw UsageError("--psi-range must have LO < HI");
  if (o.points < 2) throw UsageError("--points must be at least 2");
  const Analysis r = analyze(bar, spaced_points(radians(lo), radians(hi), o.points, Spacing::Uniform));

  if (o.json) {
    nlohmann::json out;
    out["lengths"] = {{"a1", bar.a1}, {"a2", bar.a2}, {"a3", bar.a3}, {"a4", bar.a4}};
    out["k"] = vector_json(r.k);
    out["grashof"] = to_string(r.grashof);
    out["input_fully_rotates"] = r.input_fully_rotates;
    nlohmann::json dead = nlohmann::json::array();
    for (double d : r.dead_points) dead.push_back(degrees(d));
    out["dead_points_deg"] = dead;
    out["transmission_angle_deg"] = r.transmission ? range_json(*r.transmission) : nlohmann::json(nullptr);
    nlohmann::json samples = nlohmann::json::array();
    for (const AnalysisSample& s : r.samples) {
      samples.push_back({{"psi_deg", degrees(s.psi)},
                         {"phi_plus_deg", optional_degrees(s.phi_plus)},
                         {"phi_minus_deg", optional_degrees(s.phi_minus)},
                         {"transmission_angle_deg", optional_degrees(s.transmission_angle)}});
    }
    out["samples"] = samples;
    emit(out.dump(2) + "\n", o.output);
    return;
  }
  std::ostringstream out;
  out << "four-bar a1 = " << g(bar.a1) << " (ground), a2 = " << g(bar.a2) << " (input), a3 = " << g(bar.a3)
      << " (coupler), a4 = " << g(bar.a4) << " (output)\n";
  out << "Freudenstein parameters k = [" << g(r.k(0)) << ", " << g(r.k(1)) << ", " << g(r.k(2)) << "]\n";
  out << "Grashof type: " << to_string(r.grashof) << "; the input "
      << (r.input_fully_rotates ? "turns fully" : "cannot turn fully") << "\n";
  out << "dead points (input angle, deg):";
  if (r.dead_points.empty()) out << " none";
  for (double d : r.dead_points) out << " " << f4(degrees(d));
  out << "\ntransmission angle over the range (deg): "
      << (r.transmission ? f4(degrees(r.transmission->min)) + " .. " + f4(degrees(r.transmission->max))
                         : std::string("- (cannot be assembled)"))
      << "\n\n";
  char line[160];
  std::snprintf(line, sizeof line, "%12s %16s %16s %20s\n", "psi (deg)", "phi branch +1", "phi branch -1",
                "transmission (deg)");
  out << line;
  auto cell = [](const std::optional<double>& x) { return x ? f4(degrees(*x)) : std::string("-"); };
  for (const AnalysisSample& s : r.samples) {
    std::snprintf(line, sizeof line, "%12.4f %16s %16s %20s\n", degrees(s.psi), cell(s.phi_plus).c_str(),
                  cell(s.phi_minus).c_str(), cell(s.transmission_angle).c_str());
    out << line;
  }
  emit(out.str(), o.output);
}

}  // namespace spdfit::cli
