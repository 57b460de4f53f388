// Uses the installed spdfit: fits the paper's 2x2 example from noise-free data with every
// method, then one noisy fit with its diagnostics. Shown verbatim in docs/cpp.md.
#include <spdfit/spdfit.hpp>

#include <cstdio>

int main() {
  Eigen::MatrixXd A(4, 2), X(2, 2);
  A << 5, 2, -3, 1, 1, -2, -1, 1;
  X << 3, 1, 1, 1;

  // Noise-free data: every method recovers X.
  for (const spdfit::FitResult& r : spdfit::fit_all(A, A * X)) {
    const bool recovered = r.ok() && (r.X - X).norm() < 1e-12;
    std::printf("%-10s recovers X: %s\n", std::string(spdfit::to_string(r.method)).c_str(), recovered ? "yes" : "no");
    if (!recovered) return 1;
  }

  // Noisy data: the estimate and the evidence to check it by.
  Eigen::MatrixXd noise(4, 2);
  noise << 0.3, -0.2, 0.1, 0.4, -0.3, 0.2, 0.2, -0.1;
  const spdfit::FitResult r = spdfit::spde(A + noise, A * X);
  if (!r.ok()) {
    std::fprintf(stderr, "%s\n", r.message.c_str());  // a numerical failure is a status, not a crash
    return 1;
  }
  std::printf("spdfit %s: spde area criterion %.6f (closed-form minimum %.6f), positive definite: %s\n",
              spdfit::kVersion, *r.diagnostics.area_criterion, *r.diagnostics.area_criterion_minimum,
              r.diagnostics.positive_definite ? "yes" : "no");
  for (const spdfit::Warning& warning : r.warnings) {
    std::printf("warning (%s): %s\n", std::string(spdfit::code_info(warning.code).name).c_str(), warning.text.c_str());
  }

  // The result as JSON and back (spdfit/render.hpp): exact, every double bit for bit.
  const spdfit::FitResult back = spdfit::from_json<spdfit::FitResult>(spdfit::to_json(r, spdfit::JsonStyle::Exact));
  std::printf("read back from its JSON: %s\n", back.X == r.X ? "the same X" : "another X");
  return back.X == r.X ? 0 : 1;
}
