// parse_delimited: every accepted variation of delimited text, and every rejected one with the
// position and wording of its error.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "io_test_support.hpp"
#include "spdfit/io.hpp"

namespace {

using Eigen::MatrixXd;
using spdfit::io::DataError;
using spdfit::io::parse_delimited;
using spdfit::io::ReadOptions;
using spdfit::io::Table;

using spdfit::io::test::ExpectError;
using spdfit::io::test::Parse;
using spdfit::io::test::ParseError;

std::uint64_t Bits(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof(bits));
  return bits;
}

const MatrixXd k2x3 = (MatrixXd(2, 3) << 1, 2, 3, 4, 5, 6).finished();

// ---- Accepted ----------------------------------------------------------------------------------

TEST(IoDelimited, Comma) { EXPECT_EQ(Parse("1,2,3\n4,5,6\n"), k2x3); }

TEST(IoDelimited, CommaWithSpacesAroundIt) {
  EXPECT_EQ(Parse("1, 2, 3\n4 ,5 ,  6\n"), k2x3);
  EXPECT_EQ(Parse("1,\t2,3\n4\t,5,6\n"), k2x3);
}

TEST(IoDelimited, Semicolon) { EXPECT_EQ(Parse("1;2;3\n4; 5 ;6\n"), k2x3); }

TEST(IoDelimited, Tab) { EXPECT_EQ(Parse("1\t2\t3\n4\t5\t6\n"), k2x3); }

TEST(IoDelimited, RunsOfSpaces) { EXPECT_EQ(Parse("1  2     3\n   4 5 6   \n"), k2x3); }

TEST(IoDelimited, MatlabSaveAscii) {
  // What MATLAB's `save -ascii` writes: "%16.7e" per value, so leading spaces and runs of them.
  const char* text =
      "   1.0000000e+00   2.5000000e+00  -3.0000000e+00\n"
      "   4.0000000e-01  -5.0000000e+10   6.0000000e-12\n";
  const MatrixXd expected = (MatrixXd(2, 3) << 1, 2.5, -3, 0.4, -5e10, 6e-12).finished();
  EXPECT_EQ(Parse(text), expected);
}

TEST(IoDelimited, MatlabSaveAsciiDouble) {
  const char* text = "   3.141592653589793e+00   2.718281828459045e+00\n";
  const MatrixXd X = Parse(text);
  ASSERT_EQ(X.rows(), 1);
  EXPECT_EQ(X(0, 0), 3.141592653589793);
  EXPECT_EQ(X(0, 1), 2.718281828459045);
}

TEST(IoDelimited, MatlabSaveAsciiTabs) {
  // save -ascii -tabs: the same padded fields, separated by tabs.
  const char* text = "   1.0000000e+00\t   2.0000000e+00\n   3.0000000e+00\t   4.0000000e+00\n";
  EXPECT_EQ(Parse(text), (MatrixXd(2, 2) << 1, 2, 3, 4).finished());
}

TEST(IoDelimited, LineEnds) {
  EXPECT_EQ(Parse("1,2,3\r\n4,5,6\r\n"), k2x3);
  EXPECT_EQ(Parse("1,2,3\r4,5,6\r"), k2x3);  // old Mac spreadsheets
  EXPECT_EQ(Parse("1,2,3\n4,5,6"), k2x3);    // no line end at the end
  EXPECT_EQ(Parse("1,2,3\r\n\r\n4,5,6\n\n\n"), k2x3);
}

TEST(IoDelimited, ByteOrderMark) {
  EXPECT_EQ(Parse("\xEF\xBB\xBF"
                  "1,2,3\n4,5,6\n"),
            k2x3);
  const Table table = parse_delimited("\xEF\xBB\xBFx,y\r\n1,2\r\n", "A.csv");
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"x", "y"}));
}

TEST(IoDelimited, CommentsAndBlankLines) {
  const char* text =
      "# written by a logger\n"
      "% MATLAB comment\n"
      "\n"
      "   \t \n"
      "1,2,3\n"
      "   # indented comment, 7, 8\n"
      "4,5,6\n"
      "%\n";
  EXPECT_EQ(Parse(text), k2x3);
}

TEST(IoDelimited, HeaderRow) {
  const Table table = parse_delimited("time, force ,torque\n1,2,3\n4,5,6\n", "A.csv");
  EXPECT_EQ(table.values, k2x3);
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"time", "force", "torque"}));
}

TEST(IoDelimited, NoHeaderMeansNoNames) {
  EXPECT_TRUE(parse_delimited("1,2\n", "A.csv").column_names.empty());
}

TEST(IoDelimited, HeaderAfterComments) {
  const Table table = parse_delimited("# units: SI\n\na;b\n1;2\n", "A.csv");
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(table.values, (MatrixXd(1, 2) << 1, 2).finished());
}

TEST(IoDelimited, QuotedHeaderNames) {
  const Table table = parse_delimited("\"x, mm\",\"say \"\"hi\"\"\", \"1\"\n1,2,3\n", "A.csv");
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"x, mm", "say \"hi\"", "1"}));
}

TEST(IoDelimited, QuotedHeaderNamesWithSpaces) {
  const Table table = parse_delimited("\"sensor a\"  \"sensor b\"\n1 2\n", "A.csv");
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"sensor a", "sensor b"}));
}

TEST(IoDelimited, SpaceSeparatedHeader) {
  const Table table = parse_delimited("t   x   y\n1 2 3\n4 5 6\n", "A.csv");
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"t", "x", "y"}));
  EXPECT_EQ(table.values, k2x3);
}

TEST(IoDelimited, SingleColumnHeaderWithSpaces) {
  const Table table = parse_delimited("Force (N)\n1.5\n2.5\n", "A.csv");
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"Force (N)"}));
  EXPECT_EQ(table.values, (MatrixXd(2, 1) << 1.5, 2.5).finished());
}

TEST(IoDelimited, SingleNameHeaderOverSeparatedData) {
  const Table table = parse_delimited("force\n1.5\n", "A.csv");
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"force"}));
}

TEST(IoDelimited, HeaderWithEmptyIndexName) {
  // pandas' DataFrame.to_csv() writes the index with an empty name: the first column is row
  // labels, dropped with a warning (issue 18: it was read as data, a 3-column A for 2 columns).
  const Table table = parse_delimited(",a,b\n0,1.5,2.5\n1,3.5,4.5\n", "A.csv");
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(table.values, (MatrixXd(2, 2) << 1.5, 2.5, 3.5, 4.5).finished());
  ASSERT_EQ(table.warnings.size(), 1u);
  EXPECT_NE(table.warnings[0].text.find("A.csv: the first column holds row labels"), std::string::npos);
}

TEST(IoDelimited, IndexColumnsOfPandasAndR) {
  // pandas' default column names are numbers; df.cov().to_csv() labels rows with text; R's
  // write.csv quotes the labels and the header, whose first cell is "".
  const Table numbered = parse_delimited(",0,1\n0,1.5,2.5\n1,3.5,4.5\n", "A.csv");
  EXPECT_EQ(numbered.column_names, (std::vector<std::string>{"0", "1"}));
  EXPECT_EQ(numbered.values, (MatrixXd(2, 2) << 1.5, 2.5, 3.5, 4.5).finished());
  const Table cov = parse_delimited(",x1,x2\nx1,2.0,0.5\nx2,0.5,1.0\n", "C.csv");
  EXPECT_EQ(cov.values, (MatrixXd(2, 2) << 2.0, 0.5, 0.5, 1.0).finished());
  const Table r = parse_delimited("\"\",\"x1\",\"x2\"\n\"1\",2.0,0.5\n\"2\",0.5,1.0\n", "C.csv");
  EXPECT_EQ(r.column_names, (std::vector<std::string>{"x1", "x2"}));
  EXPECT_EQ(r.values, cov.values);
  // Said explicitly: labels dropped without a header, or the first column kept as data.
  ReadOptions drop, keep;
  drop.index_column = spdfit::io::IndexColumn::Drop;
  keep.index_column = spdfit::io::IndexColumn::Keep;
  EXPECT_EQ(parse_delimited("a,1,2\nb,3,4\n", "A.csv", drop).values, (MatrixXd(2, 2) << 1, 2, 3, 4).finished());
  // (Its first line 0,1 taken as data too: pandas' header of an unnamed frame otherwise.)
  ReadOptions keep_all = keep;
  keep_all.header_row = spdfit::io::HeaderRow::Absent;
  EXPECT_EQ(parse_delimited("0,1\n1,2\n2,3\n", "A.csv", keep_all).values.rows(), 3);
  EXPECT_TRUE(parse_delimited("0,1\n1,2\n2,3\n", "A.csv", keep_all).warnings.empty());
  EXPECT_EQ(parse_delimited("0,1\n1,2\n2,3\n", "A.csv", keep).values.rows(), 2);
}

TEST(IoDelimited, RowNumbersInTheFirstColumnAreRefused) {
  // Under a header without the empty first cell (index_label='i'), or no header at all.
  ExpectError("i,a,b\n0,1.5,2.5\n1,3.5,4.5\n2,5.5,6.5\n", 2, 1,
              "the first column is 0, 1, 2, ...: row numbers (an index, as pandas' to_csv writes one), not "
              "data? Drop it with --index-col (Python: index_col=True), or read it as data with "
              "--no-index-col (index_col=False)");
  EXPECT_THROW(parse_delimited("0,7\n1,8\n2,9\n", "A.csv"), DataError);
  // Fewer than three rows, one column, or any other first column: data as before.
  EXPECT_EQ(parse_delimited("0,7\n1,8\n", "A.csv").values.cols(), 2);
  EXPECT_EQ(parse_delimited("0\n1\n2\n", "A.csv").values.rows(), 3);
  EXPECT_EQ(parse_delimited("1,7\n2,8\n3,9\n", "A.csv").values.cols(), 2);
}

TEST(IoDelimited, NumberSpellings) {
  const MatrixXd X = Parse("+1,-2,+2.5e+3,1E-3,.5,5.,-0.0,0001.5000,1e-320,1e-400,-1e-400\n");
  ASSERT_EQ(X.cols(), 11);
  EXPECT_EQ(X(0, 0), 1.0);
  EXPECT_EQ(X(0, 1), -2.0);
  EXPECT_EQ(X(0, 2), 2500.0);
  EXPECT_EQ(X(0, 3), 1e-3);
  EXPECT_EQ(X(0, 4), 0.5);
  EXPECT_EQ(X(0, 5), 5.0);
  EXPECT_EQ(Bits(X(0, 6)), Bits(-0.0));
  EXPECT_EQ(X(0, 7), 1.5);
  EXPECT_EQ(X(0, 8), 1e-320);  // a denormal
  EXPECT_GT(X(0, 8), 0.0);
  EXPECT_EQ(Bits(X(0, 9)), Bits(0.0));  // below the smallest denormal: zero, as strtod gives
  EXPECT_EQ(Bits(X(0, 10)), Bits(-0.0));
}

TEST(IoDelimited, ExactValues) {
  const MatrixXd X = Parse("0.1,0.2,0.30000000000000004,1.7976931348623157e308,4.9e-324\n");
  EXPECT_EQ(X(0, 0), 0.1);
  EXPECT_EQ(X(0, 1), 0.2);
  EXPECT_EQ(X(0, 2), 0.1 + 0.2);
  EXPECT_EQ(X(0, 3), std::numeric_limits<double>::max());
  EXPECT_EQ(X(0, 4), std::numeric_limits<double>::denorm_min());
}

TEST(IoDelimited, OneByOne) {
  EXPECT_EQ(Parse("42"), (MatrixXd(1, 1) << 42).finished());
  EXPECT_EQ(Parse("  -7.5  \r\n"), (MatrixXd(1, 1) << -7.5).finished());
}

TEST(IoDelimited, SingleColumn) { EXPECT_EQ(Parse("1\n2\n3\n"), (MatrixXd(3, 1) << 1, 2, 3).finished()); }

TEST(IoDelimited, SingleRow) { EXPECT_EQ(Parse("1 2 3"), (MatrixXd(1, 3) << 1, 2, 3).finished()); }

TEST(IoDelimited, LongLine) {
  constexpr int kColumns = 200000;
  std::string text;
  // 1, 2, ...: 0, 1, ... would be pandas' header of an unnamed frame.
  for (int j = 0; j < kColumns; ++j) text += std::to_string(j + 1) + (j + 1 < kColumns ? "," : "\n");
  text += text;
  const MatrixXd X = Parse(text);
  ASSERT_EQ(X.rows(), 2);
  ASSERT_EQ(X.cols(), kColumns);
  EXPECT_EQ(X(1, kColumns - 1), kColumns);
  EXPECT_EQ(X(0, 12345), 12346);
}

TEST(IoDelimited, ManyRows) {
  std::string text;
  // (The first column starts at 1: 0, 1, 2, ... would be row numbers, which are refused.)
  for (int i = 0; i < 50000; ++i) text += std::to_string(i + 1) + "\t" + std::to_string(-i) + "\n";
  const MatrixXd X = Parse(text);
  ASSERT_EQ(X.rows(), 50000);
  EXPECT_EQ(X(49999, 1), -49999);
}

TEST(IoDelimited, Utf8TextInHeader) {
  const Table table = parse_delimited("Température;Kraft µN\n1;2\n", "A.csv");
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"Température", "Kraft µN"}));
}

// An empty field is pandas' NaN: NaN where NaN is allowed (the error's message says so otherwise).
TEST(IoDelimited, AnEmptyFieldIsNanWhenNanIsAllowed) {
  ReadOptions options;
  options.allow_nonfinite = true;
  const MatrixXd X = Parse("1,,3\n,5,\n", options);
  ASSERT_EQ(X.rows(), 2);
  ASSERT_EQ(X.cols(), 3);
  EXPECT_EQ(X(0, 0), 1.0);
  EXPECT_TRUE(std::isnan(X(0, 1)));
  EXPECT_TRUE(std::isnan(X(1, 0)));
  EXPECT_EQ(X(1, 1), 5.0);
  EXPECT_TRUE(std::isnan(X(1, 2)));
}

TEST(IoDelimited, NonfiniteWhenAllowed) {
  ReadOptions options;
  options.allow_nonfinite = true;
  const MatrixXd X = Parse("nan,NaN,inf,-Inf,Infinity,1e999,-1e999,+inf\n", options);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(std::isnan(X(0, 0)));
  EXPECT_TRUE(std::isnan(X(0, 1)));
  EXPECT_EQ(X(0, 2), inf);
  EXPECT_EQ(X(0, 3), -inf);
  EXPECT_EQ(X(0, 4), inf);
  EXPECT_EQ(X(0, 5), inf);
  EXPECT_EQ(X(0, 6), -inf);
  EXPECT_EQ(X(0, 7), inf);
}

// ---- Rejected ----------------------------------------------------------------------------------

TEST(IoDelimited, NotANumber) {
  const DataError e = ParseError("1,2,3\n4,5,6\n7,abc,9\n");
  EXPECT_STREQ(e.what(), "A.csv:3:3: 'abc' is not a number");
  ExpectError("1,2\n3,1.5abc\n", 2, 3, "'1.5abc' is not a number");
  // A log's timestamp in the first column: the message names --index-col and --a-cols.
  ExpectError("t,a\n2024-01-31T10:15:02,1.5\n", 2, 1,
              "'2024-01-31T10:15:02' is not a number; a timestamp in the first column? --index-col drops it "
              "(Python: index_col=True), or --a-cols and --b-cols choose the columns of A and B (Python: a_cols, "
              "b_cols)");
  ExpectError("1 2\n3 1e\n", 2, 3, "'1e' is not a number");
  ExpectError("1 2\n3 0x10\n", 2, 3, "'0x10' is not a number");
  ExpectError("1 2\n3 1.5.2\n", 2, 3, "'1.5.2' is not a number");
  ExpectError("1 2\n3 --1\n", 2, 3, "'--1' is not a number");
  ExpectError("1 2\n3 +-1\n", 2, 3, "'+-1' is not a number");
  ExpectError("1 2\n3 ++1\n", 2, 3, "'++1' is not a number");
  ExpectError("1 2\n3 +\n", 2, 3, "'+' is not a number");
  ExpectError("1 2\n3 infinit\n", 2, 3, "'infinit' is not a number");
}

TEST(IoDelimited, ColumnCountsCharactersOfTheRawLine) {
  ExpectError("1,2\n   1,  abc\n", 2, 8, "'abc' is not a number");
  ExpectError("1\t2\n\t4\t x\n", 2, 5, "'x' is not a number");
  // Columns count characters, not bytes: 'ä' is two bytes but one column.
  ExpectError("1;2\n1; ä\n", 2, 4, "'ä' is not a number");
  ExpectError("1;2;3\n1;2;ää\n", 2, 5, "'ää' is not a number");
  // The byte-order mark is not a column.
  ExpectError(
      "\xEF\xBB\xBF"
      "x,1\n",
      1, 1, "'x' is not a number");
}

TEST(IoDelimited, FirstLineMixingNumbersAndTextIsData) {
  ExpectError("1,abc,3\n4,5,6\n", 1, 3, "'abc' is not a number");
  ExpectError("sensor 1\n2\n", 1, 1, "'sensor' is not a number");
}

TEST(IoDelimited, DecimalComma) {
  ExpectError("1;2\n1,5;3\n", 2, 1, "'1,5' is not a number (decimal comma? use '.' for decimals)");
}

TEST(IoDelimited, EmptyFields) {
  ExpectError("1,,3\n", 1, 3, "empty field: nothing between two ','; a missing value? pandas' to_csv writes NaN as an empty field (drop such rows first)");
  ExpectError("1, ,3\n", 1, 4, "empty field: nothing between two ','; a missing value? pandas' to_csv writes NaN as an empty field (drop such rows first)");
  ExpectError("1,2,3\n4,5,\n", 2, 4, "empty field: the line ends with ','; a missing value? pandas' to_csv writes NaN as an empty field (drop such rows first)");
  ExpectError("1,2,3\n4,5, \n", 2, 4, "empty field: the line ends with ','; a missing value? pandas' to_csv writes NaN as an empty field (drop such rows first)");
  ExpectError("1;2;3\n;5;6\n", 2, 1, "empty field: the line starts with ';'; a missing value? pandas' to_csv writes NaN as an empty field (drop such rows first)");
  ExpectError("1\t2\t3\n4\t\t6\n", 2, 3, "empty field: nothing between two tabs; a missing value? pandas' to_csv writes NaN as an empty field (drop such rows first)");
  ExpectError("a,b\n1,,\n", 2, 3, "empty field: nothing between two ','; a missing value? pandas' to_csv writes NaN as an empty field (drop such rows first)");
}

TEST(IoDelimited, NaNAndInfRejected) {
  ExpectError("1,2\nnan,3\n", 2, 1, "NaN is not allowed");
  EXPECT_STREQ(ParseError("1,2\nNaN,3\n").what(), "A.csv:2:1: NaN is not allowed");
  ExpectError("1,NAN\n", 1, 3, "NaN is not allowed");
  ExpectError("1,-nan\n", 1, 3, "NaN is not allowed");
  ExpectError("1,nan(123)\n", 1, 3, "NaN is not allowed");
  ExpectError("1,inf\n", 1, 3, "Inf is not allowed");
  ExpectError("1,+inf\n", 1, 3, "Inf is not allowed");
  ExpectError("1,-Inf\n", 1, 3, "-Inf is not allowed");
  ExpectError("1,Infinity\n", 1, 3, "Inf is not allowed");
  ExpectError("1,-INFINITY\n", 1, 3, "-Inf is not allowed");
  // A first row of missing values is data, not a header.
  ExpectError("NaN,NaN\n1,2\n", 1, 1, "NaN is not allowed");
}

TEST(IoDelimited, OverflowRejected) {
  ExpectError("1,1e999\n", 1, 3, "'1e999' is too large for a double (it would be Inf)");
  ExpectError("1,-1e999\n", 1, 3, "'-1e999' is too large for a double (it would be -Inf)");
  ExpectError("1,+1.8e308\n", 1, 3, "'+1.8e308' is too large for a double (it would be Inf)");
  ExpectError("1,0.001e312\n", 1, 3, "'0.001e312' is too large for a double (it would be Inf)");
  EXPECT_EQ(Parse("1,0.0001e312\n")(0, 1), 1e308);
}

TEST(IoDelimited, RaggedRows) {
  const DataError e = ParseError("# data\n1,2,3,4,5,6\n1,2,3,4,5,6\n1,2,3,4,5\n");
  EXPECT_STREQ(e.what(), "A.csv:4: row has 5 fields, expected 6 (as in line 2)");
  EXPECT_EQ(e.line(), 4u);
  EXPECT_EQ(e.column(), 0u);
  ExpectError("1 2\n3 4 5\n", 2, 0, "row has 3 fields, expected 2 (as in line 1)");
  ExpectError("1 2\n3\n", 2, 0, "row has 1 field, expected 2 (as in line 1)");
  ExpectError("a,b,c\n1,2,3\n4,5,6,7\n", 3, 0, "row has 4 fields, expected 3 (as in line 1)");
  ExpectError("a,b\n1,2,3\n", 2, 0, "row has 3 fields, expected 2 (as in line 1)");
  ExpectError("force\n1\t2\n", 2, 0, "row has 2 fields, expected 1 (as in line 1)");
}

TEST(IoDelimited, MixedSeparators) {
  ExpectError("1,2\n3;4\n", 2, 2,
              "found ';' here, but fields in this file are separated by ',' (see line 1)");
  ExpectError("1 2\n3,4\n", 2, 2,
              "found ',' here, but fields in this file are separated by spaces (see line 1)");
  ExpectError("1 2\n3\t4\n", 2, 2,
              "found a tab here, but fields in this file are separated by spaces (see line 1)");
  ExpectError("1,2\n3\t4\n", 2, 2,
              "found a tab here, but fields in this file are separated by ',' (see line 1)");
  ExpectError("1\t2\n3 4\n", 2, 1,
              "'3 4' is not a number; fields in this file are separated by tabs (see line 1)");
  ExpectError("1\n2,3\n", 2, 2, "found ',' here, but line 1 has a single field");
  ExpectError("a,b\n1 2\n", 2, 0, "this line separates fields with spaces, but the header (line 1) uses ','");
}

TEST(IoDelimited, Quotes) {
  // Quoted numbers in data rows read as numbers (issue 18: this reverses the earlier refusal of
  // '"2"'); quoted text, or nothing between the quotes, is still an error naming the column.
  const Table quoted = parse_delimited("1,\"2\"\n\" -3.5e2 \",\"4\"\n", "A.csv", {});
  ASSERT_EQ(quoted.values.rows(), 2);
  EXPECT_EQ(quoted.values(0, 1), 2.0);
  EXPECT_EQ(quoted.values(1, 0), -350.0);
  ExpectError("1,\"x\"\n", 1, 3, "'\"x\"' is quoted text, not a number");
  const DataError empty = ParseError("1,2\n3,\"\"\n");
  EXPECT_EQ(empty.line(), 2u);
  EXPECT_NE(empty.problem().find("empty field"), std::string::npos) << empty.what();
  ExpectError("1,2\n\"NaN\",4\n", 2, 1, "NaN is not allowed");
  // A first line whose quoted fields are numbers, beside an empty first cell, is R's write.csv
  // header "","1","2": its empty cell marks a column of row labels.
  const Table r = parse_delimited("\"\",\"1\",\"2\"\n\"a\",\"3\",4\n\"b\",5,6\n", "A.csv", {});
  ASSERT_EQ(r.values.rows(), 2);
  ASSERT_EQ(r.values.cols(), 2);
  EXPECT_EQ(r.column_names, (std::vector<std::string>{"1", "2"}));
  EXPECT_EQ(r.values(0, 0), 3.0);
  ExpectError("\"a,b\n1,2\n", 1, 1, "missing closing quote");
  ExpectError("\"a\"x,b\n1,2\n", 1, 4, "unexpected text after closing quote");
  ExpectError("\"a\"x b\n1 2\n", 1, 4, "unexpected text after closing quote");
}

// Issue 42: a first row whose every field reads as a number, quoted or not, is data (an export
// that quotes every cell); quoted names beside quoted numbers make a header; quoted 1, 2, ..., k
// is data, with a warning (R's write.csv quotes numbered names so).
TEST(IoDelimited, QuotedNumbersInTheFirstRowAreData) {
  const Table all = parse_delimited("\"2.04\",\"-1\"\n\"3\",\"4\"\n\"5\",\"6e-1\"\n", "A.csv", {});
  ASSERT_EQ(all.values.rows(), 3);
  EXPECT_EQ(all.values(0, 0), 2.04);
  EXPECT_TRUE(all.column_names.empty());
  EXPECT_TRUE(all.warnings.empty());
  const Table mixed = parse_delimited("\"t\",\"1\"\n3,4\n", "A.csv", {});
  ASSERT_EQ(mixed.values.rows(), 1);
  EXPECT_EQ(mixed.column_names, (std::vector<std::string>{"t", "1"}));
  const Table numbered = parse_delimited("\"1\",\"2\",\"3\"\n4,5,6\n", "A.csv", {});
  ASSERT_EQ(numbered.values.rows(), 2);
  ASSERT_EQ(numbered.warnings.size(), 1u);
  EXPECT_NE(numbered.warnings[0].text.find("is read as data"), std::string::npos) << numbered.warnings[0].text;
  EXPECT_NE(numbered.warnings[0].text.find("--header-row"), std::string::npos);
  // Unquoted 1, 2, 3 is as obvious as any row of numbers: no warning.
  EXPECT_TRUE(parse_delimited("1,2,3\n4,5,6\n", "A.csv", {}).warnings.empty());
  // pandas' quoted header "0","1" stays a header (the one exception).
  const Table pandas = parse_delimited("\"0\",\"1\"\n4,5\n6,7\n", "A.csv", {});
  EXPECT_EQ(pandas.values.rows(), 2);
}

TEST(IoDelimited, NoData) {
  EXPECT_STREQ(ParseError("").what(), "A.csv: no data rows (the text is empty)");
  EXPECT_STREQ(ParseError("\xEF\xBB\xBF").what(), "A.csv: no data rows (the text is empty)");
  EXPECT_STREQ(ParseError("# nothing\n\n  \n").what(), "A.csv: no data rows (only comments and blank lines)");
  EXPECT_STREQ(ParseError("\n").what(), "A.csv: no data rows (only comments and blank lines)");
  EXPECT_STREQ(ParseError("% c\nx,y\n# c\n").what(), "A.csv: no data rows (only a header row, line 2)");
}

TEST(IoDelimited, HeaderOnlyFirstLine) {
  // Only the first non-comment line can be a header (and a units row under it); later text is an
  // error.
  ExpectError("a,b\nc,d\ne,f\n", 3, 1, "'e' is not a number");
  EXPECT_STREQ(ParseError("a,b\nc,d\n").what(), "A.csv: no data rows (only a header row, line 1, and a units row, "
                                                  "line 2)");
}

// A spreadsheet's error value in a row's first cell (Excel writes #N/A unquoted) is refused, naming
// the line: skipped as a comment, it would shift every later row's number. Comments stay comments.
TEST(IoDelimited, SpreadsheetErrorValuesAreNotComments) {
  const std::string rest =
      " is a spreadsheet's error value (a formula that failed), not a number; a line starting with # would "
      "otherwise be a comment, skipped, and every later row numbered one less: fix or delete that row in the "
      "spreadsheet, or export it again";
  ExpectError("a,b\n1,2\n#N/A,3\n4,5\n", 3, 1, "'#N/A'" + rest);
  ExpectError("1;2\n#DIV/0!;3\n", 2, 1, "'#DIV/0!'" + rest);
  ExpectError("1,2\n#VALUE!\n", 2, 1, "'#VALUE!'" + rest);
  const Table table =
      parse_delimited("# logged 2026-12-02\na,b\n1,2\n#NA is not an error value\n#N/Ab\n3,4\n", "A.csv", {});
  EXPECT_EQ(table.values.rows(), 2);
}

// Excel writes ",,,,," for rows it has formatted but holds no values: after the data they are
// blank lines, silently; between data rows too, with a notice (--rows numbers data rows only).
TEST(IoDelimited, SpreadsheetEmptyRowsAreBlankLines) {
  const Table trailing = parse_delimited("a,b,c\n1,2,3\n4,5,6\n,,\n,,\r\n;;\n", "A.csv", {});
  ASSERT_EQ(trailing.values.rows(), 2);
  EXPECT_EQ(trailing.values(1, 2), 6.0);
  EXPECT_TRUE(trailing.warnings.empty());
  const Table middle = parse_delimited("a,b\n1,2\n,\n , \n3,4\n,\n5,6\n", "A.csv", {});
  ASSERT_EQ(middle.values.rows(), 3);
  EXPECT_EQ(middle.values(2, 1), 6.0);
  ASSERT_EQ(middle.warnings.size(), 1u);
  EXPECT_EQ(middle.warnings[0].text,
            "A.csv: lines 3, 4 and 6 hold only separators (a spreadsheet's empty rows) between data rows: skipped "
            "as blank lines are, so --rows numbers the data rows without them");
  // the first five named, the others counted
  std::string many = "a,b\n1,2\n";
  for (int k = 0; k < 8; ++k) many += ",\n3,4\n";
  const Table counted = parse_delimited(many, "A.csv", {});
  ASSERT_EQ(counted.warnings.size(), 1u);
  EXPECT_EQ(counted.warnings[0].text.substr(0, 37), "A.csv: lines 3, 5, 7, 9, 11 and 3 mor");
  ExpectError("a,b\n1,2\n,3\n", 3, 1,
              "empty field: the line starts with ','; a missing value? pandas' to_csv writes NaN as an empty "
              "field (drop such rows first)");
}

// A units row under the header (DAQ loggers write one): skipped with a notice when none of its
// fields is a number; a first row with a number in it stays data (or an error).
TEST(IoDelimited, UnitsRowUnderTheHeaderIsSkipped) {
  const Table table = parse_delimited("t,Fx,Fy\ns,N,\"N\"\n0.1,2,3\n0.2,4,5\n", "A.csv", {});
  ASSERT_EQ(table.values.rows(), 2);
  EXPECT_EQ(table.values(1, 2), 5.0);
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"t", "Fx", "Fy"}));
  ASSERT_EQ(table.warnings.size(), 1u);
  EXPECT_EQ(table.warnings[0].text,
            "A.csv:2: the line under the header, 's,N,\"N\"', is read as a units row (as loggers write one under "
            "the column names) and skipped: none of its fields is a number");
  // Unitless columns may have empty cells; NaN is a number's spelling: data, refused as such.
  EXPECT_EQ(parse_delimited("a;b;c\n;m;\n1;2;3\n", "A.csv", {}).values.rows(), 1);
  ExpectError("a,b\nx,1\n", 2, 1, "'x' is not a number");
  EXPECT_EQ(ParseError("a,b\nNaN,nan\n").line(), 2u);
  // not the header's fields; a decimal comma is a number; a "1" among units is hinted at
  const std::string units = "; a units row under the header? It is skipped only when none of its fields is a number";
  ExpectError("a,b\nN,N,N\n1,2\n", 2, 1, "'N' is not a number" + units);
  ExpectError("a;b\n3,5;4,5\n", 2, 1, "'3,5' is not a number (decimal comma? use '.' for decimals)");
  ExpectError("t,a,b,c\ns,N,N,1\n1,2,3,4\n", 2, 1, "'s' is not a number" + units);
  // Only directly under the header.
  ExpectError("a,b\n1,2\nN,N\n", 3, 1, "'N' is not a number");
}

// Quoted fields that are not numbers get the hints unquoted ones get: the selected column, a
// timestamp in the first column, a decimal comma.
TEST(IoDelimited, QuotedTextNamesTheSelectedColumn) {
  ReadOptions options;
  options.columns = {{"2", "a_cols"}, {"3", "b_cols"}};
  const DataError e = ParseError("t,a,b\n\"0.1\",\"1\",\"ERR\"\n", options);
  EXPECT_EQ(e.line(), 2u);
  EXPECT_EQ(e.problem(), "'\"ERR\"' is quoted text, not a number; column 3 is selected by `b_cols` '3'");
  const std::string timestamp = ParseError("t,a\n\"2026-11-27 10:00:00\",\"1\"\n").problem();
  EXPECT_NE(timestamp.find("a timestamp in the first column?"), std::string::npos) << timestamp;
  EXPECT_NE(ParseError("a;b\n\"1,5\";\"2\"\n").problem().find("(decimal comma? use '.' for decimals)"),
            std::string::npos);
}

}  // namespace
