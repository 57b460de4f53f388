#include "physical/identifiability.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "spdfit/rank.hpp"

namespace spdfit::physical::detail {

namespace {

// A null-space vector (unit norm in the scaled parameters, exact to about 1e-15) reaches a
// parameter when its component there is above this.
constexpr double kReach = 1e-8;
// Coefficients below this fraction of the largest are left out of a combination's text.
constexpr double kShown = 1e-6;

std::string coefficient_text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

}  // namespace

std::string combination_text(const Eigen::VectorXd& coefficients, const std::vector<std::string>& names) {
  Eigen::Index top = 0;
  const double largest = coefficients.cwiseAbs().maxCoeff(&top);
  if (!(largest > 0.0)) return "0";
  const Eigen::VectorXd c = coefficients / coefficients(top);
  std::string out;
  for (Eigen::Index j = 0; j < c.size(); ++j) {
    if (std::abs(c(j)) <= kShown) continue;
    const double magnitude = std::abs(c(j));
    const bool one = std::abs(magnitude - 1.0) < 1e-12;
    if (out.empty()) {
      out += c(j) < 0 ? "-" : "";
    } else {
      out += c(j) < 0 ? " - " : " + ";
    }
    out += (one ? std::string() : coefficient_text(magnitude) + " ") + names[static_cast<std::size_t>(j)];
  }
  return out;
}

Identifiability identifiability(const Eigen::MatrixXd& R, const std::vector<std::string>& names, double cutoff) {
  const Eigen::Index p = R.cols();
  Identifiability out;
  out.parameters = p;
  out.determined.assign(static_cast<std::size_t>(p), true);
  if (p == 0) return out;
  // Unit-norm columns: the rank and the pivots do not depend on the parameters' units.
  Eigen::VectorXd norm = R.colwise().norm().transpose();
  Eigen::VectorXd scale(p);
  for (Eigen::Index j = 0; j < p; ++j) scale(j) = norm(j) > 0.0 ? 1.0 / norm(j) : 1.0;
  const Eigen::MatrixXd Rs = R * scale.asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Rs, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  out.rank = numerical_rank(s, cutoff);
  out.condition = out.rank == p && s(p - 1) > 0.0 ? s(0) / s(p - 1) : std::numeric_limits<double>::infinity();

  // The undetermined combinations: the null space, back in the parameters' own units.
  const Eigen::MatrixXd null_scaled = svd.matrixV().rightCols(p - out.rank);
  for (Eigen::Index c = 0; c < null_scaled.cols(); ++c) {
    UndeterminedCombination u;
    const Eigen::VectorXd v = null_scaled.col(c);
    Eigen::VectorXd physical = scale.asDiagonal() * v;
    physical /= physical.norm();
    for (Eigen::Index j = 0; j < p; ++j) {
      if (std::abs(v(j)) > kReach) {
        out.determined[static_cast<std::size_t>(j)] = false;
        u.parameters.push_back(names[static_cast<std::size_t>(j)]);
      }
    }
    u.coefficients = physical;
    u.text = combination_text(physical, names);
    out.undetermined.push_back(std::move(u));
  }

  // The base parameters from the column-pivoted QR: Rs P = Q [T11 T12; 0 T22], beta = theta_B +
  // T11^-1 T12 theta_N in the scaled parameters; each row made 1 on its pivot in the parameters'
  // own units.
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Rs);
  const Eigen::Index r = out.rank;
  const Eigen::MatrixXd T = qr.matrixQR().topRows(std::min<Eigen::Index>(r, qr.matrixQR().rows()))
                                .triangularView<Eigen::Upper>();
  Eigen::MatrixXd combination = Eigen::MatrixXd::Zero(r, p);  // in pivoted, scaled order
  if (r > 0) {
    combination.leftCols(r).setIdentity();
    if (r < p) {
      combination.rightCols(p - r) =
          T.topLeftCorner(r, r).triangularView<Eigen::Upper>().solve(T.topRightCorner(r, p - r));
    }
  }
  // Rows in the order of their pivot parameters (the regressor's column order), each made 1 on it.
  const auto& perm = qr.colsPermutation().indices();
  std::vector<Eigen::Index> rows(static_cast<std::size_t>(r));
  for (Eigen::Index i = 0; i < r; ++i) rows[static_cast<std::size_t>(i)] = i;
  std::sort(rows.begin(), rows.end(), [&perm](Eigen::Index a, Eigen::Index b) { return perm(a) < perm(b); });
  out.base = Eigen::MatrixXd::Zero(r, p);
  for (Eigen::Index row = 0; row < r; ++row) {
    const Eigen::Index i = rows[static_cast<std::size_t>(row)];
    for (Eigen::Index k = 0; k < p; ++k) {
      const Eigen::Index j = perm(k);
      out.base(row, j) = combination(i, k) / scale(j);  // theta_s = phi / scale
    }
    out.base.row(row) /= out.base(row, perm(i));
    out.base_names.push_back(combination_text(out.base.row(row).transpose(), names));
  }
  return out;
}

}  // namespace spdfit::physical::detail
