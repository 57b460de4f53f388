#include "spdfit/triangular_factor.hpp"

#include "spdfit/outcome.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "factor/chunk_appender.hpp"
#include "factor/data_checks.hpp"
#include "numerics/linalg.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace detail {

void check_data(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, Index n, Index d) {
  check_shapes(A, B, n, d);
  check_finite(A, B);
}

void check_shapes(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, Index n, Index d) {
  if (A.rows() != B.rows()) {
    throw InputError("A is " + std::to_string(A.rows()) + "x" + std::to_string(A.cols()) + " but B is " +
                         std::to_string(B.rows()) + "x" + std::to_string(B.cols()) +
                         ": they must have the same numbers of rows (samples)",
                     Code::DataShape, "B");
  }
  if (A.cols() != n || B.cols() != d) {
    throw InputError("A and B have " + std::to_string(A.cols()) + " and " + std::to_string(B.cols()) +
                         " columns, expected " + std::to_string(n) + " and " + std::to_string(d),
                     Code::DataShape);
  }
}

std::optional<NonfiniteEntry> first_nonfinite(const Eigen::Ref<const MatrixXd>& M) {
  if (M.allFinite()) return std::nullopt;
  for (Index i = 0; i < M.rows(); ++i) {
    for (Index j = 0; j < M.cols(); ++j) {
      const double v = M(i, j);
      if (!std::isfinite(v)) return NonfiniteEntry{i, j, std::isnan(v) ? "NaN" : v > 0 ? "Inf" : "-Inf"};
    }
  }
  return std::nullopt;
}

namespace {
// "A contains NaN or Inf: NaN in row 3, column 2 (counting from 1; A[2, 1] in NumPy)".
void check_finite_named(const Eigen::Ref<const MatrixXd>& M, const char* name) {
  const std::optional<NonfiniteEntry> e = first_nonfinite(M);
  if (!e) return;
  throw std::invalid_argument(std::string(name) + " contains NaN or Inf: " + e->what + " in row " +
                              std::to_string(e->row + 1) + ", column " + std::to_string(e->column + 1) +
                              " (counting from 1; " + name + "[" + std::to_string(e->row) + ", " +
                              std::to_string(e->column) + "] in NumPy)");
}
}  // namespace

void check_finite(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B) {
  check_finite_named(A, "A");
  check_finite_named(B, "B");
}

std::string too_few_rows(Index m, Index n) {
  return "the data has " + std::to_string(m) + " rows but " + std::to_string(n) +
         " columns: at least as many rows as columns are needed";
}

}  // namespace detail

TriangularFactor::TriangularFactor(Index n) : TriangularFactor(n, n) {}

TriangularFactor::TriangularFactor(Index n, Index d) : n_(n), d_(d) {
  if (n < 1 || d < 1) throw std::invalid_argument("A and B must each have at least one column");
  R_ = MatrixXd::Zero(n + d, n + d);
}

TriangularFactor::TriangularFactor(Index n, Index d, bool intercept) : TriangularFactor(n, d) {
  intercept_ = intercept;
}

TriangularFactor TriangularFactor::from_data(const Eigen::Ref<const MatrixXd>& A,
                                             const Eigen::Ref<const MatrixXd>& B) {
  TriangularFactor factor(A.cols(), B.cols());
  factor.append(A, B);
  return factor;
}

TriangularFactor TriangularFactor::from_data(const Eigen::Ref<const MatrixXd>& A,
                                             const Eigen::Ref<const MatrixXd>& B, bool intercept) {
  TriangularFactor factor(A.cols(), B.cols(), intercept);
  factor.append(A, B);
  return factor;
}

void TriangularFactor::scale_columns(const Eigen::VectorXd& scale_a, const Eigen::VectorXd& scale_b) {
  const auto valid = [](const Eigen::VectorXd& f, Index size) {
    return f.size() == size && f.allFinite() && (f.array() > 0.0).all();
  };
  if (!valid(scale_a, n_) || !valid(scale_b, d_)) {
    throw std::invalid_argument("TriangularFactor::scale_columns: " + std::to_string(n_) + " and " +
                                std::to_string(d_) + " factors, each finite and > 0, are needed");
  }
  // R's column j is the data's column j (in Q's basis): it scales with the data. The stored data
  // are A 2^-ea: A D_a 2^-(ea + k) keeps them in range when 2^k is the largest factor's power.
  auto scale = [this](const Eigen::VectorXd& f, std::optional<int>& exponent, Index first) {
    const int k = detail::scale_exponent(f.maxCoeff()).value_or(0);
    auto block = R_.middleCols(first, f.size());
    block = block * f.asDiagonal();
    detail::multiply_by_power_of_two(block, -k);
    if (exponent) *exponent += k;
  };
  scale(scale_a, exponent_a_, 0);
  scale(scale_b, exponent_b_, n_);
  // The means are in the data's units: they scale with them.
  if (intercept_ && means_.size() == n_ + d_) {
    means_.head(n_) = means_.head(n_).cwiseProduct(scale_a);
    means_.tail(d_) = means_.tail(d_).cwiseProduct(scale_b);
  }
}

void TriangularFactor::raise_exponents(std::optional<int> ea, std::optional<int> eb) {
  // R = [R11 R12; 0 R22]: the first n columns come from A, the last d from B, so a column
  // block scales with its own exponent. Powers of two make this exact (bar underflow of
  // entries that are negligible next to the new data). A block whose data so far was all
  // zero has no exponent yet and its columns of R are zero, so the first nonzero data sets it.
  auto raise = [this](std::optional<int>& current, std::optional<int> wanted, Index first_col, Index cols) {
    if (!wanted) return;
    if (!current) {
      current = wanted;
      return;
    }
    if (*wanted <= *current) return;
    R_.middleCols(first_col, cols) =
        detail::times_power_of_two(R_.middleCols(first_col, cols), *current - *wanted);
    current = wanted;
  };
  raise(exponent_a_, ea, 0, n_);
  raise(exponent_b_, eb, n_, d_);
}

void TriangularFactor::absorb(Eigen::Ref<MatrixXd> scaled_rows) {
  if (rows_ == 0) {
    R_ = detail::triangular_factor_in_place(scaled_rows);
    return;
  }
  detail::absorb_rows_into_factor(R_, scaled_rows);
}

void TriangularFactor::append(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B) {
  detail::check_shapes(A, B, n_, d_);
  if (A.rows() == 0) return;
  // Checking, finding the scale of, copying and folding a chunk into R touch it while it is in
  // the cache (one pass over A and B from memory, not five).
  MatrixXd scratch;
  detail::ChunkAppender::append(
      *this, A.rows(),
      [&](Index first, Index len, Eigen::Ref<MatrixXd> rows) {
        const auto part_a = A.middleRows(first, len);
        const auto part_b = B.middleRows(first, len);
        detail::check_finite(part_a, part_b);
        rows.leftCols(n_) = part_a;
        rows.rightCols(d_) = part_b;
        return detail::ChunkAppender::Extent{part_a.cwiseAbs().maxCoeff(), part_b.cwiseAbs().maxCoeff()};
      },
      &scratch);
}

namespace detail {

void ChunkAppender::append(TriangularFactor& factor, Index count, const Fill& fill, MatrixXd* scratch) {
  if (count <= 0) return;
  const Index cols = factor.n_ + factor.d_;
  const Index chunk = std::min(count, absorb_chunk_rows(cols));
  if (scratch->rows() < chunk || scratch->cols() != cols) scratch->resize(chunk, cols);
  const MatrixXd saved_r = factor.R_;
  const std::optional<int> saved_a = factor.exponent_a_, saved_b = factor.exponent_b_;
  const Index saved_rows = factor.rows_;
  const Eigen::VectorXd saved_means = factor.means_;
  const double saved_mass = factor.mass_;
  try {
    for (Index first = 0; first < count; first += chunk) {
      const Index len = std::min(chunk, count - first);
      auto rows = scratch->topRows(len);
      const Extent extent = fill(first, len, rows);
      factor.raise_exponents(scale_exponent(extent.max_a), scale_exponent(extent.max_b));
      if (factor.intercept_) {
        factor.absorb_centred(rows, nullptr, static_cast<double>(len), len);
      } else {
        factor.absorb_rows(rows, len);
      }
    }
  } catch (...) {
    factor.R_ = saved_r;
    factor.exponent_a_ = saved_a;
    factor.exponent_b_ = saved_b;
    factor.rows_ = saved_rows;
    factor.means_ = saved_means;
    factor.mass_ = saved_mass;
    throw;
  }
}

TriangularFactor ChunkAppender::from_triangle(const MatrixXd& R, Index n, Index rows, int exponent_a, int exponent_b,
                                              bool intercept, const Eigen::VectorXd& means, double mass) {
  TriangularFactor out(n, R.cols() - n, intercept);
  out.R_ = R;
  out.rows_ = rows;
  out.exponent_a_ = exponent_a;
  out.exponent_b_ = exponent_b;
  if (intercept) {
    out.means_ = means;
    out.mass_ = mass;
  }
  return out;
}

}  // namespace detail

void TriangularFactor::absorb_rows(Eigen::Ref<MatrixXd> rows, Index count) {
  auto rows_a = rows.leftCols(n_);
  auto rows_b = rows.rightCols(d_);
  detail::multiply_by_power_of_two(rows_a, -exponent_a());
  detail::multiply_by_power_of_two(rows_b, -exponent_b());
  absorb(rows);  // the rows are a scratch copy
  rows_ += count;
}

void TriangularFactor::absorb_centred(Eigen::Ref<MatrixXd> rows, const std::vector<double>* weights, double count,
                                      Index row_count) {
  const Index k = rows.rows(), cols = n_ + d_;
  if (k == 0 || !(count > 0.0)) return;
  auto rows_a = rows.leftCols(n_);
  auto rows_b = rows.rightCols(d_);
  detail::multiply_by_power_of_two(rows_a, -exponent_a());
  detail::multiply_by_power_of_two(rows_b, -exponent_b());
  // The chunk's (weighted) mean in two passes: the second removes what rounding left of an offset
  // much larger than the spread, so that the centred rows carry the spread alone.
  const auto weighted_mean = [&]() -> Eigen::RowVectorXd {
    if (!weights) return rows.colwise().sum() / count;
    Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(cols);
    for (Index i = 0; i < k; ++i) sum += (*weights)[static_cast<std::size_t>(i)] * rows.row(i);
    return sum / count;
  };
  Eigen::RowVectorXd mean = weighted_mean();
  rows.rowwise() -= mean;
  const Eigen::RowVectorXd correction = weighted_mean();
  rows.rowwise() -= correction;
  mean += correction;
  if (weights) {
    for (Index i = 0; i < k; ++i) rows.row(i) *= std::sqrt((*weights)[static_cast<std::size_t>(i)]);
  }
  // The chunk's mean and the means so far in the data's units (powers of two: exact).
  Eigen::VectorXd chunk_mean = mean.transpose();
  chunk_mean.head(n_) = detail::times_power_of_two(chunk_mean.head(n_), exponent_a());
  chunk_mean.tail(d_) = detail::times_power_of_two(chunk_mean.tail(d_), exponent_b());
  const double before = mass_;
  if (rows_ == 0 || means_.size() != cols) {
    absorb(rows);
    means_ = chunk_mean;
  } else {
    absorb(rows);
    // The between-chunk part of the scatter: m k / (m + k) (mu - mu_k)(mu - mu_k)^T, one row.
    MatrixXd between = (std::sqrt(before * count / (before + count)) * (means_ - chunk_mean)).transpose();
    auto between_a = between.leftCols(n_);
    auto between_b = between.rightCols(d_);
    detail::multiply_by_power_of_two(between_a, -exponent_a());
    detail::multiply_by_power_of_two(between_b, -exponent_b());
    absorb(between);
    means_ += (chunk_mean - means_) * (count / (before + count));
  }
  mass_ += count;
  rows_ += row_count;
}

void TriangularFactor::merge(const TriangularFactor& other) { merge({&other}, {1}); }

void TriangularFactor::append(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                              const std::vector<std::uint32_t>& counts) {
  detail::check_data(A, B, n_, d_);
  if (counts.size() != static_cast<std::size_t>(A.rows())) {
    throw std::invalid_argument("append: " + std::to_string(counts.size()) + " counts for " +
                                std::to_string(A.rows()) + " rows");
  }
  Index kept = 0;
  for (std::uint32_t c : counts) kept += c > 0;
  if (kept == 0) return;
  raise_exponents(detail::scale_exponent(A), detail::scale_exponent(B));
  if (intercept_) {
    // Chunks of the kept rows, each centred by its weighted mean (the counts are the weights).
    constexpr Index kCentredChunk = 1024;
    MatrixXd chunk(std::min(kept, kCentredChunk), n_ + d_);
    std::vector<double> weights;
    double total = 0.0;
    Index at = 0;
    for (Index i = 0; i < A.rows(); ++i) {
      const std::uint32_t c = counts[static_cast<std::size_t>(i)];
      if (c == 0) continue;
      chunk.row(at).head(n_) = A.row(i);
      chunk.row(at).tail(d_) = B.row(i);
      weights.push_back(static_cast<double>(c));
      total += c;
      if (++at == chunk.rows()) {
        absorb_centred(chunk, &weights, total, static_cast<Index>(total));
        at = 0;
        weights.clear();
        total = 0.0;
      }
    }
    if (at > 0) {
      auto last = chunk.topRows(at);
      absorb_centred(last, &weights, total, static_cast<Index>(total));
    }
    return;
  }
  // The kept rows are scaled by sqrt(count) into chunks of at most kChunk rows, each absorbed in
  // turn (a TSQR), so the work space stays small however many rows there are.
  constexpr Index kChunk = 1024;
  MatrixXd scaled(std::min(kept, kChunk), n_ + d_);
  Index k = 0;
  std::uint64_t chunk_rows = 0;  // the chunk's rows, counted with their counts
  for (Index i = 0; i < A.rows(); ++i) {
    const std::uint32_t c = counts[static_cast<std::size_t>(i)];
    if (c == 0) continue;
    const double w = c == 1 ? 1.0 : std::sqrt(static_cast<double>(c));
    scaled.row(k).head(n_) = w * A.row(i);
    scaled.row(k).tail(d_) = w * B.row(i);
    chunk_rows += c;
    if (++k == scaled.rows()) {
      absorb_rows(scaled, static_cast<Index>(chunk_rows));
      k = 0;
      chunk_rows = 0;
    }
  }
  if (k > 0) {
    auto last = scaled.topRows(k);
    absorb_rows(last, static_cast<Index>(chunk_rows));
  }
}

void TriangularFactor::append(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                              const Eigen::Ref<const Eigen::VectorXd>& weights) {
  detail::check_data(A, B, n_, d_);
  if (weights.size() != A.rows()) {
    throw std::invalid_argument("append: " + std::to_string(weights.size()) + " weights for " +
                                std::to_string(A.rows()) + " rows");
  }
  Index kept = 0;
  for (Index i = 0; i < weights.size(); ++i) {
    if (!(weights(i) >= 0.0) || !std::isfinite(weights(i))) {
      throw std::invalid_argument("append: weight " + std::to_string(i + 1) + " is not a finite number >= 0");
    }
    kept += weights(i) > 0.0;
  }
  if (kept == 0) return;
  raise_exponents(detail::scale_exponent(A), detail::scale_exponent(B));
  constexpr Index kChunk = 1024;
  MatrixXd chunk(std::min(kept, kChunk), n_ + d_);
  std::vector<double> chunk_weights;
  Index at = 0;
  double total = 0.0;
  const auto flush = [&](Index rows) {
    auto part = chunk.topRows(rows);
    if (intercept_) {
      absorb_centred(part, &chunk_weights, total, rows);
    } else {
      for (Index i = 0; i < rows; ++i) part.row(i) *= std::sqrt(chunk_weights[static_cast<std::size_t>(i)]);
      absorb_rows(part, rows);
    }
    chunk_weights.clear();
    total = 0.0;
  };
  for (Index i = 0; i < A.rows(); ++i) {
    const double w = weights(i);
    if (w == 0.0) continue;
    chunk.row(at).head(n_) = A.row(i);
    chunk.row(at).tail(d_) = B.row(i);
    chunk_weights.push_back(w);
    total += w;
    if (++at == chunk.rows()) {
      flush(at);
      at = 0;
    }
  }
  if (at > 0) flush(at);
}

void TriangularFactor::merge(const std::vector<const TriangularFactor*>& others,
                             const std::vector<std::uint32_t>& counts) {
  if (others.size() != counts.size()) {
    throw std::invalid_argument("merge: " + std::to_string(others.size()) + " factors but " +
                                std::to_string(counts.size()) + " counts");
  }
  Index kept = 0;
  for (std::size_t k = 0; k < others.size(); ++k) {
    if (others[k]->n_ != n_ || others[k]->d_ != d_) {
      throw std::invalid_argument("cannot merge factors of A and B with " + std::to_string(n_) + " and " +
                                  std::to_string(d_) + " columns and with " + std::to_string(others[k]->n_) +
                                  " and " + std::to_string(others[k]->d_) + " columns");
    }
    if (others[k]->intercept_ != intercept_) {
      throw std::invalid_argument("cannot merge a factor of [1 A B] (with an intercept) and one of [A B]");
    }
    if (counts[k] == 0 || others[k]->rows_ == 0) continue;
    raise_exponents(others[k]->exponent_a_, others[k]->exponent_b_);
    ++kept;
  }
  if (kept == 0) return;
  const Index size = n_ + d_;
  // With an intercept, one row per factor besides the factors: sqrt(w m_k) (mu_k - mu), the part of
  // the scatter between the factors' means mu_k and the merged mean mu.
  const Index between_rows = intercept_ ? kept + 1 : 0;
  MatrixXd stacked(size * kept + between_rows, size);
  if (intercept_) {
    double mass = mass_;
    Eigen::VectorXd mean = rows_ > 0 ? means_ : Eigen::VectorXd::Zero(size);
    Eigen::VectorXd shift = Eigen::VectorXd::Zero(size);  // sum of w m_k (mu_k - origin)
    bool have = rows_ > 0;
    for (std::size_t k = 0; k < others.size(); ++k) {
      if (counts[k] == 0 || others[k]->rows_ == 0) continue;
      const double w = static_cast<double>(counts[k]) * others[k]->mass_;
      if (!have) {
        mean = others[k]->means_;
        mass = w;
        have = true;
        continue;
      }
      shift += w * (others[k]->means_ - mean);
      mass += w;
    }
    mean += shift / mass;
    Index row = size * kept;
    const auto between = [&](double weight, const Eigen::VectorXd& mu) {
      auto r = stacked.row(row++);
      r = (std::sqrt(weight) * (mu - mean)).transpose();
      auto ra = r.head(n_);
      auto rb = r.tail(d_);
      detail::multiply_by_power_of_two(ra, -exponent_a());
      detail::multiply_by_power_of_two(rb, -exponent_b());
    };
    if (rows_ > 0) {
      between(mass_, means_);
    } else {
      stacked.row(row++).setZero();
    }
    for (std::size_t k = 0; k < others.size(); ++k) {
      if (counts[k] == 0 || others[k]->rows_ == 0) continue;
      between(static_cast<double>(counts[k]) * others[k]->mass_, others[k]->means_);
    }
    means_ = mean;
    mass_ = mass;
  }
  Index at = 0;
  std::uint64_t total = 0;
  for (std::size_t k = 0; k < others.size(); ++k) {
    const TriangularFactor& other = *others[k];
    if (counts[k] == 0 || other.rows_ == 0) continue;
    auto block = stacked.middleRows(at, size);
    const double w = counts[k] == 1 ? 1.0 : std::sqrt(static_cast<double>(counts[k]));
    block = w * other.R_;
    auto block_a = block.leftCols(n_);
    auto block_b = block.rightCols(d_);
    detail::multiply_by_power_of_two(block_a, other.exponent_a() - exponent_a());
    detail::multiply_by_power_of_two(block_b, other.exponent_b() - exponent_b());
    at += size;
    total += counts[k] * static_cast<std::uint64_t>(other.rows_);
  }
  absorb(stacked);
  rows_ += static_cast<Index>(total);
}

}  // namespace spdfit
