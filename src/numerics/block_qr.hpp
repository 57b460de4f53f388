// The structured block QR of the triangular factor: R <- the R of [R; C], for the tall, narrow
// blocks of rows that streaming, appending and merging absorb (a flat tall-skinny QR: the rows
// are taken in cache-sized chunks, each folded into R in turn). It is spdfit's own kernel, built
// for several instruction sets in one binary (baseline x86-64, AVX2 with FMA, AVX-512) and chosen
// once, at first use, from the CPU (runtime dispatch: the binary still runs on any x86-64). Its
// code is plain loops over raw columns, no Eigen expressions, so no Eigen code is compiled for
// more than one instruction set (which would break the one-definition rule). Internal.
#pragma once

#include <Eigen/Core>
#include <string>

namespace spdfit::detail {

/// The instruction sets spdfit's own kernels are built for, narrowest first.
enum class VectorIsa { Baseline, Avx2, Avx512 };

/// "baseline", "avx2" or "avx512": the names SPDFIT_KERNELS takes.
const char* vector_isa_name(VectorIsa isa);

/// The widest of VectorIsa this CPU runs and its OS enables: AVX-512 needs F, BW, VL and DQ;
/// AVX2 needs FMA too. kBaseline off x86-64. Reads CPUID once.
VectorIsa cpu_vector_isa();

/// Narrows the kernels' instruction set, for measurements and tests: "baseline", "avx2" or
/// "avx512" (case and surrounding blanks ignored). A set wider than the CPU's is not taken (the
/// CPU's widest is); any other value is ignored. Read once, at the kernels' first use.
inline constexpr const char* kKernelsVariable = "SPDFIT_KERNELS";

/// The instruction set the kernels run on: cpu_vector_isa(), narrowed by SPDFIT_KERNELS.
VectorIsa kernel_isa();

// kernel_isa_report() and kernel_isa_warning(), which say what kernel_isa() chose, are public
// (spdfit/blas.hpp).

/// The rows of C the block QR folds into R at a time, for k columns: a multiple of it, given to
/// absorb_into_triangle call by call, gives the same bits as all the rows in one call.
Eigen::Index block_qr_chunk_rows(Eigen::Index k);

/// R (k x k, contiguous, upper triangular; below the diagonal is not read and left as it was)
/// <- the upper triangular factor of the Householder QR of [R; C], for C of any number of rows
/// and k columns, which is overwritten (it ends holding reflectors). Throws std::invalid_argument
/// for shapes that do not fit or an R that is a block of a larger matrix. R^T R grows by C^T C exactly in exact
/// arithmetic; the arithmetic is backward stable, as the unblocked QR (LAPACK's dgeqr2).
/// Cost 2 rows k^2 flops. Runs on kernel_isa().
void absorb_into_triangle(Eigen::Ref<Eigen::MatrixXd> R, Eigen::Ref<Eigen::MatrixXd> C);

/// The same on a chosen instruction set, which the CPU must run (tests compare them).
void absorb_into_triangle(VectorIsa isa, Eigen::Ref<Eigen::MatrixXd> R, Eigen::Ref<Eigen::MatrixXd> C);

}  // namespace spdfit::detail
