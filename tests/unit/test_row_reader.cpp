// The streaming reader gives read_table's rows and read_table's errors, however the file is cut
// into blocks of rows and pieces of text.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "file_test_support.hpp"
#include "spdfit/io.hpp"
#include "spdfit/row_reader.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using io::DataError;
using io::RowReader;

class RowReaderTest : public test::ScratchDirectory {};

// Every row of `path` through a RowReader, `block` rows at a time.
MatrixXd ReadAll(const std::string& path, Index block) {
  RowReader reader(path);
  MatrixXd all;
  MatrixXd rows;
  Index total = 0;
  while (const Index k = reader.read(block, &rows)) {
    EXPECT_LE(k, block);
    all.conservativeResize(total + k, rows.cols());
    all.middleRows(total, k) = rows;
    total += k;
  }
  EXPECT_EQ(reader.read(block, &rows), 0) << "reading on after the end gives nothing";
  EXPECT_EQ(reader.rows_read(), static_cast<std::uint64_t>(total));
  return all;
}

// The DataError that `read` throws (a failed test if none).
template <typename Read>
DataError ErrorOf(Read read) {
  try {
    read();
  } catch (const DataError& e) {
    return e;
  }
  ADD_FAILURE() << "no DataError";
  return DataError("", 0, 0, "");
}

void ExpectSameError(const std::string& path, Index block) {
  const DataError whole = ErrorOf([&] { io::read_table(path); });
  const DataError streamed = ErrorOf([&] { ReadAll(path, block); });
  EXPECT_EQ(std::string(streamed.what()), std::string(whole.what()));
  EXPECT_EQ(streamed.line(), whole.line());
  EXPECT_EQ(streamed.column(), whole.column());
}

// Text of `rows` x 3 numbers, comma-separated, with line end `eol`, over a megabyte when rows is
// large (so that it spans several pieces of RowReader::kTextPieceBytes).
std::string Csv(Index rows, const std::string& eol, test::Generator* g) {
  std::ostringstream text;
  text.precision(17);
  for (Index i = 0; i < rows; ++i)
    text << g->normal() << "," << g->normal() * 1e3 << "," << g->normal() << eol;
  return text.str();
}

TEST_F(RowReaderTest, TextGivesReadTablesRowsInAnyBlockSize) {
  test::Generator g(1);
  const std::string path = Write("A.csv", "\xEF\xBB\xBF# a comment\nx,y,z\n" + Csv(40000, "\n", &g));
  const MatrixXd expected = io::read_matrix(path);
  ASSERT_GT(std::filesystem::file_size(path), 2 * RowReader::kTextPieceBytes);
  for (Index block : {3, 4096, 100000}) {  // block 1 is tested on shorter data in test_stream.cpp
    EXPECT_EQ(ReadAll(path, block), expected) << "block " << block;  // the same parser: bitwise equal
  }
  RowReader reader(path);
  MatrixXd rows;
  reader.read(1, &rows);
  EXPECT_EQ(reader.columns(), 3);
  EXPECT_EQ(reader.column_names(), (std::vector<std::string>{"x", "y", "z"}));
}

// A CR LF line end split between two pieces is one line end, not an empty line and a CR.
TEST_F(RowReaderTest, CrLfAcrossAPieceBoundaryIsOneLineEnd) {
  const std::string line = "1.5,2.5\r\n";  // 9 bytes; its CR at offset 7
  // A comment line of c bytes first, so that some row's CR is the piece's last byte:
  // c + 9k + 7 = kTextPieceBytes - 1.
  const std::size_t piece = RowReader::kTextPieceBytes;
  const std::size_t c = (piece - 8) % 9 + 9;
  std::string text = "#" + std::string(c - 3, 'x') + "\r\n";
  while (text.size() < 2 * piece) text += line;
  ASSERT_EQ(text[piece - 1], '\r');
  ASSERT_EQ(text[piece], '\n');
  const std::string path = Write("B.csv", text);
  const MatrixXd expected = io::read_matrix(path);
  EXPECT_EQ(ReadAll(path, 1000), expected);
  // The same with lone CRs (old Mac line ends) cut at the boundary.
  std::string mac = text;
  for (char& ch : mac) ch = ch == '\n' ? ' ' : ch;
  const std::string mac_path = Write("C.csv", mac);
  EXPECT_EQ(ReadAll(mac_path, 1000), io::read_matrix(mac_path));
}

TEST_F(RowReaderTest, BadTextDeepInTheFileFailsAsReadTableDoes) {
  test::Generator g(2);
  const std::string good = Csv(60000, "\n", &g);
  ExpectSameError(Write("token.csv", good + "1,2,oops\n" + good), 1000);
  ExpectSameError(Write("ragged.csv", good + "1,2\n"), 1000);
  ExpectSameError(Write("nan.csv", good + "1,nan,3\n"), 1000);
  ExpectSameError(Write("binary.csv", good + std::string("1,2,\0\n", 6)), 1000);
  ExpectSameError(Write("header_only.csv", "x,y\n"), 10);
  ExpectSameError(Write("comments_only.csv", "# nothing\n"), 10);
  ExpectSameError(Write("empty.csv", ""), 10);
  ExpectSameError(Path("missing.csv"), 10);
  ExpectSameError(dir_.string(), 10);
  const DataError e = ErrorOf([&] { ReadAll(Write("t.csv", good + "1,2,oops\n"), 1000); });
  EXPECT_EQ(e.line(), 60001u);
}

TEST_F(RowReaderTest, AnEndlessLineIsRefused) {
  const std::string path =
      Write("long.csv", std::string(RowReader::kMaxLineBytes + 3 * RowReader::kTextPieceBytes, '1'));
  const DataError e = ErrorOf([&] { ReadAll(path, 10); });
  EXPECT_EQ(e.line(), 1u);
  EXPECT_NE(std::string(e.what()).find("longer than"), std::string::npos) << e.what();
}

// A .npy header by hand, for layouts write_npy does not produce.
std::string NpyBytes(const std::string& dict, const std::string& data) {
  std::string header = dict;
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string bytes = "\x93NUMPY\x01";
  bytes += '\0';
  bytes += static_cast<char>(header.size() & 0xFF);
  bytes += static_cast<char>(header.size() >> 8);
  return bytes + header + data;
}

TEST_F(RowReaderTest, NpyInBothOrdersGivesReadTablesRows) {
  test::Generator g(3);
  const MatrixXd M = g.gaussian(10007, 4);
  const std::string c_order = Path("c.npy");
  io::write_npy(c_order, M);
  std::string column_major(reinterpret_cast<const char*>(M.data()), sizeof(double) * M.size());
  const std::string fortran = Write(
      "f.npy", NpyBytes("{'descr': '<f8', 'fortran_order': True, 'shape': (10007, 4), }", column_major));
  std::string big(column_major);
  for (std::size_t k = 0; k < big.size(); k += 8) std::reverse(big.begin() + k, big.begin() + k + 8);
  const std::string big_endian =
      Write("b.npy", NpyBytes("{'descr': '>f8', 'fortran_order': True, 'shape': (10007, 4), }", big));
  // Big-endian in C order too: read by blocks into a buffer (pread), then converted.
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> row_major = M;
  std::string big_rows(reinterpret_cast<const char*>(row_major.data()), sizeof(double) * M.size());
  for (std::size_t k = 0; k < big_rows.size(); k += 8) std::reverse(big_rows.begin() + k, big_rows.begin() + k + 8);
  const std::string big_endian_c =
      Write("bc.npy", NpyBytes("{'descr': '>f8', 'fortran_order': False, 'shape': (10007, 4), }", big_rows));
  for (const std::string& path : {c_order, fortran, big_endian, big_endian_c}) {
    EXPECT_EQ(io::read_matrix(path), M) << path;
    for (Index block : {1, 999, 20000}) EXPECT_EQ(ReadAll(path, block), M) << path << " block " << block;
  }
  // int32 (C order) and float32 (Fortran order) stream as they read whole: converted to double.
  std::string ints, floats;
  MatrixXd int_values(10007, 4), float_values(10007, 4);
  for (Index i = 0; i < 10007; ++i) {
    for (Index j = 0; j < 4; ++j) {
      const auto v = static_cast<std::int32_t>(std::lround(M(i, j) * 1e6));
      ints.append(reinterpret_cast<const char*>(&v), 4);
      int_values(i, j) = v;
    }
  }
  for (Index j = 0; j < 4; ++j) {
    for (Index i = 0; i < 10007; ++i) {
      const auto v = static_cast<float>(M(i, j));
      floats.append(reinterpret_cast<const char*>(&v), 4);
      float_values(i, j) = v;
    }
  }
  const std::string i4 = Write("i4.npy", NpyBytes("{'descr': '<i4', 'fortran_order': False, 'shape': (10007, 4), }", ints));
  const std::string f4 = Write("f4.npy", NpyBytes("{'descr': '<f4', 'fortran_order': True, 'shape': (10007, 4), }", floats));
  for (Index block : {1, 999, 20000}) {
    EXPECT_EQ(ReadAll(i4, block), int_values) << block;
    EXPECT_EQ(ReadAll(f4, block), float_values) << block;
  }
  EXPECT_EQ(io::read_matrix(f4), float_values);
}

TEST_F(RowReaderTest, BadNpyFailsAsReadTableDoes) {
  test::Generator g(4);
  MatrixXd M = g.gaussian(5000, 3);
  M(4321, 1) = std::numeric_limits<double>::quiet_NaN();
  const std::string nan = Path("nan.npy");
  io::write_npy(nan, M);
  ExpectSameError(nan, 1000);
  const DataError e = ErrorOf([&] { ReadAll(nan, 1000); });
  EXPECT_NE(std::string(e.what()).find("entry (4322, 2) is NaN"), std::string::npos) << e.what();
  ExpectSameError(
      Write("short.npy", NpyBytes("{'descr': '<f8', 'fortran_order': False, 'shape': (1000, 3), }",
                                  std::string(8 * 2999, '\0'))),
      100);
  ExpectSameError(Write("complex.npy", NpyBytes("{'descr': '<c16', 'fortran_order': False, 'shape': (2, 2), }",
                                                std::string(64, '\0'))),
                  100);
  ExpectSameError(Write("int.npy", NpyBytes("{'descr': '<i4', 'fortran_order': False, 'shape': (2, 2), }",
                                            std::string(15, '\0'))),
                  100);
  ExpectSameError(Write("huge.npy", NpyBytes("{'descr': '<f8', 'fortran_order': False, "
                                             "'shape': (1000000000000, 1000000000000), }",
                                             std::string(16, '\0'))),
                  100);
}

}  // namespace
}  // namespace spdfit

namespace spdfit {
namespace {

// Column selections (ReadOptions::columns): the streaming reader in any block size gives what
// read_table gives, the selected columns in the selections' order, text columns not selected
// skipped unparsed, and the selections' 1-based columns.
TEST_F(RowReaderTest, ColumnSelectionsStreamAsReadTableReadsThem) {
  std::string text = "time,a,b,c,note\n";
  for (int i = 0; i < 50; ++i) {
    text += "10:00:" + std::to_string(i) + "," + std::to_string(i) + "," + std::to_string(2 * i) + "," +
            std::to_string(3 * i) + ",text\n";
  }
  const std::string path = Write("log.csv", text);
  io::ReadOptions options;
  options.columns = {{"c,a", "a_cols"}, {"3", "b_cols"}};
  const io::Table table = io::read_table(path, options);
  ASSERT_EQ(table.values.cols(), 3);
  EXPECT_EQ(table.values(7, 0), 21.0);
  EXPECT_EQ(table.values(7, 1), 7.0);
  EXPECT_EQ(table.values(7, 2), 14.0);
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"c", "a", "b"}));
  EXPECT_EQ(table.selected_columns, (std::vector<std::vector<std::size_t>>{{4, 2}, {3}}));
  for (Index block : {1, 7, 64}) {
    RowReader reader(path, options);
    MatrixXd all, rows;
    Index total = 0;
    while (const Index k = reader.read(block, &rows)) {
      all.conservativeResize(total + k, rows.cols());
      all.middleRows(total, k) = rows;
      total += k;
    }
    EXPECT_EQ(all, table.values) << block;
    EXPECT_EQ(reader.selected_columns(), table.selected_columns);
  }
  EXPECT_EQ(io::describe_columns({2, 3, 4}, {"a", "b", "c"}), "columns a..c (2-4)");
  EXPECT_EQ(io::describe_columns({4, 2}, {}), "columns 4, 2");
  EXPECT_THROW(io::check_column_selection({"3:1", "a_cols"}), io::ColumnSelectionError);
  options.columns = {{"a:c", "a_cols"}, {"c", "b_cols"}};
  EXPECT_THROW(io::read_table(path, options), io::ColumnSelectionError);
}

// The same selection picks the same columns from a list of names (a DataFrame's) as from a file
// with that header: the file's reader is the reference.
TEST_F(RowReaderTest, SelectColumnsOnNamesIsTheFilesSelection) {
  const std::vector<std::string> names{"time", "a", "b", "c", "note"};
  const std::string path = Write("named.csv", "time,a,b,c,note\n1,2,3,4,5\n6,7,8,9,10\n");
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{{"c,a", "3"}, {"a:b", "4"}, {"2:3", "c"}}) {
    io::ReadOptions options;
    options.columns = {{a, "a_cols"}, {b, "b_cols"}};
    EXPECT_EQ(io::select_columns(options.columns, names, "the table"), io::read_table(path, options).selected_columns)
        << a << " " << b;
  }
  try {
    io::select_columns({{"a:z", "a_cols"}}, names, "the table");
    ADD_FAILURE() << "no error";
  } catch (const io::ColumnSelectionError& e) {
    EXPECT_NE(std::string(e.what()).find("no column named z in the table; its columns: time, a, b, c, note"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(io::select_columns({{"a:b", "a_cols"}, {"b", "b_cols"}}, names, "the table"), io::ColumnSelectionError);
  EXPECT_THROW(io::select_columns({{"6", "a_cols"}}, names, "the table"), io::ColumnSelectionError);
}

}  // namespace
}  // namespace spdfit
