// `inertia repair`'s option table and workflow: a JSON body or every link of a URDF file.
#include <algorithm>
#include <cctype>
#include <limits>
#include <string>

#include "interface/option_builders.hpp"
#include "physical/common_options.hpp"
#include "spdfit/inertia_repair.hpp"

namespace spdfit {

namespace {

using InertiaSpec = OptionSpec<InertiaRepairRequest>;

std::vector<InertiaSpec> make_inertia_table() {
  std::vector<InertiaSpec> table;
  InertiaSpec file = physical::detail::text_option<InertiaRepairRequest>("input", "FILE", "", "", "A JSON body or a URDF file", "");
  file.type = OptionType::File;
  file.positional = true;
  file.required = true;
  file.set = [](InertiaRepairRequest& r, const OptionValue& v) { r.input = std::get<std::string>(v); };
  table.push_back(file);

  for (InertiaSpec& spec : output_options(&InertiaRepairRequest::output, {"output"},
                                   {"Write the repaired JSON or URDF to FILE instead of stdout (a URDF's report goes "
                                    "to stderr)"})) {
    table.push_back(std::move(spec));
  }

  InertiaSpec floor = spdfit::detail::option_entry<InertiaRepairRequest>(
      "min_eig_rel", "--min-eig-rel", "min_eig_rel", OptionType::Real, "NUMBER",
      "Floor of the second moments as a fraction of the largest: each principal moment stays below the sum of the "
      "other two by twice that (kept through 7 printed digits; 0: the plain projection)",
      "1e-6");
  floor.range = {0.0, 1.0, false, true};
  floor.set = [](InertiaRepairRequest& r, const OptionValue& v) { r.options.min_eig_rel = std::get<double>(v); };
  floor.get = [](const InertiaRepairRequest& r) -> std::optional<OptionValue> { return r.options.min_eig_rel; };
  table.push_back(floor);

  InertiaSpec metric = physical::detail::choice_option<InertiaRepairRequest>(
      "metric", "--metric", "metric", {"inertia", "second-moment"},
      "The distance minimized: inertia (||I' - I||_F, the distance reported) or second-moment (the eigenvalue "
      "clip of the second moment about the centre of mass)",
      "inertia");
  metric.nullable = false;
  metric.set = [](InertiaRepairRequest& r, const OptionValue& v) {
    r.options.metric = *parse_inertia_metric(std::get<std::string>(v));
  };
  metric.get = [](const InertiaRepairRequest& r) -> std::optional<OptionValue> {
    return std::string(to_string(r.options.metric));
  };
  table.push_back(metric);
  return table;
}

}  // namespace

const std::vector<OptionSpec<InertiaRepairRequest>>& inertia_repair_option_table() {
  static const std::vector<OptionSpec<InertiaRepairRequest>> table = make_inertia_table();
  return table;
}

bool is_urdf_path(std::string_view path) {
  std::string lower(path);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  auto ends_with = [&lower](std::string_view tail) {
    return lower.size() >= tail.size() && lower.compare(lower.size() - tail.size(), tail.size(), tail) == 0;
  };
  return ends_with(".urdf") || ends_with(".xml");
}

InertiaRepairRun run_inertia_repair(const InertiaRepairRequest& request) {
  InertiaRepairRun run;
  if (is_urdf_path(request.input)) {
    run.urdf = repair_urdf_file(request.input, request.options);
  } else {
    run.body = repair_inertia(read_rigid_body(request.input), request.options);
  }
  return run;
}

}  // namespace spdfit
