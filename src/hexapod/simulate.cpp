#include "spdfit/hexapod/simulate.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace spdfit::hexapod {

Eigen::MatrixXd thesis_mass_matrix() {
  Eigen::MatrixXd M(6, 6);
  // Thesis eq. (6.1), exactly as printed (symmetric). Entries that the hexapod's three-fold
  // symmetry makes equal differ by up to 4e-4 in print ((1,6) = 0.6110 but (4,5) = 0.6114).
  M << 4.6881, 0.1978, -0.4042, 1.7981, -0.4046, 0.6110,  //
      0.1978, 4.6881, 0.6110, -0.4046, 1.7981, -0.4042,   //
      -0.4042, 0.6110, 4.6881, 0.1975, -0.4042, 1.7984,   //
      1.7981, -0.4046, 0.1975, 4.6881, 0.6114, -0.4042,   //
      -0.4046, 1.7981, -0.4042, 0.6114, 4.6881, 0.1975,   //
      0.6110, -0.4042, 1.7984, -0.4042, 0.1975, 4.6881;
  return M;
}

std::string_view to_string(NoiseDistribution distribution) {
  return distribution == NoiseDistribution::Gaussian ? "gaussian" : "uniform";
}

std::optional<NoiseDistribution> parse_noise_distribution(std::string_view name) {
  if (name == "uniform") return NoiseDistribution::Uniform;
  if (name == "gaussian") return NoiseDistribution::Gaussian;
  return std::nullopt;
}

bool SimulationOptions::is_valid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (samples < 1) return fail("samples must be at least 1");
  if (!(noise_var >= 0.0) || !std::isfinite(noise_var)) return fail("noise_var must be a finite number >= 0");
  if (force_noise_var && (!(*force_noise_var >= 0.0) || !std::isfinite(*force_noise_var))) {
    return fail("force_noise_var must be a finite number >= 0");
  }
  if (!(signal_var > 0.0) || !std::isfinite(signal_var))
    return fail("signal_var must be a finite number > 0");
  return true;
}

void add_noise(Eigen::MatrixXd& out, double variance, NoiseDistribution distribution, Random& random) {
  // Column by column, as MATLAB fills rand([m, n]); Eigen's default storage is column-major,
  // so this is also memory order.
  if (distribution == NoiseDistribution::Gaussian) {
    const double sd = std::sqrt(variance);
    for (Eigen::Index j = 0; j < out.cols(); ++j)
      for (Eigen::Index i = 0; i < out.rows(); ++i) out(i, j) += sd * random.normal();
  } else {
    // nm (rand - 0.5) has variance nm^2 / 12: half-width nm / 2 = sqrt(3 V).
    const double half_width = std::sqrt(3.0 * variance);
    for (Eigen::Index j = 0; j < out.cols(); ++j)
      for (Eigen::Index i = 0; i < out.rows(); ++i) out(i, j) += random.uniform(-half_width, half_width);
  }
}

void simulate_into(const Eigen::MatrixXd& truth, const SimulationOptions& options, Random& random,
                   Measurements& out) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument("simulate: " + error);
  if (truth.rows() != truth.cols() || truth.rows() < 1) {
    throw std::invalid_argument("simulate: the true matrix must be square and non-empty");
  }
  const Eigen::Index m = options.samples, n = truth.rows();
  // lddot = 10 (rand - 0.5): uniform on [-5, 5] for the default S = 25/3.
  out.A_true.setZero(m, n);
  add_noise(out.A_true, options.signal_var, NoiseDistribution::Uniform, random);
  out.A = out.A_true;
  add_noise(out.A, options.noise_var, options.distribution, random);  // lddotm (eq. 6.3)
  out.B_true.resize(m, n);
  out.B_true.noalias() = out.A_true * truth;  // fb = lddot * Mprel (eq. 6.2)
  out.B = out.B_true;
  const double force_noise_var = options.force_noise_var.value_or(options.noise_var);
  add_noise(out.B, force_noise_var, options.distribution, random);  // fbm (eq. 6.4)
}

Measurements simulate(const Eigen::MatrixXd& truth, const SimulationOptions& options, Random& random) {
  Measurements out;
  simulate_into(truth, options, random, out);
  return out;
}

Measurements simulate(const Eigen::MatrixXd& truth, const SimulationOptions& options, std::uint64_t seed) {
  Random random(trial_seed(seed, 0));  // trial 0 of run_trials' per-trial generators
  return simulate(truth, options, random);
}

}  // namespace spdfit::hexapod
