#include "spdfit/hexapod/identify.hpp"

#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

#include "spdfit/fit.hpp"
#include "spdfit/hexapod/model.hpp"

namespace spdfit::hexapod {

std::vector<MethodIdentification> identify(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                           const IdentifyOptions& options) {
  const Eigen::Index n = A.cols();
  auto check_square = [n](const std::optional<Eigen::MatrixXd>& M, const char* what) {
    if (M && (M->rows() != n || M->cols() != n)) {
      throw std::invalid_argument(std::string("identify: the ") + what + " must be " + std::to_string(n) +
                                  "x" + std::to_string(n) + " like the data's columns, not " +
                                  std::to_string(M->rows()) + "x" + std::to_string(M->cols()));
    }
  };
  check_square(options.truth, "true matrix");
  check_square(options.stiffness, "stiffness matrix");
  if (options.stiffness && !options.stiffness->isApprox(options.stiffness->transpose())) {
    throw std::invalid_argument("identify: the stiffness matrix must be symmetric");
  }

  std::vector<MethodIdentification> out;
  for (FitResult& result : fit_all(A, B, options.fit)) {
    MethodIdentification m;
    m.result = std::move(result);
    const FitResult& r = m.result;
    if (r.ok()) {
      if (options.truth) m.error_vs_truth = (r.X - *options.truth).norm();
      if (r.diagnostics.symmetric) {
        m.eigenvalues =
            Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(r.X, Eigen::EigenvaluesOnly).eigenvalues();
      }
      if (options.stiffness && r.diagnostics.positive_definite) {
        try {
          m.modes_hz = modal_frequencies_hz(r.X, *options.stiffness);
        } catch (const std::invalid_argument&) {
          // Positive definite by its eigenvalues but not by Cholesky: so nearly singular
          // that its modes mean nothing. Leave them out.
        }
      }
    }
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace spdfit::hexapod
