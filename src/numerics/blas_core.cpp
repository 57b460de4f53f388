#include "numerics/blas_core.hpp"

#include <strings.h>

#include <array>
#include <cstdlib>

#include "numerics/block_qr.hpp"

// OpenBLAS's name for the kernels it chose (cblas.h declares it; which cblas.h /usr/include holds
// depends on Debian's alternatives, so it is declared here). Weak: with another BLAS, or none
// (SPDFIT_LAPACK off), the symbol is absent and its address null.
extern "C" char* openblas_get_corename(void) __attribute__((weak));
extern "C" void openblas_set_num_threads(int) __attribute__((weak));
extern "C" int blas_thread_shutdown_(void) __attribute__((weak));

namespace spdfit {

namespace {

// OpenBLAS 0.3.21's x86-64 cores whose kernels stop short of AVX2 (the names of its corename[]
// table in driver/others/dynamic.c). It falls back to one of these on a CPU it does not know, or
// when the OS does not enable the wider registers (which __builtin_cpu_supports sees as well).
// Excavator is left out: OpenBLAS names it only on that AMD CPU, never as a fallback.
constexpr std::array<const char*, 20> kGenericCores = {
    "Katmai", "Coppermine",  "Northwood", "Prescott",  "Banias",     "Atom",         "Core2",
    "Penryn", "Dunnington",  "Nehalem",   "Athlon",    "Opteron",    "Opteron_SSE3", "Barcelona",
    "Nano",   "Sandybridge", "Bobcat",    "Bulldozer", "Piledriver", "Steamroller"};

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

// The widest extension OpenBLAS has double-precision kernels for, as BlasCoreCheck::cpu: the
// Haswell kernels use FMA3 as well as AVX2; the SkylakeX ones AVX-512 F, BW, VL and DQ (every
// AVX-512 CPU from Skylake-SP on has all four), which is cpu_vector_isa()'s rule.
std::string cpu_vector_extension() {
  switch (detail::cpu_vector_isa()) {
    case detail::VectorIsa::Avx512:
      return "AVX-512";
    case detail::VectorIsa::Avx2:
      return "AVX2";
    case detail::VectorIsa::Baseline:
      break;
  }
  return "";
}

}  // namespace

std::string blas_core_name() {
  if (openblas_get_corename == nullptr) return "";
  const char* name = openblas_get_corename();
  return name ? name : "";
}

void set_blas_threads(int threads) {
  if (openblas_set_num_threads != nullptr) openblas_set_num_threads(threads);
}

void idle_blas_threads() {
  if (blas_thread_shutdown_ != nullptr) blas_thread_shutdown_();
}

bool is_generic_blas_core(const std::string& core) {
  for (const char* generic : kGenericCores) {
    if (strcasecmp(core.c_str(), generic) == 0) return true;
  }
  return false;
}

BlasCoreCheck check_blas_core() {
  BlasCoreCheck check;
  check.reported = blas_core_name();
  const std::string test_core = environment(kTestBlasCoreVariable);
  if (!check.reported.empty() && !test_core.empty()) {
    check.reported = test_core;
    check.from_test_switch = true;
  }
  check.cpu = cpu_vector_extension();
  check.user_coretype = environment(kOpenBlasCoreVariable);
  if (check.user_coretype.empty() && is_generic_blas_core(check.reported)) {
    if (check.cpu == "AVX-512") check.suggested = "SkylakeX";
    if (check.cpu == "AVX2") check.suggested = "Haswell";
  }
  return check;
}

}  // namespace spdfit
