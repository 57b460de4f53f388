// Compiled with -O3 (GCC 12 vectorizes the lane sums and the updates of householder_step only
// there) and -ffp-contract=off (src/CMakeLists.txt): with no fused multiply-adds and sums in fixed
// lanes, every variant computes the same bits, so results do not depend on the CPU. The variants
// are functions with a target attribute, each inlining the same baseline code; the baseline one
// uses no ymm or zmm register (checked with objdump by tests/isa/check_kernel_isa.sh).
#include "numerics/block_qr.hpp"

#include "spdfit/blas.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <stdexcept>

#include "numerics/householder.hpp"

namespace spdfit::detail {

namespace {

using Eigen::Index;

// Lanes of the sums: eight doubles, one AVX-512 register, two AVX2 ones or four SSE2 ones.
constexpr int kLanes = 8;

[[gnu::always_inline]] inline void absorb_chunks(double* R, Index k, double* C, Index rows, Index ldc) {
  const Index chunk = block_qr_chunk_rows(k);
  for (Index first = 0; first < rows; first += chunk) {
    const Index len = std::min(chunk, rows - first);
    double* part = C + first;
    for (Index j = 0; j < k; ++j) {
      householder_step<kLanes>(R + j + j * k, k, part + j * ldc, ldc, len, k - j);
    }
  }
}

using Kernel = void (*)(double*, Index, double*, Index, Index);

void absorb_baseline(double* R, Index k, double* C, Index rows, Index ldc) { absorb_chunks(R, k, C, rows, ldc); }

#if defined(__x86_64__) && defined(__GNUC__)
#define SPDFIT_X86_KERNELS 1
[[gnu::target("avx2,fma")]] void absorb_avx2(double* R, Index k, double* C, Index rows, Index ldc) {
  absorb_chunks(R, k, C, rows, ldc);
}
[[gnu::target("avx512f,avx512bw,avx512vl,avx512dq,avx2,fma")]] void absorb_avx512(double* R, Index k, double* C,
                                                                                  Index rows, Index ldc) {
  absorb_chunks(R, k, C, rows, ldc);
}
#endif

Kernel kernel_for(VectorIsa isa) {
#ifdef SPDFIT_X86_KERNELS
  if (isa == VectorIsa::Avx512) return absorb_avx512;
  if (isa == VectorIsa::Avx2) return absorb_avx2;
#endif
  (void)isa;
  return absorb_baseline;
}

// The name, ignoring case and surrounding blanks ("AVX2" and " avx2" are avx2).
bool parse_isa(std::string name, VectorIsa* isa) {
  const auto blank = [](unsigned char c) { return std::isspace(c) != 0; };
  name.erase(name.begin(), std::find_if_not(name.begin(), name.end(), blank));
  name.erase(std::find_if_not(name.rbegin(), name.rend(), blank).base(), name.end());
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (VectorIsa candidate : {VectorIsa::Baseline, VectorIsa::Avx2, VectorIsa::Avx512}) {
    if (name == vector_isa_name(candidate)) {
      *isa = candidate;
      return true;
    }
  }
  return false;
}

struct KernelChoice {
  VectorIsa isa = VectorIsa::Baseline;
  std::string report;
  std::string warning;  // SPDFIT_KERNELS set to something not taken
};

KernelChoice choose_kernels() {
  KernelChoice choice;
  const VectorIsa cpu = cpu_vector_isa();
  choice.isa = cpu;
  const char* value = std::getenv(kKernelsVariable);
  const std::string requested = value ? value : "";
  VectorIsa asked = cpu;
  const std::string setting = std::string(kKernelsVariable) + "=" + requested;
  if (requested.empty()) {
    choice.report = std::string(vector_isa_name(cpu)) + " (the CPU's widest)";
  } else if (!parse_isa(requested, &asked)) {
    choice.report = std::string(vector_isa_name(cpu)) + " (the CPU's widest; " + setting +
                    " is not one of baseline, avx2, avx512, and is ignored)";
    choice.warning = setting + " is not one of baseline, avx2, avx512: ignored, spdfit's kernels run on " +
                     vector_isa_name(cpu) + ", the CPU's widest";
  } else if (asked > cpu) {
    choice.report = std::string(vector_isa_name(cpu)) + " (the CPU's widest; " + setting +
                    " asks for more than the CPU has)";
    choice.warning = setting + " asks for more than this CPU has: spdfit's kernels run on " +
                     vector_isa_name(cpu) + ", the CPU's widest";
  } else {
    choice.isa = asked;
    choice.report = std::string(vector_isa_name(asked)) + " (" + setting + ")";
  }
  return choice;
}

const KernelChoice& kernel_choice() {
  static const KernelChoice choice = choose_kernels();
  return choice;
}

}  // namespace

const char* vector_isa_name(VectorIsa isa) {
  switch (isa) {
    case VectorIsa::Avx512:
      return "avx512";
    case VectorIsa::Avx2:
      return "avx2";
    case VectorIsa::Baseline:
      break;
  }
  return "baseline";
}

VectorIsa cpu_vector_isa() {
#ifdef SPDFIT_X86_KERNELS
  __builtin_cpu_init();  // may run before the constructors that would otherwise call it
  // libgcc's __builtin_cpu_supports also checks that the OS saves the registers (XGETBV).
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  if (avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq")) {
    return VectorIsa::Avx512;
  }
  if (avx2) return VectorIsa::Avx2;
#endif
  return VectorIsa::Baseline;
}

// About 256 kB of C, so that a chunk stays in the L2 cache while its k reflections sweep it
// (measured on an AMD EPYC: 128-row to 2048-row chunks within 10%).
Index block_qr_chunk_rows(Index k) { return std::clamp<Index>(Index{32768} / std::max<Index>(k, 1), 128, 4096); }

VectorIsa kernel_isa() { return kernel_choice().isa; }

void absorb_into_triangle(VectorIsa isa, Eigen::Ref<Eigen::MatrixXd> R, Eigen::Ref<Eigen::MatrixXd> C) {
  const Index k = R.cols();
  if (R.rows() != k || C.cols() != k) {
    throw std::invalid_argument("absorb_into_triangle: R is " + std::to_string(R.rows()) + " x " +
                                std::to_string(R.cols()) + " and C has " + std::to_string(C.cols()) + " columns");
  }
  if (R.outerStride() != k) throw std::invalid_argument("absorb_into_triangle: R must be contiguous (a whole matrix)");
  if (isa > cpu_vector_isa()) throw std::invalid_argument("absorb_into_triangle: the CPU lacks that instruction set");
  if (C.rows() == 0 || k == 0) return;
  kernel_for(isa)(R.data(), k, C.data(), C.rows(), C.outerStride());
}

void absorb_into_triangle(Eigen::Ref<Eigen::MatrixXd> R, Eigen::Ref<Eigen::MatrixXd> C) {
  absorb_into_triangle(kernel_isa(), R, C);
}

}  // namespace spdfit::detail

namespace spdfit {

std::string kernel_isa_report() { return detail::kernel_choice().report; }

std::string kernel_isa_warning() { return detail::kernel_choice().warning; }

}  // namespace spdfit
