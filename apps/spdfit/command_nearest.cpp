// spdfit nearest [--min-eig E] [--json] [--output FILE] X
#include <memory>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "input.hpp"
#include "output.hpp"
#include "spdfit/io.hpp"
#include "spdfit/nearest_spd.hpp"
#include "validators.hpp"

namespace spdfit::cli {

namespace {
struct NearestOptionsCli {
  std::string path, output;
  double min_eig = 0.0;
  bool json = false;
};
}  // namespace

Command add_nearest_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<NearestOptionsCli>();
  CLI::App* sub = app.add_subcommand(
      "nearest", "Nearest symmetric positive (semi)definite matrix to X (Higham); repairs covariances");
  sub->add_option("--min-eig", options->min_eig,
                  "Smallest eigenvalue allowed (default 0: semidefinite; > 0: strictly definite)")
      ->check(non_negative());
  sub->add_flag("--json", options->json, "Print the result and its diagnostics as JSON");
  sub->add_option("-o,--output", options->output, "Write to FILE instead of stdout");
  sub->add_option("X", options->path, "File of X (n x n): delimited text or .npy")->required();

  auto run = [options, &global]() {
    const Eigen::MatrixXd X = load_matrix(options->path);
    if (X.rows() != X.cols()) {
      throw io::DataError(options->path, 0, 0,
                          "X is " + std::to_string(X.rows()) + "x" + std::to_string(X.cols()) +
                              ": a square matrix is needed");
    }
    const NearestSpdResult result = nearest_spd(X, options->min_eig);
    if (result.clipped > 0) {
      warn(global, std::to_string(result.clipped) + " eigenvalue(s) of the symmetric part were below " +
                       io::format_double(options->min_eig) + " and were raised to it");
    }
    if (!options->json) {
      emit(matrix_csv(result.X), options->output);
      return;
    }
    nlohmann::json out;
    out["n"] = X.rows();
    out["min_eig"] = options->min_eig;
    out["X"] = matrix_json(result.X);
    out["distance"] = number_json(result.distance);
    out["clipped"] = result.clipped;
    out["min_eigenvalue_before"] = number_json(result.min_eigenvalue_before);
    emit(out.dump(2) + "\n", options->output);
  };
  return {sub, run};
}

}  // namespace spdfit::cli
