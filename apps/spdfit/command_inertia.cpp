// spdfit inertia repair [--min-eig-rel R] [-o FILE] FILE: the nearest physically consistent
// rigid-body inertia, for a JSON body or every link of a URDF file.
#include <algorithm>
#include <cctype>
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "output.hpp"
#include "validators.hpp"
#include "spdfit/inertia_repair.hpp"

namespace spdfit::cli {

namespace {

struct InertiaRepairCli {
  std::string input, output;
  std::string metric = std::string(to_string(InertiaRepairOptions{}.metric));
  double min_eig_rel = InertiaRepairOptions{}.min_eig_rel;
};

// URDF files are XML: .urdf or .xml (any case); anything else is read as a JSON body.
bool is_urdf(const std::string& path) {
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  auto ends_with = [&lower](const std::string& tail) {
    return lower.size() >= tail.size() && lower.compare(lower.size() - tail.size(), tail.size(), tail) == 0;
  };
  return ends_with(".urdf") || ends_with(".xml");
}

}  // namespace

Command add_inertia_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* inertia = app.add_subcommand("inertia", "Rigid-body inertias: repair physically inconsistent ones");
  inertia->require_subcommand(1);
  auto options = std::make_shared<InertiaRepairCli>();
  CLI::App* repair = inertia->add_subcommand(
      "repair",
      "The nearest physically consistent inertia (mass and centre of mass kept): FILE is JSON "
      "{\"mass\", \"center_of_mass\", \"inertia\"} (SI, about the centre of mass; or the --json of hexapod identify "
      "--physical or payload identify) or a URDF file (.urdf, .xml), whose every link's <inertial> is checked");
  repair->add_option("FILE", options->input, "A JSON body or a URDF file")->required();
  repair->add_option("-o,--output", options->output,
                     "Write the repaired JSON or URDF to FILE instead of stdout (a URDF's report goes to stderr)");
  repair->add_option("--min-eig-rel", options->min_eig_rel,
                     "Floor of the second moments as a fraction of the largest: each principal moment stays below "
                     "the sum of the other two by twice that (default 1e-6, kept through 7 printed digits; 0: the "
                     "plain projection)")
      ->check(relative_floor());
  repair->add_option("--metric", options->metric,
                     "The distance minimized: inertia (||I' - I||_F, the distance reported; default) or "
                     "second-moment (the eigenvalue clip of the second moment about the centre of mass)")
      ->check(CLI::IsMember({"inertia", "second-moment"}));

  auto run = [options, &global]() {
    InertiaRepairOptions repair_options;
    repair_options.min_eig_rel = options->min_eig_rel;
    repair_options.metric = *parse_inertia_metric(options->metric);
    if (is_urdf(options->input)) {
      const UrdfRepairResult result = repair_urdf_file(options->input, repair_options);
      std::cerr << urdf_repair_report(result);
      emit(result.text, options->output);
    } else {
      const InertiaRepairResult result = repair_inertia(read_rigid_body(options->input), repair_options);
      for (const Warning& w : result.warnings) warn(global, w);
      emit(inertia_repair_json(result), options->output);
    }
  };
  return {inertia, run};
}

}  // namespace spdfit::cli
