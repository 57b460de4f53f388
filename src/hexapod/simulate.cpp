#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/hexapod/simulation_warnings.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

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
  auto valid_std = [](const std::optional<Eigen::VectorXd>& s) {
    return !s || (s->size() > 0 && s->allFinite() && (s->array() >= 0.0).all());
  };
  if (!valid_std(noise_std_a)) return fail("noise_std_a must be one or more finite numbers >= 0");
  if (!valid_std(noise_std_b)) return fail("noise_std_b must be one or more finite numbers >= 0");
  if (noise_std_a && noise_var != 0.0) return fail("noise_std_a and noise_var cannot both be given");
  if (noise_std_b && force_noise_var) return fail("noise_std_b and force_noise_var cannot both be given");
  if (rest_samples < 0) return fail("rest_samples must be >= 0");
  if (!rest_force.allFinite()) return fail("rest_force must be finite");
  if (!(scale_b > 0.0) || !std::isfinite(scale_b)) return fail("scale_b must be a finite number > 0");
  return true;
}

namespace {

// The standard deviations of one side for n columns: given per column or per side, or from the
// variance.
Eigen::VectorXd side_std(const std::optional<Eigen::VectorXd>& given, double variance, Eigen::Index n,
                         const char* name) {
  if (!given) return Eigen::VectorXd::Constant(n, std::sqrt(variance));
  if (given->size() == 1) return Eigen::VectorXd::Constant(n, (*given)(0));
  if (given->size() != n) {
    throw std::invalid_argument(std::string("simulate: ") + name + " has " + std::to_string(given->size()) +
                                " values but the true matrix has " + std::to_string(n) +
                                " columns: give one for every column, or one for all");
  }
  return *given;
}

}  // namespace

NoiseModel true_noise_model(const SimulationOptions& options, Eigen::Index n) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument("simulate: " + error);
  const Eigen::VectorXd std_a = side_std(options.noise_std_a, options.noise_var, n, "noise_std_a");
  const Eigen::VectorXd std_b =
      side_std(options.noise_std_b, options.force_noise_var.value_or(options.noise_var), n, "noise_std_b");
  return NoiseModel::from_std(std_a, std_b * options.scale_b);
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

void add_noise(Eigen::MatrixXd& out, const Eigen::VectorXd& std_dev, NoiseDistribution distribution,
               Random& random) {
  for (Eigen::Index j = 0; j < out.cols(); ++j) {
    const double sd = std_dev.size() == 1 ? std_dev(0) : std_dev(j);
    if (distribution == NoiseDistribution::Gaussian) {
      for (Eigen::Index i = 0; i < out.rows(); ++i) out(i, j) += sd * random.normal();
    } else {
      const double half_width = std::sqrt(3.0) * sd;  // variance sd^2
      for (Eigen::Index i = 0; i < out.rows(); ++i) out(i, j) += random.uniform(-half_width, half_width);
    }
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
  const bool per_column_a = options.noise_std_a.has_value(), per_column_b = options.noise_std_b.has_value();
  const Eigen::VectorXd std_a =
      per_column_a ? side_std(options.noise_std_a, 0.0, n, "noise_std_a") : Eigen::VectorXd();
  const Eigen::VectorXd std_b =
      per_column_b ? side_std(options.noise_std_b, 0.0, n, "noise_std_b") : Eigen::VectorXd();
  if (options.rest_force.size() != 0 && options.rest_force.size() != n) {
    throw std::invalid_argument("simulate: rest_force has " + std::to_string(options.rest_force.size()) +
                                " values but the true matrix has " + std::to_string(n) + " columns");
  }
  const double force_noise_var = options.force_noise_var.value_or(options.noise_var);
  auto noise_a = [&](Eigen::MatrixXd& M) {
    if (per_column_a) {
      add_noise(M, std_a, options.distribution, random);
    } else {
      add_noise(M, options.noise_var, options.distribution, random);
    }
  };
  auto noise_b = [&](Eigen::MatrixXd& M) {
    if (per_column_b) {
      add_noise(M, std_b, options.distribution, random);
    } else {
      add_noise(M, force_noise_var, options.distribution, random);
    }
  };
  // lddot = 10 (rand - 0.5): uniform on [-5, 5] for the default S = 25/3.
  out.A_true.setZero(m, n);
  add_noise(out.A_true, options.signal_var, NoiseDistribution::Uniform, random);
  out.A = out.A_true;
  noise_a(out.A);  // lddotm (eq. 6.3)
  out.B_true.resize(m, n);
  out.B_true.noalias() = out.A_true * truth;  // fb = lddot * Mprel (eq. 6.2)
  out.B = out.B_true;
  // A static load (preload, untared forces) in every row, moving or at rest.
  if (options.rest_force.size() == n) out.B.rowwise() += options.rest_force.transpose();
  noise_b(out.B);  // fbm (eq. 6.4)

  // Rows at rest: the accelerations zero, the forces the static load (none: zero), each with its
  // sensor's noise.
  const Eigen::Index rest = options.rest_samples;
  out.rest_A.setZero(rest, n);
  out.rest_B.resize(rest, n);
  if (rest > 0) {
    const Eigen::VectorXd force = options.rest_force.size() == n ? options.rest_force : Eigen::VectorXd::Zero(n);
    out.rest_B.rowwise() = force.transpose();
    noise_a(out.rest_A);
    noise_b(out.rest_B);
  }
  if (options.scale_b != 1.0) {
    out.B *= options.scale_b;
    out.B_true *= options.scale_b;
    out.rest_B *= options.scale_b;
  }
}

std::vector<Warning> simulation_warnings(const Eigen::MatrixXd& truth, const SimulationOptions& options) {
  std::vector<Warning> warnings;
  if (options.samples < truth.cols()) {
    warnings.push_back(Warning(Code::FewSamples, "fewer samples (" + std::to_string(options.samples) + ") than M_p has columns (" +
                       std::to_string(truth.cols()) + "): the estimators need m >= n"));
  }
  return warnings;
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
