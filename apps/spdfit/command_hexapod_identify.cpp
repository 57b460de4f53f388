// spdfit hexapod identify A B [--truth T] [--geometry G | --stiffness K] [--physical
// [--fit-strut-mass common|each]] [--bootstrap N] [--json]: M_p identified from measured
// accelerations and forces by every estimator, and with --physical the payload's mass properties.
#include <CLI/CLI.hpp>
#include <memory>
#include <sstream>

#include "bootstrap_options.hpp"
#include "hexapod_commands.hpp"
#include "input.hpp"
#include "output.hpp"
#include "spdfit/fit_request.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/identify.hpp"
#include "spdfit/hexapod/physical_request.hpp"
#include "spdfit/hexapod/render.hpp"
#include "spdfit/inertia_repair.hpp"
#include "spdfit/io.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

namespace {

Eigen::MatrixXd parse_stiffness(const std::string& text, Eigen::Index n) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string field;
  while (std::getline(in, field, ',')) {
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || field.find_first_not_of(" \t", used) != std::string::npos || !(value >= 0.0)) {
      throw UsageError("--stiffness: '" + field + "' is not a non-negative number");
    }
    values.push_back(value);
  }
  if (values.size() == 1) values.assign(static_cast<std::size_t>(n), values.front());
  if (values.size() != static_cast<std::size_t>(n)) {
    throw UsageError("--stiffness: give one number or " + std::to_string(n) +
                     " comma-separated numbers, not " + std::to_string(values.size()));
  }
  return Eigen::Map<const Eigen::VectorXd>(values.data(), n).asDiagonal();
}

}  // namespace

Command add_hexapod_identify(CLI::App& parent, const GlobalOptions& global) {
  struct Cli {
    std::string a_path, b_path, truth, geometry, stiffness, output, urdf;
    int precision = 9;
    bool json = false, physical = false;
    BootstrapCli bootstrap;
    std::unique_ptr<TableOptions<hexapod::PhysicalOptions>> physical_options;
    std::unique_ptr<TableOptions<FitRequest>> fit_options;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* sub = parent.add_subcommand(
      "identify", "Identify M_p from accelerations A and base forces B (B ~= A M_p) with every estimator");
  sub->add_option("A", cli->a_path, "File of payload accelerations along the struts (m x 6)")->required();
  sub->add_option("B", cli->b_path,
                  "File of base forces (m x 6). Without it, --a-cols and --b-cols choose the columns of the "
                  "accelerations and the forces in A's file");
  sub->add_option("--truth", cli->truth, "File of the true M_p, to report each method's error");
  auto* geometry =
      sub->add_option("--geometry", cli->geometry, "Geometry file whose strut stiffness gives the modes");
  auto* stiffness =
      sub->add_option("--stiffness", cli->stiffness,
                      "Strut stiffness (N/m) for the modes: one number, or one per strut, comma-separated");
  stiffness->excludes(geometry);
  sub->add_flag("--physical", cli->physical,
                "Also fit the payload's mass, centre of mass and inertia (physically consistent) with the "
                "Jacobian of --geometry known, each beside the geometry's nominal value");
  cli->physical_options =
      std::make_unique<TableOptions<hexapod::PhysicalOptions>>(*sub, hexapod::physical_option_table());
  // The fit's iteration limit and rank cut-off, for every estimator and the physical fit alike, and
  // the noise (its ratio or a noise model), for every estimator.
  std::vector<std::string_view> here = noise_option_names();
  here.insert(here.end(), {"max_iterations", "rank_tolerance", "a_cols", "b_cols"});
  cli->fit_options = std::make_unique<TableOptions<FitRequest>>(*sub, fit_option_table(),
                                                                all_but(fit_option_table(), here));
  auto* urdf = sub->add_option("--urdf", cli->urdf,
                               "With --physical: also write the payload as a URDF <link> with its <inertial> to FILE");
  sub->add_option("--precision", cli->precision, "Significant digits of --urdf's numbers (default 9)")
      ->check(CLI::Range(1, 17))
      ->needs(urdf);
  sub->add_flag("--json", cli->json, "Print every result as JSON");
  sub->add_option("-o,--output", cli->output, "Write to FILE instead of stdout");
  add_bootstrap_options(*sub, cli->bootstrap,
                        "each method's standard errors and the intervals of its eigenvalues and modes",
                        "Threads for --bootstrap (default: one per core)");

  auto run = [cli, &global]() {
    FitRequest request;
    apply_bootstrap_options(cli->bootstrap, request.options);
    request.read = global.read;
    cli->fit_options->apply(request);
    const DataPair data = load_pair(cli->a_path, cli->b_path, request, global);
    const Eigen::Index n = data.A.cols();
    if (data.B.cols() != n) {
      throw io::DataError(cli->b_path.empty() ? cli->a_path : cli->b_path, 0, 0,
                          "B has " + std::to_string(data.B.cols()) + " columns but A (" + cli->a_path + ") has " +
                              std::to_string(n) + ": the mass-inertia matrix is square, so forces and "
                                                   "accelerations need the same struts");
    }
    hexapod::IdentifyOptions options;
    if (!cli->truth.empty()) {
      options.truth = load_matrix(cli->truth, global);
      if (options.truth->rows() != n || options.truth->cols() != n) {
        throw io::DataError(cli->truth, 0, 0,
                            "the true M_p must be " + std::to_string(n) + "x" + std::to_string(n));
      }
    }
    const std::vector<std::string_view> physical_given = cli->physical_options->given();
    if (!cli->physical && !physical_given.empty()) {
      throw UsageError(spell_option(physical_given.front(), Frontend::Cli) + " needs --physical");
    }
    if (!cli->urdf.empty() && !cli->physical) throw UsageError("--urdf needs --physical: it writes the payload's fit");
    if (cli->physical && cli->geometry.empty()) {
      throw UsageError(
          "--physical needs --geometry: the Jacobian and the nominal payload come from the geometry file");
    }
    hexapod::Geometry geometry;
    if (!cli->geometry.empty()) {
      geometry = hexapod::read_geometry(cli->geometry);
      if (n != 6)
        throw io::DataError(cli->a_path, 0, 0, "a hexapod geometry needs data with 6 columns (struts)");
      options.stiffness = Eigen::MatrixXd(geometry.strut_stiffness.asDiagonal());
    } else if (!cli->stiffness.empty()) {
      options.stiffness = parse_stiffness(cli->stiffness, n);
    }
    check_fit_options(request, cli->fit_options->given());
    options.fit = resolved_fit_options(request, n, n);
    hexapod::PhysicalOptions physical_options;
    cli->physical_options->apply(physical_options);
    hexapod::apply_fit_options(options.fit, cli->fit_options->given(), physical_options);
    const std::vector<hexapod::MethodIdentification> methods = hexapod::identify(data.A, data.B, options);
    for (const hexapod::MethodIdentification& m : methods) {
      for (const std::string& w : m.result.warnings)
        warn(global, std::string(to_string(m.result.method)) + ": " + w);
    }
    if (!cli->physical) {
      emit(cli->json ? hexapod::to_json(methods, options) : hexapod::report(methods, options), cli->output);
      return;
    }
    // A parameter the geometry confounds, or data that cannot identify one: std::invalid_argument
    // naming it, a data error.
    const hexapod::PhysicalEstimate physical =
        hexapod::identify_physical(data.A, data.B, geometry, physical_options);
    for (const std::string& w : physical.warnings) warn(global, "physical: " + w);
    emit(cli->json ? hexapod::to_json(methods, options, physical)
                   : hexapod::report(methods, options, physical, geometry),
         cli->output);
    // The report says why too; the exit status tells a script that the fit asked for failed.
    if (!physical.ok()) throw DataFailure("the physical fit failed: " + physical.message);
    if (!cli->urdf.empty()) io::write_text(cli->urdf, urdf_link(physical.payload, "payload", cli->precision));
  };
  return {sub, run};
}

}  // namespace spdfit::cli
