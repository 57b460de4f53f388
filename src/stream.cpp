#include "spdfit/stream.hpp"

#include <deque>
#include <future>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "spdfit/experiment/monte_carlo.hpp"  // resolve_threads
#include "spdfit/row_reader.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace {

std::string rows_text(std::uint64_t rows) { return std::to_string(rows) + (rows == 1 ? " row" : " rows"); }

// One block of A and the same rows of B.
struct Block {
  MatrixXd A, B;
};

class PairReader {
 public:
  PairReader(const std::string& a_path, const std::string& b_path, const StreamOptions& options,
             bool side_by_side)
      : a_(a_path, options.read),
        b_(b_path, options.read),
        block_rows_(options.block_rows),
        side_by_side_(side_by_side) {}

  // The next block of both files; false at the end of both. The two files are read side by
  // side on two threads when asked to (parsing text is the expensive part of streaming).
  bool next(Block* block) {
    Index got_a = 0;
    Index got_b = 0;
    if (side_by_side_) {
      std::future<Index> b = std::async(std::launch::async, [&] { return b_.read(block_rows_, &block->B); });
      // The future's destructor waits for B even when reading A throws.
      got_a = a_.read(block_rows_, &block->A);
      got_b = b.get();
    } else {
      got_a = a_.read(block_rows_, &block->A);
      got_b = b_.read(block_rows_, &block->B);
    }
    check(got_a, got_b);
    return got_a > 0;
  }

  std::uint64_t rows() const { return a_.rows_read(); }
  const io::RowReader& a() const { return a_; }

 private:
  // Blocks are full until a file ends, so a difference in rows shows as blocks of different
  // sizes; the columns are compared at the first block.
  void check(Index got_a, Index got_b) const {
    if (got_a > 0 && got_b > 0 && a_.columns() != b_.columns()) {
      throw io::DataError(b_.path(), 0, 0,
                          "B has " + std::to_string(b_.columns()) + " columns but A (" + a_.path() +
                              ") has " + std::to_string(a_.columns()) +
                              ": A and B must have the same numbers of rows (samples) and columns");
    }
    if (got_a == got_b) return;
    const std::string problem =
        got_a < got_b ? "B has more than " + rows_text(a_.rows_read()) + " but A (" + a_.path() + ") has " +
                            std::to_string(a_.rows_read())
                      : "B has " + rows_text(b_.rows_read()) + " but A (" + a_.path() + ") has more";
    throw io::DataError(b_.path(), 0, 0, problem + ": A and B must have the same numbers of rows (samples)");
  }

  io::RowReader a_, b_;
  Index block_rows_;
  bool side_by_side_;
};

}  // namespace

TriangularFactor stream_factor(const std::string& a_path, const std::string& b_path,
                               const StreamOptions& options) {
  if (options.block_rows < 1) throw std::invalid_argument("block_rows must be at least 1");
  const unsigned threads = experiment::resolve_threads(options.threads);
  PairReader reader(a_path, b_path, options, threads > 1);

  // Blocks' factors are computed on up to `threads` threads while the next blocks are read, and
  // merged strictly in block order, so the result is the same for every thread count.
  std::deque<std::future<TriangularFactor>> in_flight;
  std::optional<TriangularFactor> total;
  auto merge_oldest = [&] {
    TriangularFactor block = in_flight.front().get();
    in_flight.pop_front();
    if (total) {
      total->merge(block);
    } else {
      total = std::move(block);
    }
  };
  const auto fewer_rows_than_columns = [&] {
    return io::DataError(a_path, 0, 0,
                         "A has " + std::to_string(reader.rows()) + " rows (samples) but " +
                             std::to_string(reader.a().columns()) +
                             " columns: at least as many samples as columns are needed");
  };
  Block block;
  while (reader.next(&block)) {
    // A short block is the last: refuse m < n before the O(n^2) factor of a hostile, very wide
    // file is allocated.
    if (block.A.rows() < options.block_rows && reader.rows() < static_cast<std::uint64_t>(block.A.cols())) {
      throw fewer_rows_than_columns();
    }
    // One thread: computed on this one when merged (deferred).
    const std::launch policy = threads == 1 ? std::launch::deferred : std::launch::async;
    in_flight.push_back(
        std::async(policy, [b = std::move(block)] { return TriangularFactor::from_data(b.A, b.B); }));
    block = Block{};
    if (in_flight.size() >= threads) merge_oldest();
  }
  while (!in_flight.empty()) merge_oldest();

  if (reader.rows() < static_cast<std::uint64_t>(reader.a().columns())) throw fewer_rows_than_columns();
  return std::move(*total);
}

}  // namespace spdfit
