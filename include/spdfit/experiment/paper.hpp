// The two experiments of Chen & McInroy, section IV (shared/seeds/001): the hexapod's 21
// parameters (Figure 2) and the 2x2 example (Figure 3), as Monte Carlo experiments.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "spdfit/experiment/monte_carlo.hpp"
#include "spdfit/experiment/statistics.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/method.hpp"

namespace spdfit::experiment {

/// Per-entry error statistics of several methods over the same trials.
struct EntryExperimentResult {
  std::size_t trials = 0;
  std::uint64_t seed = 0;
  Eigen::MatrixXd truth;
  std::vector<std::pair<Eigen::Index, Eigen::Index>> entries;  ///< upper_triangle_entries(n)
  std::vector<EntryStatistics> methods;

  /// The statistics of `method`; throws std::invalid_argument when it was not run.
  const EntryStatistics& of(Method method) const;

  /// Method a against b on each entry (in `entries`' order), trial by trial: compare_paired of
  /// the absolute errors |e_a| and |e_b|. Throws std::invalid_argument for a method not run.
  /// Cost O(trials x entries).
  std::vector<PairedComparison> compare(Method a, Method b) const;

  /// On how many entries a has the smaller mean absolute error than b, and on how many the
  /// smaller standard deviation of the error (the paper's Figure 2 read entry by entry).
  struct Wins {
    std::size_t mae = 0, std = 0;
    std::size_t entries = 0;  ///< of how many
  };
  Wins wins(Method a, Method b) const;
};

// ---- Figure 2: the hexapod -------------------------------------------------------------------

/// The paper's hexapod experiment. The paper's data came from six load cells and six
/// accelerometers on a UW hexapod, whose noise levels it does not give; the default here is
/// the thesis generator at its Experiment 2 level (V = 0.86, m = 12, uniform noise).
struct PaperHexapodOptions {
  hexapod::SimulationOptions simulation = default_simulation();
  Eigen::MatrixXd truth;  ///< empty: thesis_mass_matrix() (eq. 6.1; the paper's M is its rounding)
  /// The paper compares least squares (symmetric Procrustes, Higham's method [4]) with SPDE.
  std::vector<Method> methods = {Method::SymmetricProcrustes, Method::Spde};

  static hexapod::SimulationOptions default_simulation() {
    hexapod::SimulationOptions s;
    s.noise_var = 0.86;
    return s;
  }
};

/// For each of the 21 independent entries of M_p, the statistics of each method's estimation
/// error over the trials (the paper used 100). Throws std::invalid_argument on invalid
/// options. Cost O(trials (m n^2 + n^3)).
EntryExperimentResult run_paper_hexapod(const PaperHexapodOptions& options,
                                        const MonteCarloOptions& monte_carlo);

// ---- Figure 3: the 2x2 example ---------------------------------------------------------------

/// The paper's 2x2 example: X = [3 1; 1 1], A0 = [5 -3 1 -1; 2 1 -2 1]^T (4x2), B0 = A0 X;
/// A = A0 + noise of standard deviation std_a, B = B0 + noise of standard deviation std_b,
/// Gaussian, independent in every entry.
struct Paper2x2Options {
  double std_a = 0.0;
  double std_b = 1.0;
  /// procrustes, tls (not symmetrized: the paper's footnote 2) and spde.
  std::vector<Method> methods = {Method::SymmetricProcrustes, Method::TotalLeastSquares, Method::Spde};
};

/// X and A0 of the paper's 2x2 example.
Eigen::MatrixXd paper_2x2_truth();
Eigen::MatrixXd paper_2x2_design();

/// The 2x2 example at one noise level: statistics of the errors in x11, x12, x22 (the paper
/// used 10,000 trials). A's noise is drawn before B's, column by column. Throws
/// std::invalid_argument on invalid options (negative or non-finite deviations).
EntryExperimentResult run_paper_2x2(const Paper2x2Options& options, const MonteCarloOptions& monte_carlo);

/// The levels of the paper's Figure 3: std_a = 0, 0.1, ..., 1.9.
std::vector<double> paper_2x2_sweep_levels();

/// run_paper_2x2 at every level of `std_a_levels`, all with the same seed: trial k draws the
/// same standard normal numbers at every level (common random numbers), so differences between
/// levels are due to the noise level, not to the draw.
std::vector<EntryExperimentResult> run_paper_2x2_sweep(const Paper2x2Options& options,
                                                       const std::vector<double>& std_a_levels,
                                                       const MonteCarloOptions& monte_carlo);

}  // namespace spdfit::experiment
