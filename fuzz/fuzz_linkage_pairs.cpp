// Fuzzes linkage::parse_pairs, the reader of `spdfit linkage synthesize --pairs` files, and the
// synthesis it feeds. Properties: the bytes give at least three finite pairs or an io::DataError;
// synthesis on them succeeds with finite parameters and link lengths or fails with a status and
// a message; it never returns NaN or Inf in an answer.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_check.hpp"
#include "spdfit/linkage/pairs_file.hpp"
#include "spdfit/linkage/synthesis.hpp"

namespace {

// Synthesis costs O(m) per Gauss-Newton step; above this many pairs only the reader is fuzzed,
// to keep the fuzzer's executions fast.
constexpr Eigen::Index kMaxPairsToSynthesize = 64;

void check_solution(const spdfit::linkage::LinkageSolution& s) {
  SPDFIT_FUZZ_CHECK(s.k.allFinite());
  SPDFIT_FUZZ_CHECK(std::isfinite(s.design_error_norm));
  if (s.lengths) {
    for (double a : {s.lengths->a1, s.lengths->a2, s.lengths->a3, s.lengths->a4}) {
      SPDFIT_FUZZ_CHECK(std::isfinite(a) && a > 0.0);
    }
  }
  SPDFIT_FUZZ_CHECK(s.phi_generated.allFinite());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  spdfit::linkage::PrescribedPairs pairs;
  try {
    pairs = spdfit::linkage::parse_pairs(bytes, "fuzz.csv");
  } catch (const spdfit::io::DataError& e) {
    SPDFIT_FUZZ_CHECK(!e.problem().empty());
    return 0;
  }
  SPDFIT_FUZZ_CHECK(pairs.delta_psi.size() >= 3 && pairs.delta_psi.size() == pairs.delta_phi.size());
  SPDFIT_FUZZ_CHECK(pairs.delta_psi.allFinite() && pairs.delta_phi.allFinite());
  if (pairs.delta_psi.size() > kMaxPairsToSynthesize) return 0;

  const spdfit::linkage::SynthesisResult r =
      spdfit::linkage::synthesize(pairs.delta_psi, pairs.delta_phi, Eigen::VectorXd());
  if (!r.ok()) {
    SPDFIT_FUZZ_CHECK(!r.message.empty());
    return 0;
  }
  check_solution(r.design);
  check_solution(r.structural);
  SPDFIT_FUZZ_CHECK(r.design.lengths && r.structural.lengths);
  SPDFIT_FUZZ_CHECK(std::isfinite(r.structural.structural_error_rms));
  return 0;
}
