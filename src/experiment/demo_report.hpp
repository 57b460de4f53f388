// The report of `spdfit demo`: its tables (demo_tables.cpp) and the explanation drawn from
// them (demo_findings.cpp).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "spdfit/experiment/paper.hpp"
#include "spdfit/experiment/physical.hpp"
#include "spdfit/experiment/thesis.hpp"

namespace spdfit::experiment::demo {

/// What the demo runs.
struct Results {
  std::uint64_t seed = 1;
  std::vector<experiment::ThesisExperimentResult> thesis;   ///< Experiments 1-3 (m = 12)
  std::vector<experiment::ThesisExperimentResult> samples;  ///< Experiment 2 at sample_sizes()
  std::vector<experiment::EntryExperimentResult> paper;     ///< the 2x2 example at levels_2x2()
  /// Beyond the seeds: every (width, m) of beyond_widths() x beyond_sizes(), widths outer,
  /// running beyond_methods().
  std::vector<experiment::ThesisExperimentResult> beyond;
  /// Section 6: physical identification of the payload against the generic methods.
  std::optional<experiment::PhysicalExperimentResult> physical;
  /// Section 7, units and noise: units_options() fitted without a noise model and with the rest
  /// segment's.
  experiment::ThesisExperimentResult units;
};

/// Section 6's sample sizes (its other settings are the physical experiment's defaults).
const std::vector<Eigen::Index>& physical_sizes();

/// Section 7's experiment: per-sensor Gaussian noise, B in kN, a rest segment; auto and spd-tls
/// fitted assuming equal noise and with the rest rows' covariances.
experiment::ThesisExperimentOptions units_options();

/// Section 5's uniform noise widths nm (variance nm^2 / 12), sample sizes and methods.
const std::vector<double>& beyond_widths();
const std::vector<Eigen::Index>& beyond_sizes();
const std::vector<Method>& beyond_methods();
/// beyond_methods() but auto: the methods auto is measured against.
const std::vector<Method>& beyond_estimators();

/// The 2x2 example's noise levels std_a, and the larger sample sizes Experiment 2 is rerun at.
const std::vector<double>& levels_2x2();
const std::vector<Eigen::Index>& sample_sizes();

/// Sections 1-7: the built-in hexapod, the thesis' experiments, the 2x2 example, more samples,
/// the methods beyond the seeds against m, physical identification of the payload (6), and units
/// and noise (7).
std::string tables(const Results& results);

/// "What the numbers show": each statement chosen by comparing the numbers in `results`.
std::string findings(const Results& results);

/// Text helpers shared by both: `text` wrapped at kWidth columns (the first line starting with
/// `first`, the others with `rest`); a "* " bullet; "12%" (spdfit/format.hpp formats the numbers).
inline constexpr std::size_t kWidth = 98;
std::string wrap(const std::string& text, const std::string& first = "", const std::string& rest = "");
std::string bullet(const std::string& text);
std::string percent(double fraction);

}  // namespace spdfit::experiment::demo
