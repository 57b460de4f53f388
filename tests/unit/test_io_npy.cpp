// parse_npy and write_npy: round trips, hand-built files in every layout NumPy writes, and
// damaged or unsupported files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io/npy_layout.hpp"
#include "io/parse.hpp"
#include "spdfit/io.hpp"

namespace {

using Eigen::MatrixXd;
using spdfit::io::DataError;
using spdfit::io::parse_npy;
using spdfit::io::ReadOptions;

std::uint64_t Bits(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof(bits));
  return bits;
}

void ExpectBitwiseEqual(const MatrixXd& actual, const MatrixXd& expected) {
  ASSERT_EQ(actual.rows(), expected.rows());
  ASSERT_EQ(actual.cols(), expected.cols());
  for (Eigen::Index i = 0; i < expected.rows(); ++i) {
    for (Eigen::Index j = 0; j < expected.cols(); ++j) {
      EXPECT_EQ(Bits(actual(i, j)), Bits(expected(i, j))) << "at (" << i << ", " << j << ")";
    }
  }
}

// A file in the test temp dir, unique to this process (ctest runs tests in parallel) and
// removed when the test ends.
class TempFile {
 public:
  explicit TempFile(const std::string& name)
      : path_(testing::TempDir() + "/spdfit_io_" + std::to_string(::getpid()) + "_" + name) {}
  ~TempFile() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string Encode(double x, bool big_endian = false) {
  const std::uint64_t bits = Bits(x);
  std::string bytes(8, '\0');
  for (int k = 0; k < 8; ++k) bytes[big_endian ? 7 - k : k] = static_cast<char>(bits >> (8 * k));
  return bytes;
}

std::string EncodeAll(std::initializer_list<double> values, bool big_endian = false) {
  std::string bytes;
  for (const double x : values) bytes += Encode(x, big_endian);
  return bytes;
}

// A .npy file as numpy.save lays it out: magic, version, header length (2 bytes for 1.0,
// 4 bytes for 2.0 and 3.0), the dict padded with spaces and ending in '\n' so that the data
// starts at a multiple of 64, then the data.
std::string MakeNpy(const std::string& dict, const std::string& data, int major = 1, bool pad = true) {
  const std::size_t preamble = major == 1 ? 10 : 12;
  std::string header = dict;
  if (pad) {
    header.append((64 - (preamble + header.size() + 1) % 64) % 64, ' ');
    header += '\n';
  }
  std::string bytes = "\x93NUMPY";
  bytes += static_cast<char>(major);
  bytes += '\0';
  const std::size_t length = header.size();
  for (std::size_t k = 0; k < preamble - 8; ++k) bytes += static_cast<char>(length >> (8 * k));
  return bytes + header + data;
}

std::string Dict(const std::string& descr, bool fortran, const std::string& shape) {
  return "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") +
         ", 'shape': " + shape + ", }";
}

DataError NpyError(const std::string& bytes, ReadOptions options = {}) {
  try {
    parse_npy(bytes, "X.npy", options);
  } catch (const DataError& e) {
    return e;
  }
  ADD_FAILURE() << "no DataError";
  return DataError("", 0, 0, "");
}

void ExpectNpyError(const std::string& bytes, const std::string& problem) {
  const DataError e = NpyError(bytes);
  EXPECT_EQ(e.source(), "X.npy");
  EXPECT_EQ(e.line(), 0u);
  EXPECT_EQ(e.column(), 0u);
  EXPECT_EQ(e.problem(), problem) << e.what();
}

const MatrixXd k2x3 = (MatrixXd(2, 3) << 1, 2, 3, 4, 5, 6).finished();

// ---- Round trips -------------------------------------------------------------------------------

TEST(IoNpy, WriteThenReadIsBitwiseExact) {
  std::mt19937_64 rng(20240611);
  MatrixXd X(7, 5);
  for (Eigen::Index i = 0; i < X.size(); ++i) {
    double x;
    do {
      const std::uint64_t bits = rng();
      std::memcpy(&x, &bits, sizeof(x));
    } while (!std::isfinite(x));
    X(i) = x;
  }
  X(0, 0) = -0.0;
  X(1, 1) = std::numeric_limits<double>::denorm_min();
  X(2, 2) = -std::numeric_limits<double>::max();
  X(3, 3) = 0.1;
  const TempFile file("io_npy_roundtrip.npy");
  const std::string& path = file.path();
  spdfit::io::write_npy(path, X);
  ExpectBitwiseEqual(spdfit::io::read_matrix(path), X);
  ExpectBitwiseEqual(parse_npy(ReadBytes(path), path), X);
}

TEST(IoNpy, WriteThenReadShapes) {
  for (const auto& [m, n] : {std::pair{1, 1}, {1, 6}, {6, 1}, {3, 4}, {64, 3}}) {
    const MatrixXd X = MatrixXd::Random(m, n);
    const TempFile file("io_npy_shape.npy");
    const std::string& path = file.path();
    spdfit::io::write_npy(path, X);
    ExpectBitwiseEqual(spdfit::io::read_matrix(path), X);
  }
}

TEST(IoNpy, WriteThenReadNonfinite) {
  MatrixXd X = k2x3;
  X(0, 1) = std::numeric_limits<double>::quiet_NaN();
  X(1, 2) = -std::numeric_limits<double>::infinity();
  const TempFile file("io_npy_nonfinite.npy");
  const std::string& path = file.path();
  spdfit::io::write_npy(path, X);
  ReadOptions options;
  options.allow_nonfinite = true;
  ExpectBitwiseEqual(spdfit::io::read_matrix(path, options), X);
}

TEST(IoNpy, WrittenLayoutIsNumpys) {
  const TempFile file("io_npy_layout.npy");
  const std::string& path = file.path();
  spdfit::io::write_npy(path, k2x3);
  const std::string bytes = ReadBytes(path);
  ASSERT_GE(bytes.size(), 10u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t length = static_cast<unsigned char>(bytes[8]) |
                             static_cast<std::size_t>(static_cast<unsigned char>(bytes[9])) << 8;
  EXPECT_EQ((10 + length) % 64, 0u);
  ASSERT_EQ(bytes.size(), 10 + length + 6 * 8);
  const std::string header = bytes.substr(10, length);
  EXPECT_EQ(header.back(), '\n');
  EXPECT_EQ(header.substr(0, header.find('}') + 1),
            "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }");
  EXPECT_EQ(header.find_first_not_of(' ', header.find('}') + 1), header.size() - 1);
  // C order, little-endian.
  EXPECT_EQ(bytes.substr(10 + length), EncodeAll({1, 2, 3, 4, 5, 6}));
  // The exact bytes numpy.save writes for np.arange(1., 7.).reshape(2, 3) (format 1.0).
  EXPECT_EQ(bytes, MakeNpy(Dict("<f8", false, "(2, 3)"), EncodeAll({1, 2, 3, 4, 5, 6})));
}

TEST(IoNpy, WriteEmptyMatrix) {
  const TempFile file("io_npy_empty.npy");
  const std::string& path = file.path();
  spdfit::io::write_npy(path, MatrixXd(0, 3));
  const DataError e = NpyError(ReadBytes(path));
  EXPECT_EQ(e.problem(), "no data (shape (0, 3))");
}

// ---- Layouts -----------------------------------------------------------------------------------

TEST(IoNpy, COrder) {
  const std::string bytes = MakeNpy(Dict("<f8", false, "(2, 3)"), EncodeAll({1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(parse_npy(bytes, "X.npy"), k2x3);
}

TEST(IoNpy, FortranOrder) {
  const std::string bytes = MakeNpy(Dict("<f8", true, "(2, 3)"), EncodeAll({1, 4, 2, 5, 3, 6}));
  EXPECT_EQ(parse_npy(bytes, "X.npy"), k2x3);
}

TEST(IoNpy, BigEndian) {
  const std::string bytes = MakeNpy(Dict(">f8", false, "(2, 3)"), EncodeAll({1, 2, 3, 4, 5, 6}, true));
  EXPECT_EQ(parse_npy(bytes, "X.npy"), k2x3);
  const std::string fortran = MakeNpy(Dict(">f8", true, "(2, 3)"), EncodeAll({1, 4, 2, 5, 3, 6}, true));
  EXPECT_EQ(parse_npy(fortran, "X.npy"), k2x3);
}

TEST(IoNpy, Versions2And3) {
  const std::string data = EncodeAll({1, 2, 3, 4, 5, 6});
  EXPECT_EQ(parse_npy(MakeNpy(Dict("<f8", false, "(2, 3)"), data, 2), "X.npy"), k2x3);
  EXPECT_EQ(parse_npy(MakeNpy(Dict("<f8", false, "(2, 3)"), data, 3), "X.npy"), k2x3);
}

TEST(IoNpy, OneDimensionalIsAColumn) {
  const MatrixXd X = parse_npy(MakeNpy(Dict("<f8", false, "(3,)"), EncodeAll({1, 2, 3})), "X.npy");
  EXPECT_EQ(X, (MatrixXd(3, 1) << 1, 2, 3).finished());
  const MatrixXd F = parse_npy(MakeNpy(Dict("<f8", true, "(3,)"), EncodeAll({1, 2, 3})), "X.npy");
  EXPECT_EQ(F, (MatrixXd(3, 1) << 1, 2, 3).finished());
}

TEST(IoNpy, HeaderVariations) {
  const std::string data = EncodeAll({1, 2, 3, 4, 5, 6});
  for (const std::string dict : {
           "{'shape': (2, 3), 'fortran_order': False, 'descr': '<f8'}",
           "{ 'descr' : '<f8' ,\n 'fortran_order' : False , 'shape' : ( 2 , 3 ) , }",
           "{\"descr\": \"<f8\", \"fortran_order\": False, \"shape\": (2, 3)}",
           "{'descr': '<f8', 'fortran_order': False, 'shape': (2L, 3L), }",  // Python 2
           "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3,), 'extra': [None, 1], }",
       }) {
    EXPECT_EQ(parse_npy(MakeNpy(dict, data), "X.npy"), k2x3) << dict;
  }
  // Without the padding and the final newline.
  EXPECT_EQ(parse_npy(MakeNpy(Dict("<f8", false, "(2, 3)"), data, 1, false), "X.npy"), k2x3);
}

TEST(IoNpy, UnalignedData) {
  // A header whose length is not a multiple of 8 puts the doubles at odd addresses.
  const std::string bytes =
      MakeNpy(Dict("<f8", false, "(2, 3)") + " ", EncodeAll({1, 2, 3, 4, 5, 6}), 1, false);
  EXPECT_EQ(parse_npy(bytes, "X.npy"), k2x3);
}

// ---- Rejected ----------------------------------------------------------------------------------

TEST(IoNpy, TruncatedData) {
  const std::string data = EncodeAll({1, 2, 3, 4, 5, 6});
  ExpectNpyError(
      MakeNpy(Dict("<f8", false, "(12, 8)"), data + data + data + data + data + data.substr(0, 32)),
      "header claims 96 values, file holds 34 (shape is (12, 8))");
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(2, 3)"), data.substr(0, 45)),
                 "header claims 6 values, file holds 5 values and 5 stray bytes (shape is (2, 3))");
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(2, 3)"), ""),
                 "header claims 6 values, file holds 0 (shape is (2, 3))");
}

TEST(IoNpy, TooMuchData) {
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(2, 3)"), EncodeAll({1, 2, 3, 4, 5, 6, 7})),
                 "header claims 6 values, file holds 7 (shape is (2, 3))");
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(2, 3)"), EncodeAll({1, 2, 3, 4, 5, 6}) + "\n"),
                 "header claims 6 values, file holds 6 values and 1 stray byte (shape is (2, 3))");
}

// float32, integers and booleans are converted to double (issue 18: before, only float64 was
// read). The bytes are written here by hand, little- and big-endian, in both orders.
TEST(IoNpy, OtherNumericDtypesAreConverted) {
  const auto bytes_of = [](std::uint64_t bits, int size, bool big) {
    std::string out;
    for (int k = 0; k < size; ++k) out += static_cast<char>((bits >> (8 * (big ? size - 1 - k : k))) & 0xff);
    return out;
  };
  for (const bool big : {false, true}) {
    const std::string order = big ? ">" : "<";
    // int16 -2, 300, -32768, 7 as a 2 x 2 C-order array.
    std::string data;
    for (std::int64_t v : {-2, 300, -32768, 7}) data += bytes_of(static_cast<std::uint64_t>(v), 2, big);
    EXPECT_EQ(parse_npy(MakeNpy(Dict(order + "i2", false, "(2, 2)"), data), "X.npy"),
              (MatrixXd(2, 2) << -2, 300, -32768, 7).finished());
    // The same values in Fortran order: columns first.
    EXPECT_EQ(parse_npy(MakeNpy(Dict(order + "i2", true, "(2, 2)"), data), "X.npy"),
              (MatrixXd(2, 2) << -2, -32768, 300, 7).finished());
    // uint32 4294967295 and int64 -(2^53) read exactly; float32 0.1f widens to 0.1f, not 0.1.
    EXPECT_EQ(parse_npy(MakeNpy(Dict(order + "u4", false, "(1,)"), bytes_of(0xFFFFFFFFu, 4, big)), "X.npy")(0, 0),
              4294967295.0);
    EXPECT_EQ(parse_npy(MakeNpy(Dict(order + "i8", false, "(1,)"),
                                bytes_of(static_cast<std::uint64_t>(-(std::int64_t{1} << 53)), 8, big)),
                        "X.npy")(0, 0),
              -9007199254740992.0);
    std::uint32_t tenth_bits;
    const float tenth = 0.1f;
    std::memcpy(&tenth_bits, &tenth, 4);
    EXPECT_EQ(parse_npy(MakeNpy(Dict(order + "f4", false, "(1,)"), bytes_of(tenth_bits, 4, big)), "X.npy")(0, 0),
              static_cast<double>(tenth));
  }
  EXPECT_EQ(parse_npy(MakeNpy(Dict("|u1", false, "(3,)"), std::string("\x00\x7f\xff", 3)), "X.npy"),
            (MatrixXd(3, 1) << 0, 127, 255).finished());
  EXPECT_EQ(parse_npy(MakeNpy(Dict("|i1", false, "(2,)"), std::string("\x80\x01", 2)), "X.npy"),
            (MatrixXd(2, 1) << -128, 1).finished());
  EXPECT_EQ(parse_npy(MakeNpy(Dict("|b1", false, "(2,)"), std::string("\x01\x00", 2)), "X.npy"),
            (MatrixXd(2, 1) << 1, 0).finished());
  // Sizes are checked in the dtype's own bytes.
  ExpectNpyError(MakeNpy(Dict("<i4", false, "(3,)"), std::string(10, '\0')),
                 "header claims 3 values, file holds 2 values and 2 stray bytes (shape is (3,))");
}

TEST(IoNpy, UnsupportedDtype) {
  const std::string data = EncodeAll({1, 2});
  const std::string also = " is not supported; save as float64 (float32, integers and booleans are read too)";
  ExpectNpyError(MakeNpy(Dict("<f2", false, "(8,)"), data), "dtype '<f2'" + also);
  ExpectNpyError(MakeNpy(Dict("|f8", false, "(2,)"), data), "dtype '|f8'" + also);
  ExpectNpyError(MakeNpy(Dict("<i1", false, "(16,)"), data), "dtype '<i1'" + also);
  ExpectNpyError(MakeNpy(Dict("<c16", false, "(1,)"), data), "dtype '<c16'" + also);
  ExpectNpyError(MakeNpy(Dict("<M8[s]", false, "(2,)"), data), "dtype '<M8[s]'" + also);
  ExpectNpyError(MakeNpy(Dict(std::string(1000, 'f'), false, "(1,)"), data),
                 "dtype '" + std::string(40, 'f') + "...'" + also);
  ExpectNpyError(MakeNpy("{'descr': [('x', '<f8'), ('y', '<f8')], 'fortran_order': False, "
                         "'shape': (1,), }",
                         data),
                 "structured dtypes are not supported; save a plain numeric array");
}

TEST(IoNpy, UnsupportedShape) {
  const std::string data = EncodeAll({1});
  ExpectNpyError(MakeNpy(Dict("<f8", false, "()"), data),
                 "shape () is a single number; save a 1-D or 2-D array");
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(1, 1, 1)"), data),
                 "shape (1, 1, 1) has 3 dimensions; save a 1-D or 2-D array");
  std::string many = "(";
  for (int k = 0; k < 1000; ++k) many += "1, ";
  ExpectNpyError(MakeNpy(Dict("<f8", false, many + ")"), data),
                 "it has 1000 dimensions; save a 1-D or 2-D array");
}

TEST(IoNpy, HugeShapeFailsBeforeAllocating) {
  const std::string data = EncodeAll({1, 2, 3});
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(1000000000000, 1000000000000)"), data),
                 "shape (1000000000000, 1000000000000) is impossibly large; the file holds 3");
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(1000000, 1000000)"), data),
                 "header claims 1000000000000 values, file holds 3 (shape is (1000000, 1000000))");
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(18446744073709551615,)"), data),
                 "header claims 18446744073709551615 values, file holds 3 (shape is "
                 "(18446744073709551615,))");
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(100000000000000000000,)"), data),
                 "shape dimension '100000000000000000000' is too large");
}

TEST(IoNpy, Empty) {
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(0, 3)"), ""), "no data (shape (0, 3))");
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(4, 0)"), ""), "no data (shape (4, 0))");
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(0,)"), ""), "no data (shape (0,))");
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(1000000000000000000, 0)"), ""),
                 "no data (shape (1000000000000000000, 0))");
}

TEST(IoNpy, NonfiniteEntries) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const DataError e = NpyError(MakeNpy(Dict("<f8", false, "(3, 2)"), EncodeAll({1, 2, 3, 4, 5, nan})));
  EXPECT_STREQ(e.what(), "X.npy: entry (3, 2) is NaN (rows and columns counted from 1)");
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(2, 3)"), EncodeAll({1, inf, 3, 4, 5, 6})),
                 "entry (1, 2) is Inf (rows and columns counted from 1)");
  // Fortran order: still named by row and column, the first one row by row.
  ExpectNpyError(MakeNpy(Dict("<f8", true, "(2, 3)"), EncodeAll({1, 4, 2, -inf, 3, nan})),
                 "entry (2, 2) is -Inf (rows and columns counted from 1)");
  ExpectNpyError(MakeNpy(Dict(">f8", false, "(2,)"), EncodeAll({1, nan}, true)),
                 "entry (2, 1) is NaN (rows and columns counted from 1)");
}

TEST(IoNpy, BadMagicAndVersion) {
  ExpectNpyError("", "not a .npy file (it does not start with the .npy magic bytes)");
  ExpectNpyError("1,2,3\n", "not a .npy file (it does not start with the .npy magic bytes)");
  ExpectNpyError("\x93NUMPX\x01\x00", "not a .npy file (it does not start with the .npy magic bytes)");
  ExpectNpyError("\x93NUMPY", "truncated .npy file: the header is incomplete");
  ExpectNpyError(std::string("\x93NUMPY\x01\x00\x10", 9), "truncated .npy file: the header is incomplete");
  ExpectNpyError(std::string("\x93NUMPY\x02\x00\x10\x00\x00", 11),
                 "truncated .npy file: the header is incomplete");
  std::string v4 = MakeNpy(Dict("<f8", false, "(1,)"), EncodeAll({1}), 2);
  v4[6] = 4;
  ExpectNpyError(v4, "unsupported .npy format version 4.0 (1.0, 2.0 and 3.0 are supported)");
  std::string v11 = MakeNpy(Dict("<f8", false, "(1,)"), EncodeAll({1}));
  v11[7] = 1;
  ExpectNpyError(v11, "unsupported .npy format version 1.1 (1.0, 2.0 and 3.0 are supported)");
}

TEST(IoNpy, HeaderLengthPastTheEnd) {
  std::string bytes = MakeNpy(Dict("<f8", false, "(1,)"), "");
  bytes[9] = '\x7F';  // header length 118 = 0x76 becomes 0x7F76
  ExpectNpyError(bytes, "truncated .npy file: the header claims 32630 bytes, but only 118 follow");
  std::string v2 = MakeNpy(Dict("<f8", false, "(1,)"), "", 2);
  v2[11] = '\xFF';
  ExpectNpyError(v2, "truncated .npy file: the header claims 4278190196 bytes, but only 116 follow");
}

TEST(IoNpy, MalformedHeaders) {
  const std::string data = EncodeAll({1, 2});
  const auto expect_malformed = [&data](const std::string& dict, const std::string& problem) {
    ExpectNpyError(MakeNpy(dict, data), "malformed .npy header: " + problem);
  };
  expect_malformed("", "the header does not start with '{'");
  expect_malformed("['descr']", "the header does not start with '{'");
  expect_malformed("{'descr': '<f8', 'fortran_order': False}", "no 'shape' entry");
  expect_malformed("{'fortran_order': False, 'shape': (2,)}", "no 'descr' entry");
  expect_malformed("{'descr': '<f8', 'shape': (2,)}", "no 'fortran_order' entry");
  expect_malformed("{'descr': '<f8', 'fortran_order': 0, 'shape': (2,)}",
                   "'fortran_order' is not True or False");
  expect_malformed("{'descr': 8, 'fortran_order': False, 'shape': (2,)}", "'descr' is not a string");
  expect_malformed("{'descr': '<f8', 'fortran_order': False, 'shape': [2]}", "'shape' is not a tuple");
  expect_malformed("{'descr': '<f8', 'fortran_order': False, 'shape': (-2,)}",
                   "'shape' holds something other than sizes");
  expect_malformed("{'descr': '<f8', 'fortran_order': False, 'shape': ('2',)}",
                   "'shape' holds something other than sizes");
  expect_malformed("{'descr': '<f8, 'fortran_order': False, 'shape': (2,)}",
                   "expected ',' or '}' after the value of 'descr'");
  expect_malformed("{'descr': '<f8', 'fortran_order': False, 'shape': (2,)",
                   "expected ',' or '}' after the value of 'shape'");
  expect_malformed("{'descr': '<f8', 'descr': '<f8', 'fortran_order': False, 'shape': (2,)}",
                   "'descr' appears twice");
  expect_malformed("{'descr' '<f8'}", "expected ':' after 'descr'");
  expect_malformed("{1: 2}", "a key is not a string");
  expect_malformed("{'descr': '<f8', 'fortran_order': False, 'shape': (2,)} x",
                   "unexpected text after the closing '}'");
  expect_malformed("{'descr': '<f8', 'fortran_order': Fals, 'shape': (2,)}", "unexpected character 'F'");
  expect_malformed("{'descr': '<f8', 'fortran_order': False, 'shape': (2,)",
                   "expected ',' or '}' after the value of 'shape'");
  expect_malformed("{'descr': '<f8", "a string has no closing quote");
  expect_malformed("{'descr': ", "it ends early");
  expect_malformed("{'x': -}", "'-' is not followed by digits");
  expect_malformed("{'x': \x01}", "unexpected character byte 0x01");
  expect_malformed("{'x': (2 3)}", "expected ',' or ')'");
  expect_malformed("{'x': " + std::string(5000, '(') + "}", "nested too deeply");
  ExpectNpyError(MakeNpy(Dict("<f8", false, "(1,)") + std::string(20000, ' '), EncodeAll({1})),
                 "malformed .npy header: it is 20086 bytes long (at most 10000 are accepted)");
}

}  // namespace

namespace {

// rows_to_columns: C-order doubles into a column-major matrix, eight rows per column visit plus
// the rows left over, with a flag for NaN and Inf; against the plain index formula.
TEST(IoNpy, RowsToColumnsTransposesAndFlagsNonfinite) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  for (const Eigen::Index count : {0, 1, 7, 8, 9, 37}) {
    for (const Eigen::Index cols : {1, 3, 50}) {
      std::vector<double> rows(static_cast<std::size_t>(count * cols));
      for (double& x : rows) x = normal(rng);
      Eigen::MatrixXd out;
      EXPECT_TRUE(spdfit::io::detail::rows_to_columns(reinterpret_cast<const char*>(rows.data()), count, cols, &out));
      ASSERT_EQ(out.rows(), count);
      ASSERT_EQ(out.cols(), cols);
      for (Eigen::Index i = 0; i < count; ++i) {
        for (Eigen::Index j = 0; j < cols; ++j) EXPECT_EQ(out(i, j), rows[static_cast<std::size_t>(i * cols + j)]);
      }
      if (count == 0) continue;
      // One non-finite value, in a full tile and in the last (possibly partial) one.
      for (const Eigen::Index at : {Eigen::Index{0}, count * cols - 1}) {
        for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                                 -std::numeric_limits<double>::infinity()}) {
          std::vector<double> copy = rows;
          copy[static_cast<std::size_t>(at)] = bad;
          EXPECT_FALSE(spdfit::io::detail::rows_to_columns(reinterpret_cast<const char*>(copy.data()), count, cols, &out))
              << count << " x " << cols << " at " << at;
        }
      }
    }
  }
  // The largest finite double and a subnormal are finite.
  const double edge[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::denorm_min()};
  Eigen::MatrixXd out;
  EXPECT_TRUE(spdfit::io::detail::rows_to_columns(reinterpret_cast<const char*>(edge), 1, 2, &out));
}

}  // namespace
