// Simulated hexapod measurements: the thesis' data generator (000, appendix B; chapter 6).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "spdfit/hexapod/geometry.hpp"
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

  /// True when usable (samples >= 1, noise_var and force_noise_var >= 0, signal_var > 0, all
  /// finite); otherwise `error` says why.
  bool is_valid(std::string* error = nullptr) const;
};

/// One simulated experiment: measured and true payload accelerations and base forces.
struct Measurements {
  Eigen::MatrixXd A;       ///< measured accelerations along the struts, m x n (eq. 6.3)
  Eigen::MatrixXd B;       ///< measured base forces, m x n (eq. 6.4)
  Eigen::MatrixXd A_true;  ///< true accelerations
  Eigen::MatrixXd B_true;  ///< true forces A_true M (eq. 6.2 in row form, f_b^T = p_ddot^T M)
};

/// The thesis generator (appendix B): A_true uniform with variance S; B_true = A_true M;
/// A = A_true + noise, B = B_true + noise, with independent noise of variance V in every
/// entry (of variance force_noise_var in B, when given). Draws in the M-file's order (A_true, A's noise, B's
/// noise), each matrix column by column as MATLAB's rand([m, n]) fills it, from `random` (so the numbers are
/// reproducible; see Random). `truth` is n x n; the thesis' is thesis_mass_matrix().
///
/// Throws std::invalid_argument when the options are invalid or `truth` is not square.
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

/// simulate() of a hexapod whose true payload differs from the geometry's nominal one: the truth
/// is joint_space_mass_matrix(geometry, payload) (model.hpp; the payload's centre of mass offset
/// from {P}'s origin and its inertia about it), so that physical identification
/// (hexapod/physical.hpp) has a payload to recover that the geometry file does not state. Same
/// draws as simulate(truth, options, seed). Throws std::invalid_argument for an invalid geometry
/// or a payload that is not well formed (is_well_formed). Cost O(m n^2).
Measurements simulate(const Geometry& geometry, const RigidBodyInertia& payload, const SimulationOptions& options,
                      std::uint64_t seed);

}  // namespace spdfit::hexapod
