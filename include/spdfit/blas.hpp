// The linear algebra spdfit runs on: which kernels the BLAS chose for this CPU and how many threads
// it uses, and which instruction set spdfit's own block QR runs. Debian 12's OpenBLAS 0.3.21 (a
// DYNAMIC_ARCH build: one set of kernels per CPU family, chosen when the library loads) does not
// recognise some recent CPUs and falls back to its generic SSE3 "Prescott" kernels, two to four
// times slower in dgemm than its AVX2 and AVX-512 ones (docs/performance.md, "The BLAS core"). The
// variable OPENBLAS_CORETYPE overrides the choice, but OpenBLAS reads it only once, in its library
// constructor, before main runs: a program that finds the fallback restarts itself with it set
// (the command line does), a module loaded later (Python's) can only warn with the remedy.
#pragma once

#include <string>

namespace spdfit {


/// OpenBLAS's override of its choice of kernels, read when the library loads.
inline constexpr const char* kOpenBlasCoreVariable = "OPENBLAS_CORETYPE";

/// Test-only: when set (e.g. to "Prescott"), spdfit takes its value for the core OpenBLAS
/// reported, so that the generic-core path can be tested on any CPU. OpenBLAS itself never sees it.
inline constexpr const char* kTestBlasCoreVariable = "SPDFIT_TEST_BLAS_CORE";

/// What check_blas_core() found.
struct BlasCoreCheck {
  /// The core the BLAS reported (openblas_get_corename(), or the test switch's value); empty when
  /// the BLAS linked is not OpenBLAS (then there is nothing to choose).
  std::string reported;
  /// `reported` came from kTestBlasCoreVariable, not from OpenBLAS.
  bool from_test_switch = false;
  /// The widest vector extension of this CPU (enabled by the OS) that OpenBLAS has double-precision
  /// kernels for: "AVX-512" (F, BW, VL and DQ), "AVX2" (with FMA), or empty.
  std::string cpu;
  /// OPENBLAS_CORETYPE as the user set it; empty when unset or set to the empty string (which
  /// OpenBLAS ignores too).
  std::string user_coretype;
  /// The OPENBLAS_CORETYPE that selects this CPU's kernels ("SkylakeX" for AVX-512, "Haswell" for
  /// AVX2) when `reported` is a core without AVX2 on a CPU with it and the user has not chosen a
  /// core; empty otherwise (nothing to change).
  std::string suggested;
};

/// The running BLAS's own name for its kernels: openblas_get_corename() ("Haswell", "Prescott"),
/// or empty when the BLAS linked is not OpenBLAS. Ignores the test switch. Cost O(1).
std::string blas_core_name();

/// True when `core` is one of OpenBLAS 0.3.21's x86-64 cores without AVX2 kernels (Prescott,
/// Nehalem, Sandybridge, Barcelona, ...; compared ignoring case). A name it does not know (a newer
/// OpenBLAS's) is not generic: spdfit overrides only choices it knows to be a fallback.
bool is_generic_blas_core(const std::string& core);

/// Sets the BLAS's threads (openblas_set_num_threads) when it is OpenBLAS; nothing otherwise.
void set_blas_threads(int threads);

/// Stops OpenBLAS's worker threads now (blas_thread_shutdown_); its next call that uses threads
/// starts them again. Its idle threads spin in sched_yield for 2^28 clock ticks (about 0.1 s)
/// after it loads and after every threaded call: on a 2-core machine that took a core from
/// spdfit's own threads for the whole of a streamed fit of 10^7 rows. Only for a program that makes
/// no BLAS call on another thread at the same moment (the command line), never from the Python
/// module, whose process NumPy shares. Nothing when the BLAS is not OpenBLAS.
void idle_blas_threads();

/// The BLAS core, the CPU's vector extensions and the user's OPENBLAS_CORETYPE, and the core to
/// choose instead (BlasCoreCheck::suggested). Reads the environment and CPUID (through
/// __builtin_cpu_supports): cheap enough for every start of the program and every import.
BlasCoreCheck check_blas_core();


/// For a report of what runs (the command line's --verbose): spdfit's own kernels' instruction set,
/// "AVX-512 (the CPU's widest)", "baseline (SPDFIT_KERNELS=baseline)", and a note when
/// SPDFIT_KERNELS is set to a value that is not taken.
std::string kernel_isa_report();

/// Empty, or what to warn about when SPDFIT_KERNELS is set to a value that is not taken (an
/// unknown name, or a set this CPU lacks).
std::string kernel_isa_warning();

}  // namespace spdfit
