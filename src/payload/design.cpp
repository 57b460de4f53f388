// Choosing K calibration poses (payload/design.hpp): greedy then Fedorov exchange on the static
// regressor's information, compared with random K-pose choices from the same pool.
#include "spdfit/payload/design.hpp"
#include "render/json_values.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "payload/kinematics.hpp"
#include "physical/common_options.hpp"
#include "spdfit/format.hpp"
#include "spdfit/random.hpp"

namespace spdfit::payload {

namespace {

using Matrix10 = Eigen::Matrix<double, 10, 10>;
constexpr double kInf = std::numeric_limits<double>::infinity();
// The greedy phase's designs are singular until three directions: their objective is that of
// F + kRegularization F_pool (negligible once F is regular).
constexpr double kRegularization = 1e-9;
constexpr int kMaxExchanges = 1000;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

// One pose's information X^T W X (10 x 10) for gravity g in S.
Matrix10 information(const Eigen::Vector3d& g, const Eigen::Matrix<double, 6, 1>& weights) {
  Eigen::Matrix<double, 6, 10> X = Eigen::Matrix<double, 6, 10>::Zero();
  const Eigen::Vector3d s = -g;
  X.block<3, 1>(0, 0) = s;
  X.block<3, 3>(3, 1) = -skew(s);
  X.block<6, 6>(0, 4).setIdentity();
  return X.transpose() * weights.asDiagonal() * X;
}

double objective(const Matrix10& F, DesignCriterion criterion, const Eigen::Matrix<double, 10, 1>& scale) {
  const Matrix10 Fs = scale.asDiagonal() * F * scale.asDiagonal();
  if (criterion == DesignCriterion::D) {
    const Eigen::LLT<Matrix10> llt(F);
    if (llt.info() != Eigen::Success) return -kInf;
    return 2.0 * llt.matrixLLT().diagonal().array().log().sum();
  }
  if (criterion == DesignCriterion::E) {
    return Eigen::SelfAdjointEigenSolver<Matrix10>(Fs, Eigen::EigenvaluesOnly).eigenvalues()(0);
  }
  const Eigen::LLT<Matrix10> llt(Fs);
  if (llt.info() != Eigen::Success) return -kInf;
  return -llt.solve(Matrix10::Identity()).trace();
}

DesignScore score_of(const Matrix10& F, const DesignRequest& request, const Eigen::Matrix<double, 10, 1>& scale) {
  DesignScore s;
  const Eigen::LLT<Matrix10> llt(F);
  const Eigen::VectorXd eig =
      Eigen::SelfAdjointEigenSolver<Matrix10>(scale.asDiagonal() * F * scale.asDiagonal(), Eigen::EigenvaluesOnly).eigenvalues();
  s.condition = eig(0) > 0.0 ? std::sqrt(eig(9) / eig(0)) : kInf;
  if (llt.info() != Eigen::Success || !(eig(0) > 1e-14 * eig(9))) {
    // Singular (fewer than 3 gravity directions): no log det, but a function a^T theta of the
    // parameters the poses determine (a orthogonal to F's null space; in the scaled units F_s = D F D,
    // D a orthogonal to F_s's) still has the standard error sqrt(a^T F^+ a); the others are infinite.
    s.log_det = -kInf;
    const Eigen::SelfAdjointEigenSolver<Matrix10> es(scale.asDiagonal() * F * scale.asDiagonal());
    const Eigen::Matrix<double, 10, 1> lambda = es.eigenvalues();
    const double cut = 1e-14 * std::max(lambda(9), 0.0);
    Matrix10 Cs = Matrix10::Zero();  // F_s^+
    for (int i = 0; i < 10; ++i) {
      if (lambda(i) > cut) Cs += es.eigenvectors().col(i) * es.eigenvectors().col(i).transpose() / lambda(i);
    }
    const auto se_of = [&](const Eigen::Matrix<double, 10, 1>& a) {
      const Eigen::Matrix<double, 10, 1> b = scale.cwiseProduct(a);
      double off = 0.0;
      for (int i = 0; i < 10; ++i) {
        if (!(lambda(i) > cut)) off += std::pow(es.eigenvectors().col(i).dot(b), 2);
      }
      if (off > 1e-16 * b.squaredNorm()) return kInf;  // the poses do not determine it
      return std::sqrt(std::max(b.dot(Cs * b), 0.0));
    };
    s.se_mass = se_of(Eigen::Matrix<double, 10, 1>::Unit(0));
    double total = 0.0;
    for (int j = 0; j < 3; ++j) {
      Eigen::Matrix<double, 10, 1> a = Eigen::Matrix<double, 10, 1>::Zero();
      a(0) = -request.center_of_mass(j) / request.mass;  // c_j = h_j / m, linearized
      a(1 + j) = 1.0 / request.mass;
      s.se_center_of_mass(j) = se_of(a);
      total += s.se_center_of_mass(j) * s.se_center_of_mass(j);
    }
    s.se_center_of_mass_norm = std::sqrt(total);
    return s;
  }
  s.log_det = 2.0 * llt.matrixLLT().diagonal().array().log().sum();
  const Matrix10 C = llt.solve(Matrix10::Identity());
  s.se_mass = std::sqrt(C(0, 0));
  // c = h / m: J = [-c / m, 1 / m] over (m, h).
  Eigen::Matrix<double, 3, 4> J;
  J.col(0) = -request.center_of_mass / request.mass;
  J.rightCols<3>() = Eigen::Matrix3d::Identity() / request.mass;
  const Eigen::Matrix3d Cc = J * C.topLeftCorner<4, 4>() * J.transpose();
  s.se_center_of_mass = Cc.diagonal().cwiseMax(0.0).cwiseSqrt();
  s.se_center_of_mass_norm = std::sqrt(std::max(Cc.trace(), 0.0));
  return s;
}

Eigen::Vector3d percentiles(std::vector<double> v) {
  Eigen::Vector3d out = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  if (v.empty()) return out;
  std::sort(v.begin(), v.end());
  const auto at = [&v](double q) {
    const double h = (static_cast<double>(v.size()) - 1.0) * q;
    const auto lo = static_cast<std::size_t>(std::floor(h));
    const std::size_t hi = std::min(lo + 1, v.size() - 1);
    if (!std::isfinite(v[lo]) || !std::isfinite(v[hi])) return v[h - static_cast<double>(lo) < 0.5 ? lo : hi];
    return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
  };
  out << at(0.1), at(0.5), at(0.9);
  return out;
}

using Spec = OptionSpec<DesignRequest>;

std::vector<Spec> make_table() {
  std::vector<Spec> table;
  Spec candidates = physical::detail::text_option<DesignRequest>(
      "candidates", "CANDIDATES", "", "",
      "The candidate poses: one per row, the orientation as payload identify takes it (`quat_cols`, `rotation_cols` "
      "or `gravity_cols`)",
      "");
  candidates.type = OptionType::File;
  candidates.positional = true;
  candidates.required = true;
  candidates.set = [](DesignRequest& r, const OptionValue& v) { r.candidates = std::get<std::string>(v); };
  table.push_back(candidates);
  Spec poses;
  poses.name = "poses";
  poses.cli = "--poses";
  poses.python = "poses";
  poses.type = OptionType::Integer;
  poses.value_name = "K";
  poses.help = "The number of poses to choose";
  poses.default_text = "6";
  poses.range = {1.0, 1e6};
  poses.nullable = false;
  poses.set = [](DesignRequest& r, const OptionValue& v) { r.poses = int(std::get<std::int64_t>(v)); };
  poses.get = [](const DesignRequest& r) -> std::optional<OptionValue> { return std::int64_t{r.poses}; };
  table.push_back(poses);
  Spec criterion = physical::detail::choice_option<DesignRequest>(
      "criterion", "--criterion", "criterion", {"D", "E", "A"},
      "D: the largest log det of the information (invariant under units); E: its largest smallest eigenvalue, A: "
      "its smallest trace of the inverse (both with the parameters scaled to unit information over the pool)",
      "D");
  criterion.set = [](DesignRequest& r, const OptionValue& v) {
    const std::string& name = std::get<std::string>(v);
    const auto parsed = parse_design_criterion(name);
    if (!parsed) throw OptionError("`criterion` must be D, E or A, got '" + name + "'");
    r.criterion = *parsed;
  };
  criterion.get = [](const DesignRequest& r) -> std::optional<OptionValue> { return std::string(to_string(r.criterion)); };
  table.push_back(criterion);
  const auto cols = [&table](std::string_view name, std::string_view cli, std::string_view help,
                             void (*set)(DesignRequest&, const OptionValue&)) {
    Spec spec = physical::detail::columns_option<DesignRequest>(name, cli, name, "COLS", help);
    spec.set = set;
    table.push_back(spec);
  };
  cols("quat_cols", "--quat-cols", "The candidates' orientation as quaternions (4 columns, x y z w; `quat_order`)",
       [](DesignRequest& r, const OptionValue& v) { r.quat_cols = std::get<std::string>(v); });
  Spec order = physical::detail::choice_option<DesignRequest>("quat_order", "--quat-order", "quat_order",
                                                               {"xyzw", "wxyz"}, "The quaternion columns' order", "xyzw");
  order.set = [](DesignRequest& r, const OptionValue& v) {
    const std::string& name = std::get<std::string>(v);
    const auto parsed = parse_quaternion_order(name);
    if (!parsed) throw OptionError("`quat_order` must be xyzw or wxyz, got '" + name + "'");
    r.quat_order = *parsed;
  };
  table.push_back(order);
  cols("rotation_cols", "--rotation-cols", "The candidates' rotation matrices (9 columns, row-major)",
       [](DesignRequest& r, const OptionValue& v) { r.rotation_cols = std::get<std::string>(v); });
  cols("gravity_cols", "--gravity-cols", "The candidates' gravity in the sensor frame (3 columns, m/s^2)",
       [](DesignRequest& r, const OptionValue& v) { r.gravity_cols = std::get<std::string>(v); });
  Spec gravity;
  gravity.name = "gravity";
  gravity.cli = "--gravity";
  gravity.python = "gravity";
  gravity.type = OptionType::RealList;
  gravity.value_name = "X,Y,Z";
  gravity.help = "Gravity in the world frame (m/s^2)";
  gravity.default_text = "0,0,-9.80665";
  gravity.excludes = {"gravity_cols"};
  gravity.set = [](DesignRequest& r, const OptionValue& v) {
    const auto& g = std::get<std::vector<double>>(v);
    if (g.size() != 3) throw OptionError("`gravity` must be 3 numbers (x, y, z in the world frame, m/s^2)");
    r.gravity = Eigen::Vector3d(g[0], g[1], g[2]);
  };
  table.push_back(gravity);
  Spec noise;
  noise.name = "noise_std_wrench";
  noise.cli = "--noise-std-wrench";
  noise.python = "noise_std_wrench";
  noise.type = OptionType::RealList;
  noise.value_name = "S";
  noise.help = "Standard deviation of one sample's wrench noise: one, two (force N, torque N m) or six; the "
               "predicted standard errors scale with it";
  noise.default_text = "1";
  noise.range = {0.0, kInf, true, false};
  noise.set = [](DesignRequest& r, const OptionValue& v) { r.noise_std_wrench = std::get<std::vector<double>>(v); };
  table.push_back(noise);
  Spec samples;
  samples.name = "samples_per_pose";
  samples.cli = "--samples-per-pose";
  samples.python = "samples_per_pose";
  samples.type = OptionType::Integer;
  samples.value_name = "N";
  samples.help = "Samples logged (averaged) at each pose";
  samples.default_text = "1";
  samples.range = {1.0, 1e9};
  samples.nullable = false;
  samples.set = [](DesignRequest& r, const OptionValue& v) { r.samples_per_pose = int(std::get<std::int64_t>(v)); };
  samples.get = [](const DesignRequest& r) -> std::optional<OptionValue> { return std::int64_t{r.samples_per_pose}; };
  table.push_back(samples);
  Spec mass;
  mass.name = "mass";
  mass.cli = "--mass";
  mass.python = "mass";
  mass.type = OptionType::Real;
  mass.value_name = "KG";
  mass.help = "The payload's nominal mass, for the predicted standard error of its centre of mass";
  mass.default_text = "1";
  mass.range = {0.0, kInf, true, false};
  mass.set = [](DesignRequest& r, const OptionValue& v) { r.mass = std::get<double>(v); };
  mass.get = [](const DesignRequest& r) -> std::optional<OptionValue> { return r.mass; };
  table.push_back(mass);
  Spec com;
  com.name = "center_of_mass";
  com.cli = "--center-of-mass";
  com.python = "center_of_mass";
  com.type = OptionType::RealList;
  com.value_name = "X,Y,Z";
  com.help = "The payload's nominal centre of mass in the sensor frame (m)";
  com.default_text = "0,0,0";
  com.set = [](DesignRequest& r, const OptionValue& v) {
    const auto& c = std::get<std::vector<double>>(v);
    if (c.size() != 3) throw OptionError("`center_of_mass` must be 3 numbers (x, y, z in metres)");
    r.center_of_mass = Eigen::Vector3d(c[0], c[1], c[2]);
  };
  table.push_back(com);
  Spec random;
  random.name = "random";
  random.cli = "--random";
  random.python = "random";
  random.type = OptionType::Integer;
  random.value_name = "N";
  random.help = "Random K-pose choices from the same pool to compare with";
  random.default_text = "1000";
  random.range = {0.0, 1e7};
  random.nullable = false;
  random.set = [](DesignRequest& r, const OptionValue& v) { r.random = int(std::get<std::int64_t>(v)); };
  random.get = [](const DesignRequest& r) -> std::optional<OptionValue> { return std::int64_t{r.random}; };
  table.push_back(random);
  Spec seed;
  seed.name = "seed";
  seed.cli = "--seed";
  seed.python = "seed";
  seed.type = OptionType::Integer;
  seed.value_name = "N";
  seed.help = "The random choices' seed";
  seed.default_text = "1";
  seed.range = {0.0, double(std::numeric_limits<std::int64_t>::max())};
  seed.set = [](DesignRequest& r, const OptionValue& v) { r.seed = std::uint64_t(std::get<std::int64_t>(v)); };
  seed.get = [](const DesignRequest& r) -> std::optional<OptionValue> { return static_cast<std::int64_t>(r.seed); };
  table.push_back(seed);
  for (Spec& spec : output_options(&DesignRequest::output, {"json", "output"},
                                   {"Print the result as JSON", "Write the chosen rows (every column, as CSV) to FILE"})) {
    table.push_back(std::move(spec));
  }
  return table;
}

}  // namespace

std::string_view to_string(DesignCriterion criterion) {
  return criterion == DesignCriterion::E ? "E" : criterion == DesignCriterion::A ? "A" : "D";
}

std::optional<DesignCriterion> parse_design_criterion(std::string_view name) {
  if (name == "D" || name == "d") return DesignCriterion::D;
  if (name == "E" || name == "e") return DesignCriterion::E;
  if (name == "A" || name == "a") return DesignCriterion::A;
  return std::nullopt;
}

const std::vector<OptionSpec<DesignRequest>>& design_option_table() {
  static const std::vector<OptionSpec<DesignRequest>> table = make_table();
  return table;
}

bool DesignRequest::is_valid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!options_in_range(*this, design_option_table(), error)) return false;
  if (noise_std_wrench.size() != 1 && noise_std_wrench.size() != 2 && noise_std_wrench.size() != 6)
    return fail("`noise_std_wrench` takes 1, 2 (force, torque) or 6 standard deviations");
  for (double s : noise_std_wrench)
    if (!(s > 0.0) || !std::isfinite(s)) return fail("`noise_std_wrench` must be finite and > 0");
  if (!(mass > 0.0) || !std::isfinite(mass)) return fail("`mass` must be a finite number > 0");
  if (!center_of_mass.allFinite()) return fail("`center_of_mass` must be finite");
  if (!gravity.allFinite() || !(gravity.norm() > 0.0)) return fail("`gravity` must be a finite, nonzero vector");
  return true;
}

DesignResult design(const Eigen::Matrix<double, 3, Eigen::Dynamic>& g, const DesignRequest& request) {
  std::string error;
  if (!request.is_valid(&error)) throw OptionError(error);
  const Eigen::Index n = g.cols();
  const int K = request.poses;
  if (n < K) {
    throw OptionError("`poses` = " + std::to_string(K) + " is more than the " + std::to_string(n) + " candidates");
  }
  if (!g.allFinite()) throw std::invalid_argument("the candidates' gravity directions must be finite");
  Eigen::Matrix<double, 6, 1> weights;
  const std::vector<double>& s = request.noise_std_wrench;
  for (int i = 0; i < 6; ++i) {
    const double sd = s.size() == 1 ? s[0] : s.size() == 2 ? s[i < 3 ? 0 : 1] : s[static_cast<std::size_t>(i)];
    weights(i) = static_cast<double>(request.samples_per_pose) / (sd * sd);
  }
  std::vector<Matrix10> info(static_cast<std::size_t>(n));
  Matrix10 pool = Matrix10::Zero();
  for (Eigen::Index i = 0; i < n; ++i) {
    info[static_cast<std::size_t>(i)] = information(g.col(i), weights);
    pool += info[static_cast<std::size_t>(i)];
  }
  pool /= static_cast<double>(n);
  Eigen::Matrix<double, 10, 1> scale;
  for (int j = 0; j < 10; ++j) scale(j) = pool(j, j) > 0.0 ? 1.0 / std::sqrt(pool(j, j)) : 1.0;
  const Matrix10 regular = kRegularization * pool;

  DesignResult out;
  out.criterion = request.criterion;
  out.poses = K;
  out.candidates = n;
  out.distinct_candidates = detail::distinct_directions(g, 100000);
  std::vector<char> taken(static_cast<std::size_t>(n), 0);
  std::vector<Eigen::Index> chosen;
  Matrix10 F = Matrix10::Zero();
  for (int k = 0; k < K; ++k) {
    double best = -kInf;
    Eigen::Index at = -1;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (taken[static_cast<std::size_t>(j)]) continue;
      const double value = objective(F + info[static_cast<std::size_t>(j)] + regular, request.criterion, scale);
      if (at < 0 || value > best) {
        best = value;
        at = j;
      }
    }
    taken[static_cast<std::size_t>(at)] = 1;
    chosen.push_back(at);
    F += info[static_cast<std::size_t>(at)];
  }
  // Fedorov exchange: the best single swap, until none improves.
  double current = objective(F + regular, request.criterion, scale);
  for (int pass = 0; pass < kMaxExchanges; ++pass) {
    double best = current;
    int out_k = -1;
    Eigen::Index in_j = -1;
    for (int k = 0; k < K; ++k) {
      const Matrix10 without = F - info[static_cast<std::size_t>(chosen[static_cast<std::size_t>(k)])];
      for (Eigen::Index j = 0; j < n; ++j) {
        if (taken[static_cast<std::size_t>(j)]) continue;
        const double value = objective(without + info[static_cast<std::size_t>(j)] + regular, request.criterion, scale);
        if (value > best + 1e-12 * std::max(1.0, std::abs(best))) {
          best = value;
          out_k = k;
          in_j = j;
        }
      }
    }
    if (out_k < 0) break;
    const Eigen::Index removed = chosen[static_cast<std::size_t>(out_k)];
    F += info[static_cast<std::size_t>(in_j)] - info[static_cast<std::size_t>(removed)];
    taken[static_cast<std::size_t>(removed)] = 0;
    taken[static_cast<std::size_t>(in_j)] = 1;
    chosen[static_cast<std::size_t>(out_k)] = in_j;
    current = best;
  }
  // F from the chosen poses afresh (the exchanges' sums carry rounding).
  F.setZero();
  for (Eigen::Index j : chosen) F += info[static_cast<std::size_t>(j)];
  std::sort(chosen.begin(), chosen.end());
  out.chosen = chosen;
  out.score = score_of(F, request, scale);

  out.random = request.random;
  std::vector<double> log_det, se_mass, se_c, condition;
  std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
  Eigen::Index beaten = 0;
  for (int r = 0; r < request.random; ++r) {
    Random random(trial_seed(request.seed, static_cast<std::uint64_t>(r)));
    std::iota(order.begin(), order.end(), Eigen::Index{0});
    Matrix10 Fr = Matrix10::Zero();
    for (int k = 0; k < K; ++k) {
      const auto j = k + std::min(static_cast<Eigen::Index>(random.uniform() * static_cast<double>(n - k)), n - k - 1);
      std::swap(order[static_cast<std::size_t>(k)], order[static_cast<std::size_t>(j)]);
      Fr += info[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
    }
    const DesignScore sc = score_of(Fr, request, scale);
    log_det.push_back(sc.log_det);
    se_mass.push_back(sc.se_mass);
    se_c.push_back(sc.se_center_of_mass_norm);
    condition.push_back(sc.condition);
    if (sc.se_mass >= out.score.se_mass) ++beaten;
  }
  if (request.random > 0) {
    out.random_log_det = percentiles(log_det);
    out.random_se_mass = percentiles(se_mass);
    out.random_se_center_of_mass = percentiles(se_c);
    out.random_condition = percentiles(condition);
    out.beats_random = static_cast<double>(beaten) / static_cast<double>(request.random);
  }
  if (out.distinct_candidates < 3) {
    out.warnings.push_back(Warning(Code::RankDeficient, "the candidates have only " + std::to_string(out.distinct_candidates) +
                           " distinct gravity directions in the sensor frame: the mass, centre of mass and biases need 3"));
  } else if (!std::isfinite(out.score.log_det)) {
    out.warnings.push_back(Warning(Code::RankDeficient, "the chosen poses do not determine the ten parameters: choose at least 3 poses with distinct "
                           "gravity directions (`poses` >= 3)"));
  }
  return out;
}

void check_design_request(const DesignRequest& /*request*/, const std::vector<std::string_view>& given) {
  check_option_combination(design_option_table(), given);
}

DesignResult run_design(const DesignRequest& request) { return design_file(request.candidates, request); }

DesignResult design_file(const std::string& path, const DesignRequest& request) {
  std::string error;
  if (!request.is_valid(&error)) throw OptionError(error);
  const int given = !request.quat_cols.empty() + !request.rotation_cols.empty() + !request.gravity_cols.empty();
  if (given != 1) {
    throw OptionError("give the candidates' orientation once: `quat_cols`, `rotation_cols` or `gravity_cols`");
  }
  // Every column, then the orientation's by selection (the chosen rows are written whole).
  const io::Table whole = io::read_table(path, request.read);
  io::ReadOptions read = request.read;
  const std::string& spec = !request.quat_cols.empty() ? request.quat_cols
                            : !request.rotation_cols.empty() ? request.rotation_cols
                                                             : request.gravity_cols;
  const char* option = !request.quat_cols.empty() ? "quat_cols" : !request.rotation_cols.empty() ? "rotation_cols"
                                                                                                  : "gravity_cols";
  read.columns = {{spec, option}};
  io::check_column_selection(read.columns[0]);
  const io::Table table = io::read_table(path, read);
  PayloadSignals signals;
  const Eigen::Index c = table.values.cols();
  const Eigen::Index need = !request.quat_cols.empty() ? 4 : !request.rotation_cols.empty() ? 9 : 3;
  if (c != need) {
    throw io::ColumnSelectionError("`" + std::string(option) + "` = '" + spec + "' selects " + std::to_string(c) +
                                   " columns of " + path + ": it needs " + std::to_string(need));
  }
  (!request.quat_cols.empty() ? signals.quaternion : !request.rotation_cols.empty() ? signals.rotation : signals.gravity) =
      table.values;
  DesignResult out;
  try {
    out = design(signals, request);
  } catch (const detail::SignalError& e) {
    throw io::DataError(path, 0, 0, e.what(), e.code());
  }
  out.column_names = whole.column_names;
  out.chosen_rows.resize(static_cast<Eigen::Index>(out.chosen.size()), whole.values.cols());
  for (std::size_t k = 0; k < out.chosen.size(); ++k) out.chosen_rows.row(static_cast<Eigen::Index>(k)) = whole.values.row(out.chosen[k]);
  return out;
}

DesignResult design(const PayloadSignals& candidates, const DesignRequest& request) {
  if (request.quat_order == QuaternionOrder::Wxyz && candidates.quaternion.size() == 0) {
    throw OptionError("`quat_order` applies to quaternions: the candidates are not given as quaternions", Code::OptionNotApplicable);
  }
  PayloadSignals signals = candidates;
  const Eigen::Index m = std::max({candidates.quaternion.rows(), candidates.rotation.rows(), candidates.gravity.rows()});
  signals.wrench = Eigen::MatrixXd::Zero(m, 6);
  IdentifyRequest orientation;
  orientation.quat_order = request.quat_order;
  orientation.gravity = request.gravity;
  const detail::Kinematics kin = detail::kinematics(signals, orientation);
  DesignResult out = design(Eigen::Matrix<double, 3, Eigen::Dynamic>(-kin.specific_force), request);
  out.warnings.insert(out.warnings.begin(), kin.warnings.begin(), kin.warnings.end());
  return out;
}

std::string chosen_rows_csv(const DesignResult& result) {
  std::ostringstream out;
  if (!result.column_names.empty()) {
    for (std::size_t j = 0; j < result.column_names.size(); ++j) out << (j ? "," : "") << result.column_names[j];
    out << "\n";
  }
  io::write_csv(out, result.chosen_rows);
  return out.str();
}

}  // namespace spdfit::payload
