// spdfit linkage synthesize ... / spdfit linkage analyze ...: four-bar function generators.
// Registration of the options; the actions are in linkage_synthesize.cpp and linkage_analyze.cpp.
#include <memory>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "linkage_commands.hpp"
#include "validators.hpp"
#include "spdfit/linkage/prescribed_function.hpp"

namespace spdfit::cli {

Command add_linkage_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* linkage = app.add_subcommand("linkage", "Four-bar function generators: synthesize from pairs, analyze");
  linkage->require_subcommand(1);

  auto so = std::make_shared<SynthesizeOptionsCli>();
  CLI::App* syn = linkage->add_subcommand(
      "synthesize", "Synthesize a four-bar function generator (Freudenstein): design error, then structural error");
  syn->add_option("--pairs", so->pairs, "File of input-output pairs: columns psi, phi (degrees; a header row allowed)");
  syn->add_option("--weights", so->weights, "File of one positive weight per pair (W in 1/2 d^T W d)");
  syn->add_flag("--radians", so->radians, "The --pairs angles are in radians");
  syn->add_flag("--steering", so->steering, "Prescribe the steering condition (eq. 3.5); needs --rho");
  syn->add_option("--rho", so->rho, "Steering: track / wheelbase (e.g. 0.5)");
  syn->add_option("--function", so->function, "Prescribe y = f(x): linear, square, cube, sqrt, reciprocal, exp, ln, "
                                               "log10, sin, cos, tan")
      ->check(CLI::IsMember(linkage::function_names()));
  syn->add_option("--x-range", so->x_range, "--function: the x range LO:HI");
  syn->add_option("--psi-range", so->psi_range,
                  "Input angle changes LO:HI (degrees) from the dial zero (--steering default -30:30)");
  syn->add_option("--phi-range", so->phi_range, "--function: output angle changes LO:HI (degrees)");
  syn->add_option("--points", so->points, "Number of prescribed positions (default 21)");
  syn->add_option("--spacing", so->spacing, "Input spacing: uniform (default) or chebyshev")
      ->check(CLI::IsMember({"uniform", "chebyshev"}));
  syn->add_option("--alpha", so->alpha,
                  "Input dial zero (degrees): psi = alpha + delta psi (default 0; --steering: 90 - atan(rho/2))");
  syn->add_option("--beta", so->beta,
                  "Output dial zero (degrees): phi = beta + delta phi (default 0; --steering: 90 + atan(rho/2))");
  syn->add_flag("--fit-dial-zeros", so->fit_dial_zeros,
                "Also solve for alpha and beta (eq. 3.7); --alpha/--beta are then the start");
  syn->add_option("--tolerance", so->tolerance, "Gauss-Newton stops when ||Delta k|| < this (default 1e-10)")
      ->check(CLI::PositiveNumber);
  syn->add_option("--max-iterations", so->max_iterations, "Gauss-Newton iteration limit (default 100)")
      ->check(CLI::PositiveNumber);
  syn->add_option("--threshold", so->threshold,
                  "Relative singular-value cut-off for S (default max(m,3)*eps, notes 3.8)")
      ->check(rank_tolerance());
  syn->add_flag("--positions", so->positions, "Also print every position: prescribed and generated phi");
  syn->add_flag("--json", so->json, "Print the result as JSON");
  syn->add_option("-o,--output", so->output, "Write to FILE instead of stdout");

  auto ao = std::make_shared<AnalyzeOptionsCli>();
  CLI::App* ana = linkage->add_subcommand(
      "analyze", "Output angle on both assembly branches, transmission angle and dead points of a four-bar");
  ana->add_option("--lengths", ao->lengths, "a1,a2,a3,a4: ground, input, coupler, output")->required();
  ana->add_option("--psi-range", ao->psi_range, "Input angles LO:HI in degrees (default 0:360)");
  ana->add_option("--points", ao->points, "Number of input angles (default 37)");
  ana->add_flag("--json", ao->json, "Print the analysis as JSON");
  ana->add_option("-o,--output", ao->output, "Write to FILE instead of stdout");

  auto run = [so, ao, syn, ana, &global]() {
    if (so->threshold >= 1.0) throw UsageError("--threshold must be below 1");
    if (syn->parsed()) run_synthesize(*so, global);
    if (ana->parsed()) run_analyze(*ao);
  };
  return {linkage, run};
}

}  // namespace spdfit::cli
