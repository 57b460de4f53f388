// Streaming gives the in-memory estimates to rounding, whatever the block size and the number of
// threads (and for a given block size, bitwise the same for every thread count), and refuses
// mismatched files with messages that name them.
#include <gtest/gtest.h>

#include <string>

#include "file_test_support.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/io.hpp"
#include "spdfit/spde.hpp"
#include "spdfit/stream.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using io::DataError;

class StreamTest : public test::NoisyDataFiles {
 protected:
  TriangularFactor Stream(Index block_rows, unsigned threads) const {
    StreamOptions options;
    options.block_rows = block_rows;
    options.threads = threads;
    return stream_factor(a_path_, b_path_, options);
  }
};

// Rounding in the QR of a differently blocked [A B] changes R by a few eps relative; the
// estimates move by about cond * that, and this data is well conditioned (cond(A) ~ 1,
// cond(X) = 10).
constexpr double kStreamTolerance = 1e-12;

TEST_F(StreamTest, EveryMethodMatchesTheInMemoryEstimate) {
  MakeData(5003, 6, 1);
  const std::vector<FitResult> in_memory = fit_all(A_, B_);
  for (Index block : {Index{1}, Index{7}, Index{1000}, Index{1} << 15}) {
    const std::vector<FitResult> streamed = fit_all(reduce(Stream(block, 2)));
    ASSERT_EQ(streamed.size(), in_memory.size());
    for (std::size_t k = 0; k < streamed.size(); ++k) {
      ASSERT_TRUE(streamed[k].ok()) << streamed[k].message;
      EXPECT_LT(test::relative_error(streamed[k].X, in_memory[k].X), kStreamTolerance)
          << to_string(streamed[k].method) << ", block " << block;
      EXPECT_EQ(streamed[k].diagnostics.m, 5003);
    }
  }
}

TEST_F(StreamTest, TheResultDoesNotDependOnTheThreadCount) {
  // Blocks of 4096 rows and more run on the threads (15 blocks here); smaller ones on the calling
  // thread alone (stream.cpp, kMinThreadedBlockRows).
  MakeData(60000, 4, 2);
  for (Index block : {Index{333}, Index{4096}}) {
    const TriangularFactor one = Stream(block, 1);
    for (unsigned threads : {2u, 3u, 8u}) {
      const TriangularFactor many = Stream(block, threads);
      EXPECT_EQ(many.R(), one.R()) << threads << " threads, block " << block;  // bitwise
      EXPECT_EQ(many.rows(), 60000);
    }
  }
}

TEST_F(StreamTest, DataOfExtremeScaleStaysExact) {
  test::Generator g(3);
  A_ = g.gaussian(300, 3) * 1e-200;
  B_ = g.gaussian(300, 3) * 1e-100;  // X ~ 1e100; A^T A would underflow to 0
  a_path_ = Path("tiny.npy");
  b_path_ = Path("huge.npy");
  io::write_npy(a_path_, A_);
  io::write_npy(b_path_, B_);
  const FitResult streamed = spde(reduce(Stream(16, 2)));
  const FitResult in_memory = spde(A_, B_);
  ASSERT_TRUE(streamed.ok()) << streamed.message;
  EXPECT_TRUE(streamed.X.allFinite());
  EXPECT_LT(test::relative_error(streamed.X, in_memory.X), kStreamTolerance);
}

DataError StreamError(const std::string& a, const std::string& b, Index block = 100) {
  StreamOptions options;
  options.block_rows = block;
  try {
    stream_factor(a, b, options);
  } catch (const DataError& e) {
    return e;
  }
  ADD_FAILURE() << "no DataError for " << a << ", " << b;
  return DataError("", 0, 0, "");
}

TEST_F(StreamTest, NpyFilesOfDifferentLengthsAreRefusedFromTheirHeaders) {
  // Both headers give the rows: refused before a block is read, with both counts, whatever the
  // block size (a text file is counted as it is read: see below).
  test::Generator g(8);
  const std::string a = Path("A5000.npy"), b = Path("B4999.npy");
  io::write_npy(a, g.gaussian(5000, 3));
  io::write_npy(b, g.gaussian(4999, 3));
  for (Index block : {Index{7}, Index{1} << 15}) {
    const DataError e = StreamError(a, b, block);
    EXPECT_EQ(e.source(), b);
    EXPECT_EQ(e.problem(),
              "B has 4999 rows but A (" + a + ") has 5000: A and B must have the same numbers of rows (samples)");
  }
}

TEST_F(StreamTest, MismatchedFilesAreRefusedByName) {
  const std::string a = Write("A.csv", "1,2\n3,4\n5,6\n");
  const std::string longer = Write("long.csv", "1,2\n3,4\n5,6\n7,8\n");
  const std::string wide = Write("wide.csv", "1,2,3\n3,4,5\n5,6,7\n");
  const std::string flat = Write("flat.csv", "1,2,3\n");
  EXPECT_EQ(StreamError(a, longer).source(), longer);
  EXPECT_EQ(
      StreamError(a, longer).problem(),
      "B has more than 3 rows but A (" + a + ") has 3: A and B must have the same numbers of rows (samples)");
  EXPECT_EQ(
      StreamError(longer, a).problem(),
      "B has 3 rows but A (" + longer + ") has more: A and B must have the same numbers of rows (samples)");
  EXPECT_EQ(StreamError(longer, a, 2).problem(), StreamError(longer, a, 100).problem());
  // B with other columns than A is a non-square X (ls and tls): stream_factor accepts it, and
  // fit_files refuses it for a method that needs a square X, naming B's file, at the first block.
  const TriangularFactor non_square = stream_factor(a, wide);
  EXPECT_EQ(non_square.n(), 2);
  EXPECT_EQ(non_square.d(), 3);
  try {
    fit_files(a, wide, Method::Spde, {}, StreamOptions{});
    ADD_FAILURE() << "spde accepted a non-square X";
  } catch (const DataError& e) {
    EXPECT_EQ(e.source(), wide);
    EXPECT_NE(e.problem().find("use ls or tls"), std::string::npos) << e.problem();
  }
  EXPECT_EQ(StreamError(flat, flat).problem(),
            "A has 1 rows (samples) but 3 columns: at least as many samples as columns are needed");
  const DataError bad = StreamError(a, Write("bad.csv", "1,2\n3,x\n5,6\n"));
  EXPECT_EQ(bad.line(), 2u);
  EXPECT_EQ(bad.column(), 3u);
}

TEST_F(StreamTest, BlockRowsMustBePositive) {
  MakeData(10, 2, 4);
  EXPECT_THROW(Stream(0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace spdfit
