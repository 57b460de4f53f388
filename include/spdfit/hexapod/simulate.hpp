// Simulated hexapod measurements: the thesis' data generator (000, appendix B; chapter 6).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/noise_model.hpp"
#include "spdfit/random.hpp"
#include "spdfit/rigid_body.hpp"

namespace spdfit::hexapod {

/// The joint-space mass-inertia matrix of UW's hexapod (thesis eq. 6.1; kg), the truth of the
/// thesis' experiments. (The appendix-B M-file's copy is garbled; eq. 6.1 is right.)
Eigen::MatrixXd thesis_mass_matrix();

/// The distribution of the measurement noise.
enum class NoiseDistribution {
  Uniform,   ///< uniform on [-sqrt(3 V), sqrt(3 V)], as the thesis' M-file (nm (rand - 0.5))
  Gaussian,  ///< normal with variance V
};

/// "uniform" or "gaussian".
std::string_view to_string(NoiseDistribution distribution);
std::optional<NoiseDistribution> parse_noise_distribution(std::string_view name);

/// The generator's settings. The defaults are the thesis' chapter-6 set-up.
struct SimulationOptions {
  Eigen::Index samples = 12;  ///< m, rows of A and B
  double noise_var = 0.0;     ///< V: variance of the noise in every entry of A (and of B)
  /// Variance of the noise in B when it differs from A's (force and acceleration sensors
  /// seldom share a noise level); nothing means noise_var, as in the thesis.
  std::optional<double> force_noise_var;
  /// S: variance of the true accelerations, uniform on [-sqrt(3 S), sqrt(3 S)]. The thesis
  /// draws 10 (rand - 0.5), uniform on [-5, 5]: S = 25/3 (its text rounds this to 8.2).
  double signal_var = 25.0 / 3.0;
  NoiseDistribution distribution = NoiseDistribution::Uniform;
  /// Standard deviations of the noise in A, one for every column or one for all (then noise_var
  /// must be 0): sensors with noise levels of their own. 0 means exact.
  std::optional<Eigen::VectorXd> noise_std_a;
  /// The same for B (then force_noise_var must be unset), in B's units before scale_b.
  std::optional<Eigen::VectorXd> noise_std_b;
  /// Rows recorded at rest, drawn after the data (Measurements::rest_A, rest_B): zero accelerations
  /// plus A's noise, and the static load rest_force plus B's noise. 0: none.
  Eigen::Index rest_samples = 0;
  /// A static load (a preload: forces logged untared) in every row of B, moving or at rest, as real
  /// logs have it (one value per column of B, before scale_b); empty (the default): none, the rest
  /// rows of B then noise about 0. Its value does not change the rest rows' covariance, only the
  /// means of B's columns (FitOptions::offsets Rest subtracts it).
  Eigen::VectorXd rest_force;
  /// A change of B's units: B, B_true and the rest rows of B are multiplied by this after they are
  /// drawn (1e-3: newtons to kilonewtons), so that the true X is truth * scale_b. 1: none.
  double scale_b = 1.0;

  /// True when usable (samples >= 1, noise_var and force_noise_var >= 0, signal_var > 0, all
  /// finite; standard deviations finite and >= 0, not together with noise_var != 0 or
  /// force_noise_var; rest_samples >= 0; rest_force finite; scale_b finite and > 0); otherwise
  /// `error` says why. The sizes of noise_std_a, noise_std_b and rest_force are checked against
  /// the truth by simulate.
  bool is_valid(std::string* error = nullptr) const;
};

/// One simulated experiment: measured and true payload accelerations and base forces.
struct Measurements {
  Eigen::MatrixXd A;       ///< measured accelerations along the struts, m x n (eq. 6.3)
  Eigen::MatrixXd B;       ///< measured base forces, m x n (eq. 6.4)
  Eigen::MatrixXd A_true;  ///< true accelerations
  Eigen::MatrixXd B_true;  ///< true forces A_true M (eq. 6.2 in row form, f_b^T = p_ddot^T M)
  /// With SimulationOptions::rest_samples = N > 0: N rows recorded at rest (accelerations zero,
  /// forces constant) with the data's noise; empty otherwise.
  Eigen::MatrixXd rest_A, rest_B;
};

/// The thesis generator (appendix B): A_true uniform with variance S; B_true = A_true M;
/// A = A_true + noise, B = B_true + noise, with independent noise of variance V in every
/// entry (of variance force_noise_var in B, when given; of the standard deviations noise_std_a,
/// noise_std_b per column, when given). Draws in the M-file's order (A_true, A's noise, B's
/// noise), each matrix column by column as MATLAB's rand([m, n]) fills it, then the rest rows
/// (rest_A's noise, rest_B's noise), from `random` (so the numbers are reproducible; see Random).
/// Finally B, B_true and rest_B are multiplied by scale_b. `truth` is n x n; the thesis' is
/// thesis_mass_matrix().
///
/// Throws std::invalid_argument when the options are invalid, `truth` is not square, or
/// noise_std_a, noise_std_b or rest_force has a size other than 1 (rest_force: n) or n.
/// Cost O(m n^2).
Measurements simulate(const Eigen::MatrixXd& truth, const SimulationOptions& options, Random& random);

/// simulate() with the data of trial 0 of the thesis experiment for `seed`: its generator is
/// Random(trial_seed(seed, 0)), so `spdfit hexapod simulate --seed S` and Python's
/// spdfit.hexapod.simulate(seed=S) give what `spdfit experiment thesis --seed S` draws first.
Measurements simulate(const Eigen::MatrixXd& truth, const SimulationOptions& options, std::uint64_t seed);

/// simulate() into `out`, reusing its matrices' storage: a Monte Carlo loop that keeps `out`
/// allocates nothing per trial. Same numbers, same errors.
void simulate_into(const Eigen::MatrixXd& truth, const SimulationOptions& options, Random& random,
                   Measurements& out);

/// Adds independent noise of variance `variance` to every entry of `out` (any shape), column
/// by column. Draws as many numbers for variance 0 as for any other.
void add_noise(Eigen::MatrixXd& out, double variance, NoiseDistribution distribution, Random& random);

/// Adds independent noise of standard deviation std_dev(j) to every entry of column j of `out`
/// (std_dev of length 1: the same for every column), column by column as add_noise draws.
void add_noise(Eigen::MatrixXd& out, const Eigen::VectorXd& std_dev, NoiseDistribution distribution, Random& random);

/// The noise model of the generator for data with n columns (A and B): Sigma_A = diag(std_a^2)
/// (noise_var I without noise_std_a), Sigma_B = diag(std_b^2) scale_b^2 (force_noise_var or
/// noise_var without noise_std_b), as standard deviations (NoiseSource::Std): the true covariances
/// that a fit given them knows. Throws std::invalid_argument when the options are invalid or a
/// size is not 1 or n.
NoiseModel true_noise_model(const SimulationOptions& options, Eigen::Index n);

/// simulate() of a hexapod whose true payload differs from the geometry's nominal one: the truth
/// is joint_space_mass_matrix(geometry, payload) (model.hpp; the payload's centre of mass offset
/// from {P}'s origin and its inertia about it), so that physical identification
/// (hexapod/physical.hpp) has a payload to recover that the geometry file does not state. Same
/// draws as simulate(truth, options, seed). Throws std::invalid_argument for an invalid geometry
/// or a payload that is not well formed (is_well_formed). Cost O(m n^2).
Measurements simulate(const Geometry& geometry, const RigidBodyInertia& payload, const SimulationOptions& options,
                      std::uint64_t seed);

}  // namespace spdfit::hexapod
