// Uses the installed library: fits X from noise-free data and checks it is recovered.
#include <spdfit/spdfit.hpp>

#include <cstdio>

int main() {
  Eigen::MatrixXd A(4, 2), X(2, 2);
  A << 5, 2, -3, 1, 1, -2, -1, 1;
  X << 3, 1, 1, 1;
  const spdfit::FitResult r = spdfit::spde(A, A * X);
  std::printf("spdfit %s: spde error %.3g\n", spdfit::kVersion, (r.X - X).norm());
  return r.ok() && (r.X - X).norm() < 1e-12 ? 0 : 1;
}
