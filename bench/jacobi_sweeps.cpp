// How many sweeps spdfit's one-sided Jacobi SVD (src/numerics/one_sided_jacobi.hpp) takes on the
// triangular factor of [A B] that the TLS family decomposes, as it is now (on R, with V
// accumulated) and with the preconditioning that issue 19, item 2 names as the candidate for a
// faster small SVD: Jacobi on R^T (V from the normalized columns, no accumulation), on R^T after
// a column-pivoted QR of R, and after a second pivoted QR (LAPACK's dgejsv does the like).
// The data are those of the thesis' experiments in shape: m = 100 rows, n = 6, X = 2 I, graded
// columns, noise of standard deviation 0.3 on A and B. The last sweep of each run only checks
// that no pair needs a rotation. Run: build/bench/spdfit_jacobi_sweeps [trials]
#include <Eigen/Dense>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "numerics/one_sided_jacobi.hpp"

int main(int argc, char** argv) {
  using Eigen::MatrixXd;
  const int trials = argc > 1 ? std::atoi(argv[1]) : 2000;
  if (trials < 1) {
    std::fprintf(stderr, "spdfit_jacobi_sweeps: trials must be a positive integer\n");
    return 2;
  }
  std::mt19937_64 engine(1);
  std::normal_distribution<double> normal;
  const int m = 100, n = 6;
  double sweeps[4] = {0, 0, 0, 0};
  MatrixXd* no_v = nullptr;
  for (int t = 0; t < trials; ++t) {
    MatrixXd A(m, n), E(m, 2 * n);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = normal(engine) * (1.0 + j);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < 2 * n; ++j) E(i, j) = 0.3 * normal(engine);
    MatrixXd AB(m, 2 * n);
    AB << A, 2.0 * A;
    AB += E;
    const MatrixXd R = Eigen::HouseholderQR<MatrixXd>(AB).matrixQR().topRows(2 * n).triangularView<Eigen::Upper>();
    MatrixXd G = R, V;
    sweeps[0] += spdfit::detail::one_sided_jacobi(G, &V);
    MatrixXd Gt = R.transpose();
    sweeps[1] += spdfit::detail::one_sided_jacobi(Gt, no_v);
    const MatrixXd R2 = Eigen::ColPivHouseholderQR<MatrixXd>(R).matrixQR().triangularView<Eigen::Upper>();
    MatrixXd G2 = R2.transpose();
    sweeps[2] += spdfit::detail::one_sided_jacobi(G2, no_v);
    const MatrixXd R3 =
        Eigen::ColPivHouseholderQR<MatrixXd>(MatrixXd(R2.transpose())).matrixQR().triangularView<Eigen::Upper>();
    MatrixXd G3 = R3.transpose();
    sweeps[3] += spdfit::detail::one_sided_jacobi(G3, no_v);
  }
  std::printf("mean sweeps over %d trials (12 x 12 factor): R %.2f, R^T %.2f, pivoted QR then R^T %.2f, "
              "two pivoted QRs %.2f\n",
              trials, sweeps[0] / trials, sweeps[1] / trials, sweeps[2] / trials, sweeps[3] / trials);
}
