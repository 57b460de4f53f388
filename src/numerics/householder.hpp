// One step of the Householder QR, the one home of its arithmetic: LAPACK's dgeqr2 reflector with
// Eigen's sign and skip conventions (Eigen::MatrixBase::makeHouseholder). Two QRs are built on it:
// the bounded-size small_householder_qr of the Monte Carlo path (linalg.hpp), in plain serial
// sums, and the streaming block QR (block_qr.cpp), which vectorizes its sums in fixed lanes and is
// compiled for several instruction sets. Internal.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>

namespace spdfit::detail {

/// init + sum_i a[i] b[i] over i < n, summed in `Lanes` interleaved partial sums (lane q takes
/// i = q, q + Lanes, ...; init starts lane 0), added up in lane order, then the remainder
/// serially. Lanes = 1 is the plain serial sum, (init + a0 b0) + a1 b1 + ... The order is fixed by
/// Lanes alone, so every instruction set gives the same sums up to the contraction of a * b + c
/// into one fused multiply-add where the CPU has it.
template <int Lanes>
[[gnu::always_inline]] inline double lane_dot(double init, const double* a, const double* b, Eigen::Index n) {
  double acc[Lanes] = {};
  acc[0] = init;
  Eigen::Index i = 0;
  for (; i + Lanes <= n; i += Lanes) {
    for (int q = 0; q < Lanes; ++q) acc[q] += a[i + q] * b[i + q];
  }
  double sum = acc[0];
  for (int q = 1; q < Lanes; ++q) sum += acc[q];
  for (; i < n; ++i) sum += a[i] * b[i];
  return sum;
}

/// One Householder reflection H = I - tau v v^T, v = [1; essential], that zeroes the tail of the
/// first of `cols` columns and is applied to the others. Column c (0 <= c < cols) is its head
/// head[c * head_stride] (the entry on the diagonal row) and its tail of `len` contiguous entries
/// at tail + c * tail_stride (the entries the reflection zeroes in column 0, the rows below or,
/// in a structured QR of [R; C], the rows of C). On return head[0] is R's diagonal entry beta and
/// column 0's tail holds the essential part of v; the other columns are H times what they were.
/// When column 0's tail is already zero (its squared norm at most the smallest normal double,
/// Eigen's test), H = I and nothing changes. Cost 4 len cols flops.
template <int Lanes>
[[gnu::always_inline]] inline void householder_step(double* head, Eigen::Index head_stride, double* tail,
                                                    Eigen::Index tail_stride, Eigen::Index len, Eigen::Index cols) {
  const double tail_norm2 = lane_dot<Lanes>(0.0, tail, tail, len);
  if (!(tail_norm2 > std::numeric_limits<double>::min())) return;  // already triangular here: H = I
  const double c0 = head[0];
  double beta = std::sqrt(c0 * c0 + tail_norm2);
  if (c0 >= 0.0) beta = -beta;
  const double scale = 1.0 / (c0 - beta);
  for (Eigen::Index i = 0; i < len; ++i) tail[i] *= scale;  // the essential part of v
  const double tau = (beta - c0) / beta;
  head[0] = beta;
  for (Eigen::Index c = 1; c < cols; ++c) {
    double* y_head = head + c * head_stride;
    double* y = tail + c * tail_stride;
    const double w = tau * lane_dot<Lanes>(*y_head, tail, y, len);
    *y_head -= w;
    for (Eigen::Index i = 0; i < len; ++i) y[i] -= w * tail[i];
  }
}

}  // namespace spdfit::detail
