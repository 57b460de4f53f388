// `spdfit linkage synthesize`: the request (one source of prescribed positions: a pairs file, the
// steering condition or a function; dial zeros; the solver's options), its option table, the
// workflow (the rules of which options go together, the files read) and its renderings.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "spdfit/linkage/prescribed_function.hpp"
#include "spdfit/linkage/synthesis.hpp"
#include "spdfit/options.hpp"
#include "spdfit/output_request.hpp"

namespace spdfit::linkage {

/// The input angle changes of `steering` when `psi_range` is not given (degrees).
inline constexpr double kSteeringPsiRange[2] = {-30.0, 30.0};

/// What `linkage synthesize` fits. Angles in degrees, as the command line takes them (the pairs
/// file's in radians with `radians`).
struct SynthesizeRequest {
  /// The prescribed pairs: a file of psi, phi columns (the command line) or an m x 2 matrix
  /// (Python: psi and phi), angle changes in degrees (radians with `radians`).
  MatrixInput pairs;
  MatrixInput weights;  ///< one positive weight per pair: a file, or a vector
  bool radians = false;
  bool steering = false;
  std::optional<double> rho;
  std::string function;
  std::string x_range, psi_range, phi_range;  ///< "LO:HI"
  int points = 21;
  Spacing spacing = Spacing::Uniform;
  std::optional<double> alpha, beta;
  bool fit_dial_zeros = false;
  bool refine = true;  ///< refine the design solution by Gauss-Newton on the structural error
  double tolerance = 1e-10;
  int max_iterations = 100;
  std::optional<double> threshold;
  bool positions = false;  ///< the report lists every position
  OutputRequest output;    ///< json, output
};

/// The options of `linkage synthesize`.
const std::vector<OptionSpec<SynthesizeRequest>>& synthesize_option_table();

/// The prescribed positions and what came of them.
struct SynthesisRun {
  SynthesisResult result;
  PrescribedPairs pairs;    ///< radians, changes from the dial zeros
  Eigen::VectorXd weights;  ///< empty: unweighted
  std::string source;       ///< the pairs' file, or what generated them
};

/// The workflow of `linkage synthesize`: the rules of the request (exactly one source; what each
/// source takes; ranges LO < HI), as OptionError naming the options; the pairs and weights read
/// (io::DataError naming the file); the synthesis. `given`: the library names of the options given.
SynthesisRun run_synthesize(const SynthesizeRequest& request, const std::vector<std::string_view>& given);

/// `linkage synthesize --json`.
std::string to_json(const SynthesisRun& run);

/// `linkage synthesize`'s report; with `positions` every position, prescribed and generated.
std::string report(const SynthesisRun& run, bool positions);

}  // namespace spdfit::linkage
