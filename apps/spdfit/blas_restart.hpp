// Fast BLAS kernels without the user's help. OpenBLAS chooses its kernels once,
// when it loads, before main runs; on a CPU it does not recognise, Debian's 0.3.21 falls back to
// generic SSE3 ones. spdfit then restarts itself once, with OPENBLAS_CORETYPE naming the CPU's
// kernels, and says so under --verbose. The rule is numerics/blas_core.hpp's, shared with the
// Python module; this file holds only what a program can do about it: the restart.
#pragma once

#include "cli.hpp"

namespace spdfit::cli {

/// Called first in main, before anything calls the BLAS and before MPI_Init. When
/// detail::check_blas_core() suggests a core (OpenBLAS reported a core without AVX2 on a CPU with
/// AVX2 or AVX-512, and OPENBLAS_CORETYPE is unset), sets OPENBLAS_CORETYPE to it and replaces the
/// process by a fresh run of the same program with the same arguments (execv of /proc/self/exe:
/// same pid, so a launcher such as mpirun still sees its process). The marker variable
/// SPDFIT_BLAS_REEXEC carries the decision to the restarted process, which removes it and never
/// restarts again. Returns when nothing needs changing, in the restarted process, and when the
/// restart fails (the environment is then restored and the program runs on the kernels OpenBLAS
/// chose; report_blas_core warns). A user's OPENBLAS_CORETYPE is always kept.
/// Test-only: SPDFIT_TEST_BLAS_EXE names the program to run instead of /proc/self/exe.
void restart_for_blas_core(char** argv);

/// After parsing: with --verbose, prints which OpenBLAS core runs and why ("spdfit: OpenBLAS core:
/// Haswell (chosen by OpenBLAS)", or what the restart changed); warns, unless --quiet, when a
/// restart was needed but failed.
void report_blas_core(const GlobalOptions& global);

}  // namespace spdfit::cli
