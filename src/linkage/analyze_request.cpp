// `linkage analyze`'s option table and workflow (its renderings: render/linkage_analyze_render.cpp).
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

}  // namespace spdfit::linkage
