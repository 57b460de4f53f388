#include "spdfit/stream.hpp"

#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "factor/chunk_appender.hpp"
#include "factor/data_checks.hpp"
#include "io/npy_rows.hpp"
#include "numerics/parallel.hpp"
#include "pipeline/pair_checks.hpp"
#include "pipeline/stream_resampling.hpp"
#include "spdfit/row_reader.hpp"
#include "spdfit/threads.hpp"
#include "uncertainty/bootstrap.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace {

// Below this many rows per block, blocks are read and factored on the calling thread alone: handing
// a small block to another thread (a wake-up and a wait each way) costs more than its work. On 2e6
// x 6 .npy rows (AMD EPYC, 2 cores): --block-rows 7 took 15.7 s on two threads against 1.2 s on
// one, 100 rows 0.97 against 0.12 s, 1000 rows 0.13 against 0.06 s; from 4096 rows on, two threads
// are as fast or faster. The estimate does not depend on the threads either way.
constexpr Index kMinThreadedBlockRows = 4096;

// The threads a streaming pipeline runs on: options.threads resolved, or 1 for small blocks.
unsigned pipeline_threads(const StreamOptions& options) {
  return options.block_rows < kMinThreadedBlockRows ? 1u : resolve_threads(options.threads);
}

// One block of A and the same rows of B; or, when both files are C-order .npy, the buffers its
// rows are read through by the thread that factors them: each chunk's bytes of A and of B, and
// the chunk of [A B] they are decoded into, which the QR factors.
struct Block {
  MatrixXd A, B;
  std::vector<double> bytes_a, bytes_b;
  MatrixXd chunk;
};

// Rows [first, first + count) of both files (C-order .npy), read and decoded a chunk at a time
// into the QR's input and factored: the factor of the block, with the bits of from_data on the
// same rows decoded whole. A NaN or Inf is reported as the reader reports it for a whole block
// (the first in A's rows, then in B's), or, when non-finite values are allowed, as
// TriangularFactor refuses them.
TriangularFactor factor_rows(const io::detail::NpyRows& a, const io::detail::NpyRows& b, std::uint64_t first,
                             Index count, Block* buffers, bool intercept) {
  const Index n = a.columns(), d = b.columns();
  TriangularFactor factor(n, d, intercept);
  detail::ChunkAppender::append(
      factor, count,
      [&](Index at, Index len, Eigen::Ref<MatrixXd> rows) {
        const std::uint64_t from = first + static_cast<std::uint64_t>(at);
        const io::detail::DecodedExtent ea = a.read(from, len, rows.leftCols(n), &buffers->bytes_a);
        const io::detail::DecodedExtent eb = b.read(from, len, rows.rightCols(d), &buffers->bytes_b);
        if (!ea.finite || !eb.finite) {
          a.check_finite(first, count, &buffers->bytes_a);
          b.check_finite(first, count, &buffers->bytes_b);
          detail::check_finite(rows.leftCols(n), rows.rightCols(d));
        }
        return detail::ChunkAppender::Extent{ea.max_abs, eb.max_abs};
      },
      &buffers->chunk);
  return factor;
}

class PairReader {
 public:
  PairReader(detail::PairReaders readers, const StreamOptions& options, bool side_by_side, std::optional<Method> method)
      : a_(std::move(readers.a)),
        b_(std::move(readers.b)),
        one_file_(!b_),
        whole_(readers.whole),
        block_rows_(options.block_rows),
        side_by_side_(side_by_side),
        method_(method),
        check_columns_(std::move(readers.check_columns)),
        direct_a_(io::detail::direct_rows(a_)),
        direct_b_(b_ ? io::detail::direct_rows(*b_) : nullptr) {}

  /// Whether both files are C-order .npy files, whose rows next_rows() hands out to be read by
  /// the threads that factor them.
  bool direct() const { return direct_a_ && direct_b_; }
  const io::detail::NpyRows& direct_a() const { return *direct_a_; }
  const io::detail::NpyRows& direct_b() const { return *direct_b_; }

  /// With direct(): the next block's rows, [*first, *first + *count) of both files, counted as
  /// read but not read; false at the end of both. The same checks as next().
  bool next_rows(std::uint64_t* first, Index* count) {
    *first = a_.rows_read();
    const Index got_a = io::detail::skip_rows(a_, block_rows_);
    if (got_a < block_rows_ && whole_ && a_.rows_read() < static_cast<std::uint64_t>(a_.columns())) {
      // A NaN in these rows is what next() would report first: A's rows are decoded before their
      // number is checked.
      std::vector<double> bytes;
      direct_a_->check_finite(*first, got_a, &bytes);
      check_enough_rows();
    }
    const Index got_b = io::detail::skip_rows(*b_, block_rows_);
    started_ = true;
    check(got_a, got_b);
    *count = got_a;
    return got_a > 0;
  }

  /// How much of A has been read, in [0, 1].
  double fraction_read() const { return a_.fraction_read(); }

  /// The readers' warnings (a first column of row labels dropped, a file read whole), A's then
  /// B's, and their column names.
  detail::PairInfo info() const {
    detail::PairInfo out;
    out.warnings = a_.warnings();
    if (one_file_) {
      detail::SelectionSplit split = detail::split_selection(a_.path(), a_.column_names(), a_.selected_columns());
      out.a_names = std::move(split.a_names);
      out.b_names = std::move(split.b_names);
      out.a_columns = std::move(split.a_columns);
      out.b_columns = std::move(split.b_columns);
      return out;
    }
    out.warnings.insert(out.warnings.end(), b_->warnings().begin(), b_->warnings().end());
    out.a_names = a_.column_names();
    out.b_names = b_->column_names();
    return out;
  }

  // The next block of both files; false at the end of both. The two files are read side by
  // side on two threads when asked to (parsing text is the expensive part of streaming), except
  // the first block: A's is read alone, so that a hostile A (one row of millions of columns) is
  // refused before B is read too, as the in-memory reader does.
  bool next(Block* block) {
    Index got_a = 0;
    Index got_b = 0;
    if (one_file_) {
      // A's and B's columns side by side in one file: each block read once and cut in two.
      got_a = got_b = read_a(&both_);
      const Index n = a_columns();
      block->A = both_.leftCols(n);
      block->B = both_.rightCols(both_.cols() - n);
    } else if (side_by_side_ && started_) {
      if (!b_thread_) b_thread_ = std::make_unique<detail::TaskPool>(1);
      std::future<Index> b = b_thread_->submit([this, block] { return b_->read(block_rows_, &block->B); });
      try {
        got_a = read_a(&block->A);
      } catch (...) {
        b.wait();  // B's read writes into *block: it must end before the block can go
        throw;
      }
      got_b = b.get();
    } else {
      got_a = read_a(&block->A);
      got_b = b_->read(block_rows_, &block->B);
    }
    started_ = true;
    check(got_a, got_b);
    return got_a > 0;
  }

 private:
  // Throws when A, all read, has fewer rows (samples) than columns (checked on the whole file
  // before a part is read, when a file is split among processes).
  void check_enough_rows() const {
    if (whole_ && a_.rows_read() < static_cast<std::uint64_t>(a_columns())) {
      throw detail::fewer_samples_than_columns(a_.path(), a_.rows_read(),
                                           static_cast<std::uint64_t>(a_columns()));
    }
  }

  // A's columns (in one file: the first selection's) and B's.
  Index a_columns() const {
    return one_file_ ? static_cast<Index>(a_.selected_columns().front().size()) : a_.columns();
  }
  Index b_columns() const { return one_file_ ? a_.columns() - a_columns() : b_->columns(); }
  const std::string& b_path() const { return one_file_ ? a_.path() : b_->path(); }

  // A short block is A's last: m < n is refused there, before the O(n^2) factor of a very wide
  // file is allocated.
  Index read_a(MatrixXd* rows) {
    const Index got = a_.read(block_rows_, rows);
    if (got < block_rows_) check_enough_rows();
    return got;
  }

  // Blocks are full until a file ends, so a difference in rows shows as blocks of different
  // sizes; the columns are checked against the method at the first block.
  void check(Index got_a, Index got_b) {
    if (got_a > 0 && got_b > 0) {
      detail::check_method_fits(method_, b_path(), a_columns(), b_columns());
      if (check_columns_) {
        check_columns_(a_columns(), b_columns());
        check_columns_ = nullptr;  // once
      }
    }
    if (got_a == got_b) return;
    const std::string problem =
        got_a < got_b ? "B has more than " + detail::rows_text(a_.rows_read()) + " but A (" + a_.path() + ") has " +
                            std::to_string(a_.rows_read())
                      : "B has " + detail::rows_text(b_->rows_read()) + " but A (" + a_.path() + ") has more";
    throw detail::unequal_rows(b_->path(), problem);
  }

  io::RowReader a_;
  std::optional<io::RowReader> b_;
  bool one_file_;
  MatrixXd both_;  // one file: a block of A's and B's columns
  bool whole_;
  Index block_rows_;
  bool side_by_side_;
  std::optional<Method> method_;
  std::function<void(Index, Index)> check_columns_;
  bool started_ = false;
  std::unique_ptr<detail::TaskPool> b_thread_;  // reads B beside A, from the second block on
  const io::detail::NpyRows* direct_a_;         // owned by a_ and b_: C-order .npy files only
  const io::detail::NpyRows* direct_b_;
};

}  // namespace

TriangularFactor stream_factor(const std::string& a_path, const std::string& b_path,
                               const StreamOptions& options, std::vector<Warning>* warnings) {
  detail::PairInfo info;
  TriangularFactor factor = detail::stream_factor_for(std::nullopt, a_path, b_path, options, &info);
  if (warnings) *warnings = std::move(info.warnings);
  return factor;
}

namespace detail {

PairReaders::PairReaders(const std::string& a_path, const std::string& b_path, const io::ReadOptions& read)
    : a(a_path, checked_pair_read(b_path, read)) {
  if (b_path.empty()) return;
  b.emplace(b_path, read);
  // Files that declare their rows (.npy headers, MATLAB 7.3 sizes) are paired before any is read,
  // not when the shorter one ends (after minutes, for a large file).
  const std::optional<std::uint64_t> rows_a = a.rows_declared(), rows_b = b->rows_declared();
  if (rows_a && rows_b) check_same_rows(a.path(), *rows_a, b->path(), *rows_b);
}

PairReaders::PairReaders(io::RowReader a_part, io::RowReader b_part, std::uint64_t first)
    : a(std::move(a_part)), b(std::move(b_part)), whole(false), first_row(first) {}

PairReaders::PairReaders(io::RowReader part, std::uint64_t first)
    : a(std::move(part)), whole(false), first_row(first) {}

TriangularFactor stream_factor_for(const std::optional<Method>& method, const std::string& a_path,
                                   const std::string& b_path, const StreamOptions& options, PairInfo* info) {
  if (options.block_rows < 1) throw std::invalid_argument("block_rows must be at least 1");
  return stream_factor_for(method, PairReaders(a_path, b_path, options.read), options, info);
}

TriangularFactor stream_factor_for(const std::optional<Method>& method, PairReaders readers,
                                   const StreamOptions& options, PairInfo* info) {
  if (options.block_rows < 1) throw std::invalid_argument("block_rows must be at least 1");
  const unsigned threads = pipeline_threads(options);
  const bool intercept = readers.intercept;
  PairReader reader(std::move(readers), options, threads > 1, method);

  // Blocks' factors are computed on up to `threads` threads while the next blocks are read, and
  // merged strictly in block order, so the result is the same for every thread count. A block's
  // buffers come back with its factor and are read into again: allocating them anew for every
  // block cost page faults (a fresh mapping per buffer) about a sixth of the time.
  struct Factored {
    TriangularFactor factor;
    Block buffers;
  };
  // One thread: each block is factored on this one when merged (no pool).
  std::optional<detail::TaskPool> pool;
  if (threads > 1) pool.emplace(threads);
  std::deque<std::future<Factored>> in_flight;
  std::vector<Block> spare;
  std::optional<TriangularFactor> total;
  auto merge_oldest = [&] {
    Factored done = in_flight.front().get();
    in_flight.pop_front();
    spare.push_back(std::move(done.buffers));
    if (total) {
      total->merge(done.factor);
    } else {
      total = std::move(done.factor);
    }
  };
  Block block;
  auto submit = [&](auto factor_block) {
    in_flight.push_back(pool ? pool->submit(std::move(factor_block))
                             : std::async(std::launch::deferred, std::move(factor_block)));
    block = Block{};
    if (!spare.empty()) {
      block = std::move(spare.back());
      spare.pop_back();
    }
    if (in_flight.size() >= threads) merge_oldest();
    if (options.progress) options.progress(reader.fraction_read());
  };
  if (reader.direct()) {
    // Both files C-order .npy: each block's rows are read by the thread that factors them,
    // straight into the QR's chunks (the pool's threads outlive no reader: the pool is destroyed
    // first).
    std::uint64_t first = 0;
    Index count = 0;
    while (reader.next_rows(&first, &count)) {
      submit([&a = reader.direct_a(), &b = reader.direct_b(), first, count, intercept,
              buffers = std::move(block)]() mutable {
        TriangularFactor factor = factor_rows(a, b, first, count, &buffers, intercept);
        return Factored{std::move(factor), std::move(buffers)};
      });
    }
  } else {
    while (reader.next(&block)) {
      submit([b = std::move(block), intercept]() mutable {
        TriangularFactor factor = TriangularFactor::from_data(b.A, b.B, intercept);
        return Factored{std::move(factor), std::move(b)};
      });
    }
  }
  while (!in_flight.empty()) merge_oldest();
  if (options.progress) options.progress(1.0);
  if (info) *info = reader.info();

  // The last next() read a short block of A (0 rows when m is a multiple of block_rows), so
  // m >= n was checked there, and m >= 1 (an empty file is an error): there is a factor.
  return std::move(*total);
}

ResampledFactors stream_resampled_factors(Method method, const std::string& a_path, const std::string& b_path,
                                          const StreamOptions& options, int replicates, std::uint64_t seed) {
  if (options.block_rows < 1) throw std::invalid_argument("block_rows must be at least 1");
  return stream_resampled_factors(method, PairReaders(a_path, b_path, options.read), options, replicates, seed);
}

ResampledFactors stream_resampled_factors(Method method, PairReaders readers, const StreamOptions& options,
                                          int replicates, std::uint64_t seed) {
  if (options.block_rows < 1) throw std::invalid_argument("block_rows must be at least 1");
  if (readers.first_row % static_cast<std::uint64_t>(kBootstrapGroupRows) != 0) {
    throw std::invalid_argument("stream_resampled_factors: a part must start at a group of rows");
  }
  const unsigned threads = resolve_threads(options.threads);
  const std::uint64_t first_group = readers.first_row / static_cast<std::uint64_t>(kBootstrapGroupRows);
  const bool intercept = readers.intercept;
  // The groups are factored on the threads whatever the block size; B is read beside A only in
  // blocks large enough to pay for it.
  PairReader reader(std::move(readers), options, pipeline_threads(options) > 1, method);
  // Rows are copied into whole groups; a batch of groups is factored on the threads, then merged
  // into the total and into every replicate (replicates spread over the threads), each factor
  // in group order, so the result does not depend on the threads or the block size.
  constexpr std::size_t kBatchGroups = 32;
  const Index g_rows = kBootstrapGroupRows;
  ResampledFactors out;  // its replicates are allocated at the first block, when n is known
  std::vector<Block> batch;  // full groups, then possibly a short last one
  Index filled = 0;          // rows in batch.back() when it is being filled

  auto flush = [&] {
    if (batch.empty()) return;
    std::vector<TriangularFactor> factors(batch.size(), TriangularFactor(out.total.n(), out.total.d(), intercept));
    parallel_for(batch.size(), threads, [&](std::size_t k) {
      factors[k] = TriangularFactor::from_data(batch[k].A, batch[k].B, intercept);
    });
    std::vector<const TriangularFactor*> pointers;
    for (const TriangularFactor& f : factors) pointers.push_back(&f);
    out.total.merge(pointers, std::vector<std::uint32_t>(factors.size(), 1));
    const std::uint64_t first = first_group + out.groups;
    parallel_for(out.replicates.size(), threads, [&](std::size_t r) {
      std::vector<std::uint32_t> counts(factors.size());
      for (std::size_t k = 0; k < factors.size(); ++k) counts[k] = poisson_count(seed, r, first + k);
      out.replicates[r].merge(pointers, counts);
    });
    out.groups += factors.size();
    batch.clear();
  };

  Block block;
  while (reader.next(&block)) {
    const Index n = block.A.cols(), d = block.B.cols();
    if (out.replicates.empty()) {
      out.total = TriangularFactor(n, d, intercept);
      out.replicates.assign(static_cast<std::size_t>(replicates), TriangularFactor(n, d, intercept));
    }
    Index offset = 0;
    while (offset < block.A.rows()) {
      if (batch.empty() || filled == g_rows) {
        if (batch.size() == kBatchGroups) flush();
        batch.push_back(Block{MatrixXd(g_rows, n), MatrixXd(g_rows, d), {}, {}, {}});
        filled = 0;
      }
      const Index take = std::min(block.A.rows() - offset, g_rows - filled);
      batch.back().A.middleRows(filled, take) = block.A.middleRows(offset, take);
      batch.back().B.middleRows(filled, take) = block.B.middleRows(offset, take);
      filled += take;
      offset += take;
    }
    if (options.progress) options.progress(reader.fraction_read());
  }
  if (!batch.empty() && filled < g_rows) {
    batch.back().A.conservativeResize(filled, Eigen::NoChange);
    batch.back().B.conservativeResize(filled, Eigen::NoChange);
  }
  flush();
  if (options.progress) options.progress(1.0);
  out.info = reader.info();
  return out;
}

}  // namespace detail

}  // namespace spdfit
