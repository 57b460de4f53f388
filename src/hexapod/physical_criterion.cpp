// The criterion of physical identification and its exact derivatives in the parameters, from
// the triangular factor of [A B]; and the unconstrained least-squares fit of the same model.
#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <cmath>
#include <limits>

#include "hexapod/physical_solver.hpp"

namespace spdfit::hexapod::detail {

namespace {

Matrix6d sym(const Matrix6d& M) { return 0.5 * (M + M.transpose()); }

double inner(const Matrix6d& A, const Matrix6d& B) { return A.cwiseProduct(B).sum(); }

}  // namespace

PhysicalData physical_data(const TriangularFactor& factor, const PhysicalModel& model, PhysicalCriterion criterion,
                           const Eigen::MatrixXd& noise_a, const Eigen::MatrixXd& noise_b) {
  PhysicalData d;
  d.criterion = criterion;
  d.R11 = factor.R11();
  d.R12 = factor.R12();
  d.R22 = factor.R22();
  d.E22 = d.R22.transpose() * d.R22;
  d.theta_scale = std::ldexp(1.0, factor.exponent_a() - factor.exponent_b());
  const double scale_a = std::ldexp(1.0, -2 * factor.exponent_a());
  const double scale_b = std::ldexp(1.0, -2 * factor.exponent_b());
  d.noise_a = noise_a.size() ? Matrix6d(noise_a * scale_a) : Matrix6d(Matrix6d::Identity() * scale_a);
  d.noise_b = noise_b.size() ? Matrix6d(noise_b * scale_b) : Matrix6d(Matrix6d::Identity() * scale_b);
  d.M0 = d.theta_scale * model.M0;
  for (int a = 0; a < model.parameters; ++a) {
    const Matrix6d& D = model.D[static_cast<std::size_t>(a)];
    d.X.push_back(d.R11 * D);
    d.Q.push_back(d.R11.transpose() * d.X.back());
    d.SD.push_back(d.noise_a * D);
  }
  return d;
}

double raw_criterion(const PhysicalData& data, const Matrix6d& M) {
  const Matrix6d Rm = data.R11 * M - data.R12;
  if (data.criterion == PhysicalCriterion::LeastSquares) return Rm.squaredNorm() + data.R22.squaredNorm();
  const Matrix6d W = sym(M * data.noise_a * M + data.noise_b);
  const Eigen::LLT<Matrix6d> llt(W);
  if (llt.info() != Eigen::Success) return std::numeric_limits<double>::quiet_NaN();
  const Matrix6d E = Rm.transpose() * Rm + data.E22;
  return inner(E, llt.solve(Matrix6d::Identity()));
}

bool set_normalization(PhysicalData& data, const PhysicalModel& model, const ParamVector& theta_start) {
  if (data.criterion == PhysicalCriterion::LeastSquares) {
    data.f0 = data.R12.squaredNorm() + data.R22.squaredNorm();
  } else {
    Matrix6d M = data.M0;
    for (int a = 0; a < model.parameters; ++a) M += theta_start(a) * model.D[static_cast<std::size_t>(a)];
    const Eigen::LLT<Matrix6d> llt(sym(M * data.noise_a * M + data.noise_b));
    if (llt.info() != Eigen::Success) return false;
    data.f0 = inner(data.R12.transpose() * data.R12 + data.E22, llt.solve(Matrix6d::Identity()));
  }
  if (!(data.f0 > 0.0) || !std::isfinite(data.f0)) data.f0 = 1.0;  // B = 0: nothing to scale by
  return true;
}

bool evaluate(const PhysicalData& data, const PhysicalModel& model, const ParamVector& theta, int order,
              Evaluation& out) {
  const int p = model.parameters;
  Matrix6d M = data.M0;
  for (int a = 0; a < p; ++a) M += theta(a) * model.D[static_cast<std::size_t>(a)];
  M = sym(M);
  const Matrix6d Rm = data.R11 * M - data.R12;
  const double inv_f0 = 1.0 / data.f0;

  if (data.criterion == PhysicalCriterion::LeastSquares) {
    out.f = (Rm.squaredNorm() + data.R22.squaredNorm()) * inv_f0;
    if (order >= 1) {
      out.g.resize(p);
      for (int a = 0; a < p; ++a) out.g(a) = 2.0 * inv_f0 * inner(Rm, data.X[static_cast<std::size_t>(a)]);
    }
    if (order >= 2) {
      out.H.resize(p, p);
      for (int a = 0; a < p; ++a)
        for (int b = 0; b <= a; ++b) {
          out.H(a, b) = out.H(b, a) =
              2.0 * inv_f0 * inner(data.X[static_cast<std::size_t>(a)], data.X[static_cast<std::size_t>(b)]);
        }
    }
    return std::isfinite(out.f);
  }

  // Errors in variables: f = <E, K>, E = Rm^T Rm + R22^T R22, K = W^-1, W = M Sigma_A M + Sigma_B.
  const Matrix6d SM = data.noise_a * M;
  const Eigen::LLT<Matrix6d> llt(sym(M * SM + data.noise_b));
  if (llt.info() != Eigen::Success) return false;
  const Matrix6d K = llt.solve(Matrix6d::Identity());
  const Matrix6d E = Rm.transpose() * Rm + data.E22;
  out.f = inner(E, K) * inv_f0;
  if (!std::isfinite(out.f)) return false;
  if (order < 1) return true;
  // Gradient over symmetric dM: Gamma = 2 sym(R11^T Rm K - Sigma_A M F), F = K E K.
  const Matrix6d KE = K * E;
  const Matrix6d F = sym(KE * K);
  const Matrix6d NRm = data.R11.transpose() * Rm;
  const Matrix6d Gamma = 2.0 * inv_f0 * sym(NRm * K - SM * F);
  out.g.resize(p);
  for (int a = 0; a < p; ++a) out.g(a) = inner(Gamma, model.D[static_cast<std::size_t>(a)]);
  if (order < 2) return true;
  // Hessian column a: the derivative of Gamma along D_a, with dW = D Sigma_A M + M Sigma_A D,
  // dK = -K dW K, dE = (R11 D)^T Rm + Rm^T R11 D, dF = dK E K + K dE K + K E dK.
  out.H.resize(p, p);
  const Matrix6d EK = KE.transpose();
  for (int a = 0; a < p; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    const Matrix6d& D = model.D[ua];
    const Matrix6d Y = D * SM;
    const Matrix6d dK = -K * (Y + Y.transpose()) * K;
    const Matrix6d XR = data.X[ua].transpose() * Rm;
    const Matrix6d dE = XR + XR.transpose();
    const Matrix6d dF = dK * EK + K * dE * K + KE * dK;
    const Matrix6d dGamma = 2.0 * inv_f0 * sym(data.Q[ua] * K + NRm * dK - data.SD[ua] * F - SM * dF);
    for (int b = 0; b < p; ++b) out.H(b, a) = inner(dGamma, model.D[static_cast<std::size_t>(b)]);
  }
  out.H = 0.5 * (out.H + out.H.transpose()).eval();
  return true;
}

ParamVector unconstrained_least_squares(const PhysicalData& data, const PhysicalModel& model, double cutoff,
                                        Eigen::Index* rank, Eigen::MatrixXd* null_space) {
  const int p = model.parameters;
  // Dynamic storage: Eigen 3.4's JacobiSVD of a fixed-row, dynamic-column matrix resizes a fixed
  // 36-vector in its QR preconditioner (an assertion in builds that keep them).
  Eigen::MatrixXd Phi(36, p);
  const Matrix6d target = data.R12 - data.R11 * data.M0;
  ParamVector column_scale(p);
  for (int a = 0; a < p; ++a) {
    const double norm = data.X[static_cast<std::size_t>(a)].norm();
    column_scale(a) = norm > 0.0 ? 1.0 / norm : 1.0;
    Phi.col(a) = Eigen::Map<const Eigen::Matrix<double, 36, 1>>(data.X[static_cast<std::size_t>(a)].data()) *
                 column_scale(a);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Phi, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const auto& s = svd.singularValues();
  Eigen::Index r = 0;
  while (r < p && s(r) > cutoff * s(0)) ++r;
  if (rank) *rank = r;
  if (null_space) *null_space = column_scale.asDiagonal() * svd.matrixV().rightCols(p - r);
  const Eigen::VectorXd y = Eigen::Map<const Eigen::Matrix<double, 36, 1>>(target.data());
  ParamVector coefficients = ParamVector::Zero(p);
  const ParamVector Uty = svd.matrixU().leftCols(r).transpose() * y;
  for (Eigen::Index k = 0; k < r; ++k) coefficients += svd.matrixV().col(k) * (Uty(k) / s(k));
  return column_scale.cwiseProduct(coefficients);
}

}  // namespace spdfit::hexapod::detail
