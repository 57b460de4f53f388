// The physical-identification experiment: on the thesis' set-up (built-in hexapod, appendix-B
// generator), the error of M_p from the payload's mass properties (hexapod/physical.hpp) against
// the generic SPD estimators, over m, with how often each estimate is physically consistent.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "spdfit/experiment/monte_carlo.hpp"
#include "spdfit/experiment/statistics.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/physical.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/method.hpp"
#include "spdfit/rigid_body.hpp"

namespace spdfit::experiment {

/// A physical-identification fit the experiment runs beside the generic methods.
struct PhysicalVariant {
  std::string name;
  hexapod::PhysicalCriterion criterion = hexapod::PhysicalCriterion::ErrorsInVariables;
  bool consistent = true;
  hexapod::StrutMasses strut_masses = hexapod::StrutMasses::Geometry;
};

/// The variants by name, strut masses from the geometry: "physical" (errors in variables,
/// consistent: spdfit's estimator), "physical-ls" (least squares, consistent: its convex start),
/// "grey-box-tls" (errors in variables, unconstrained) and "grey-box-ls" (least squares,
/// unconstrained). A suffix ":common" or ":each" estimates the strut masses too (where the geometry
/// identifies them). Nothing for another name.
std::optional<PhysicalVariant> physical_variant(std::string_view name);

/// The four names above, for help texts and messages.
std::vector<std::string> physical_variant_names();

/// The set-up; the defaults are the table: the built-in hexapod, uniform noise of width 3.2
/// (variance 3.2^2 / 12) in every entry of A and B, m = 12, 30, 100 and 1000.
struct PhysicalExperimentOptions;

/// Sets options.methods and options.variants from names of either (a front end's --methods list,
/// in its order): generic methods (kSelectableMethods) and physical variants (physical_variant).
/// Throws std::invalid_argument naming an unknown name. Repeats are left to is_valid.
void set_estimators(PhysicalExperimentOptions& options, const std::vector<std::string>& names);

struct PhysicalExperimentOptions {
  std::optional<hexapod::Geometry> geometry;       ///< nothing: hexapod::cubic_geometry()
  std::optional<RigidBodyInertia> payload;         ///< the true payload; nothing: the geometry's nominal one
  std::vector<Eigen::Index> samples{12, 30, 100, 1000};
  hexapod::SimulationOptions simulation = [] {     ///< samples is overridden by `samples`
    hexapod::SimulationOptions s;
    s.noise_var = 3.2 * 3.2 / 12.0;
    return s;
  }();
  std::vector<Method> methods{Method::Spde, Method::SpdTotalLeastSquares};  ///< generic estimators
  std::vector<std::string> variants{"physical", "grey-box-ls", "grey-box-tls"};  ///< physical_variant names

  /// True when usable (samples >= 6 each, non-empty lists without repeats, valid simulation,
  /// known variant names, a valid geometry and payload); otherwise `error` says why.
  bool is_valid(std::string* error = nullptr) const;
};

/// One estimator's errors at one m.
struct PhysicalMethodErrors {
  std::string name;            ///< the method's or the variant's name
  std::vector<double> errors;  ///< ||M_hat - M_p||_F per trial; NaN where it failed
  Summary summary;
  /// Trials whose estimate is not physically consistent (variants: the payload's pseudo-inertia or
  /// a strut mass negative; generic methods: not positive definite).
  std::size_t inconsistent = 0;
};

struct PhysicalExperimentRow {
  Eigen::Index samples = 0;
  std::vector<PhysicalMethodErrors> methods;  ///< generic methods, then variants, in the options' order
};

struct PhysicalExperimentResult {
  PhysicalExperimentOptions options;
  Eigen::MatrixXd truth;  ///< M_p of the true payload
  std::size_t trials = 0;
  std::uint64_t seed = 0;
  std::vector<PhysicalExperimentRow> rows;  ///< one per m, in the options' order
};

/// For each m: `trials` simulations (hexapod::simulate of the true M_p with the trial's own Random:
/// trial k at m draws what `experiment thesis --samples m` draws for the same truth), each fitted
/// by the generic methods (experiment::estimate) and the variants (hexapod::identify_physical).
/// Runs on the Monte Carlo options' threads; the numbers depend only on the seed. Throws
/// std::invalid_argument on invalid options. Cost O(trials sum(m)).
PhysicalExperimentResult run_physical_experiment(const PhysicalExperimentOptions& options,
                                                 const MonteCarloOptions& monte_carlo);

/// At one m: the generic method with the lowest mean error, and the mean error of the variant
/// "physical" relative to it (the goal is <= 0.6); nothing where either is missing (no
/// generic method or no "physical" variant ran, or every trial of one failed).
struct PhysicalComparison {
  std::string best_generic;
  double ratio = 0.0;  ///< mean error of "physical" / mean error of best_generic
};
std::optional<PhysicalComparison> compare_to_generic(const PhysicalExperimentResult& result,
                                                     const PhysicalExperimentRow& row);

/// `spdfit experiment physical --json`: {"experiment": "physical", "noise_var", "force_noise_var",
/// "signal_var", "distribution", "trials", "seed", "payload" (with options.payload: {"mass",
/// "center_of_mass", "inertia"}), "truth" [6x6], "methods" (generic, then
/// variants, by name), "rows": [{"samples", "methods": {name: {"mean", "std", "median", "max",
/// "min", "standard_error", "count", "failures", "inconsistent"}}, "best_generic" and
/// "physical_ratio" (compare_to_generic, null when it has none)}]}; NaN as null. Cost O(rows
/// methods).
std::string to_json(const PhysicalExperimentResult& result);

/// The experiment as a table for people: one row per m, each estimator's mean error with its
/// standard error, the ratio of "physical" to the best generic method, then how many estimates
/// were not physically consistent. Cost O(rows methods).
std::string report(const PhysicalExperimentResult& result);

}  // namespace spdfit::experiment

namespace spdfit {

/// What experiment::to_json wrote, read back (spdfit/render.hpp's from_json): every key it writes;
/// std::invalid_argument naming the class and the key for another document.
template <typename T>
T from_json(const std::string& text);
template <> experiment::PhysicalExperimentResult from_json<experiment::PhysicalExperimentResult>(const std::string& text);

}  // namespace spdfit
