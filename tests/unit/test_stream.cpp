// Streaming gives the in-memory estimates to rounding, whatever the block size and the number of
// threads (and for a given block size, bitwise the same for every thread count), and refuses
// mismatched files with messages that name them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

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

// The factor stream_factor computes, from the data in memory: each block's from_data, merged into
// the total in block order.
TriangularFactor BlockByBlock(const MatrixXd& A, const MatrixXd& B, Index block) {
  std::optional<TriangularFactor> total;
  for (Index first = 0; first < A.rows(); first += block) {
    const Index len = std::min(block, A.rows() - first);
    TriangularFactor part = TriangularFactor::from_data(A.middleRows(first, len), B.middleRows(first, len));
    if (total) {
      total->merge(part);
    } else {
      total = std::move(part);
    }
  }
  return *total;
}

void ExpectSameFactor(const TriangularFactor& actual, const TriangularFactor& expected, const std::string& what) {
  EXPECT_EQ(actual.R(), expected.R()) << what;  // bitwise
  EXPECT_EQ(actual.rows(), expected.rows()) << what;
  EXPECT_EQ(actual.exponent_a(), expected.exponent_a()) << what;
  EXPECT_EQ(actual.exponent_b(), expected.exponent_b()) << what;
}

// A .npy file of M's values with the given dtype ('<f8', '>f8', '<f4', '<i2') and order, as NumPy
// lays it out (the header padded so that the data start at a multiple of 64).
std::string WriteNpy(const std::string& path, const MatrixXd& M, const std::string& descr, bool fortran) {
  std::string data;
  auto put = [&](double x) {
    std::string bytes;
    if (descr[1] == 'f' && descr[2] == '8') {
      bytes.assign(reinterpret_cast<const char*>(&x), 8);
    } else if (descr[1] == 'f') {
      const auto f = static_cast<float>(x);
      bytes.assign(reinterpret_cast<const char*>(&f), 4);
    } else {
      const auto i = static_cast<std::int16_t>(std::lround(x * 1000.0));
      bytes.assign(reinterpret_cast<const char*>(&i), 2);
    }
    if (descr[0] == '>') std::reverse(bytes.begin(), bytes.end());
    data += bytes;
  };
  for (Index outer = 0; outer < (fortran ? M.cols() : M.rows()); ++outer) {
    for (Index inner = 0; inner < (fortran ? M.rows() : M.cols()); ++inner) put(fortran ? M(inner, outer) : M(outer, inner));
  }
  std::string header = "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") + ", 'shape': (" +
                       std::to_string(M.rows()) + ", " + std::to_string(M.cols()) + "), }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string bytes = "\x93NUMPY\x01";
  bytes += '\0';
  bytes += static_cast<char>(header.size() & 0xFF);
  bytes += static_cast<char>(header.size() >> 8);
  std::ofstream(path, std::ios::binary) << bytes << header << data;
  return path;
}

TEST_F(StreamTest, NpyFilesStreamToTheBitsOfTheirBlocksFactoredInMemory) {
  // Two C-order .npy files are read by the threads that factor them, a chunk at a time, straight
  // into the QR's input; Fortran order and other files are read a block at a time and factored
  // with from_data. Either way the factor is that of each block's from_data merged in order, to
  // the bit, for every dtype, byte order and block size (chunk boundaries of the block QR: 2730
  // rows at n + d = 12; 2731 rows is a chunk and one row).
  MakeData(70001, 6, 4);
  A_.col(2) *= 1e-3;  // a later chunk raises the exponent of A: R is rescaled on the way
  A_.bottomRows(10000) *= 64.0;
  const std::string a = Path("A64.npy");
  io::write_npy(a, A_);
  const std::vector<std::pair<std::string, bool>> layouts = {{"<f8", false}, {">f8", false}, {"<f4", false},
                                                             {"<i2", false}, {"<f8", true}};
  for (const auto& [descr, fortran] : layouts) {
    const std::string b = WriteNpy(Path("B" + descr.substr(1) + (fortran ? "F" : "C") + ".npy"), B_, descr, fortran);
    const MatrixXd B = io::read_matrix(b);
    for (Index block : {Index{1000}, Index{2731}, Index{4096}, Index{1} << 15}) {
      const TriangularFactor expected = BlockByBlock(A_, B, block);
      for (unsigned threads : {1u, 2u}) {
        StreamOptions options;
        options.block_rows = block;
        options.threads = threads;
        ExpectSameFactor(stream_factor(a, b, options), expected,
                         b + ", block " + std::to_string(block) + ", " + std::to_string(threads) + " threads");
      }
    }
  }
}

TEST_F(StreamTest, NonFiniteNpyValuesAreReportedAsTheReaderReportsThem) {
  // Decoded in chunks on the factoring threads, a NaN is still reported as the reader reports it
  // for a whole block: the first in A's block, then in B's, with its row in the file.
  test::Generator g(9);
  MatrixXd A = g.gaussian(70000, 3), B = g.gaussian(70000, 3);
  A(40000, 2) = std::numeric_limits<double>::quiet_NaN();
  B(33000, 0) = -std::numeric_limits<double>::infinity();  // earlier, in the same block of 32768 rows
  const std::string a = Path("Anan.npy"), b = Path("Binf.npy"), a_ok = Path("A.npy");
  io::write_npy(a, A);
  io::write_npy(b, B);
  A(40000, 2) = 1.0;
  io::write_npy(a_ok, A);
  for (unsigned threads : {1u, 2u}) {
    StreamOptions options;
    options.threads = threads;
    try {
      stream_factor(a, b, options);
      ADD_FAILURE() << "no error";
    } catch (const DataError& e) {
      EXPECT_EQ(e.source(), a);
      EXPECT_EQ(e.problem(), "entry (40001, 3) is NaN (rows and columns counted from 1)");
    }
    try {
      stream_factor(a_ok, b, options);
      ADD_FAILURE() << "no error";
    } catch (const DataError& e) {
      EXPECT_EQ(e.source(), b);
      EXPECT_EQ(e.problem(), "entry (33001, 1) is -Inf (rows and columns counted from 1)");
    }
    // Allowed by the reader, they are refused by the factor, as from_data refuses the block.
    options.read.allow_nonfinite = true;
    std::string expected;
    try {
      TriangularFactor::from_data(A.middleRows(32768, 32768), B.middleRows(32768, 32768));
    } catch (const std::invalid_argument& e) {
      expected = e.what();
    }
    ASSERT_FALSE(expected.empty());
    try {
      stream_factor(a_ok, b, options);
      ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()), expected);
    }
  }
  // Fewer rows than columns and a NaN: the NaN is found first, as when A's block is decoded whole.
  MatrixXd few = g.gaussian(2, 3);
  few(1, 1) = std::numeric_limits<double>::quiet_NaN();
  const std::string short_a = Path("short.npy"), short_b = Path("shortB.npy");
  io::write_npy(short_a, few);
  io::write_npy(short_b, g.gaussian(2, 3));
  const DataError e = StreamError(short_a, short_b);
  EXPECT_EQ(e.problem(), "entry (2, 2) is NaN (rows and columns counted from 1)");
}

}  // namespace
}  // namespace spdfit
