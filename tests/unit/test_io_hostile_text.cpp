// parse_delimited on input that is not text, or is text built to exhaust time or memory: it
// must fail with a clear message, in linear time, without crashing.
#include <gtest/gtest.h>

#include <string>

#include "io_test_support.hpp"
#include "spdfit/io.hpp"

namespace {

using Eigen::MatrixXd;
using spdfit::io::DataError;
using spdfit::io::parse_delimited;
using spdfit::io::ReadOptions;

using spdfit::io::test::ExpectError;
using spdfit::io::test::Parse;
using spdfit::io::test::ParseError;

// ---- Not text ----------------------------------------------------------------------------------

TEST(IoHostileText, BinaryGarbage) {
  const DataError nul = ParseError(std::string("1,2\n3,\0\n", 8));
  EXPECT_EQ(nul.line(), 2u);
  EXPECT_EQ(nul.column(), 3u);
  EXPECT_EQ(nul.problem(), "looks like a binary file, not text (NUL byte at byte offset 6)");
  ExpectError("1,2\n3,\x01\n", 2, 3,
              "looks like a binary file, not text (control character 0x01 at byte offset 6)");
  ExpectError("1,2\r3,\x7F\n", 2, 3,
              "looks like a binary file, not text (control character 0x7F at byte offset 6)");
  ExpectError("1,2\r\n\x1B\n", 2, 1,
              "looks like a binary file, not text (control character 0x1B at byte offset 5)");
  ExpectError(
      "a\xC3\xA9"
      "b,\x0C\n",
      1, 5, "looks like a binary file, not text (control character 0x0C at byte offset 5)");
  // The offset counts the byte-order mark; the column does not.
  ExpectError("\xEF\xBB\xBF\x02", 1, 1,
              "looks like a binary file, not text (control character 0x02 at byte offset 3)");
  // Binary content is reported even when an earlier line has another error.
  EXPECT_EQ(ParseError(std::string("abc\n1,x\n\0", 9)).line(), 3u);
  // A zip file, such as an .xlsx workbook.
  EXPECT_NE(ParseError(std::string("PK\x03\x04\x14\0\x06\0", 8)).problem().find("binary"), std::string::npos);
  EXPECT_NE(ParseError(std::string("PK\x03\x04\x14\0\x06\0", 8)).problem().find("Excel .xlsx workbook"),
            std::string::npos);
  EXPECT_NE(ParseError(std::string("\xD0\xCF\x11\xE0\xA1\xB1\x1A\xE1\0", 9)).problem().find(".xls workbook"),
            std::string::npos);
}

TEST(IoHostileText, InvalidUtf8) {
  const auto expect_invalid = [](const std::string& text, std::size_t line, std::size_t column) {
    const DataError e = ParseError(text);
    EXPECT_EQ(e.line(), line) << text;
    EXPECT_EQ(e.column(), column) << text;
    EXPECT_NE(e.problem().find("not valid UTF-8"), std::string::npos) << e.what();
  };
  expect_invalid("Temp\xE9rature,x\n1,2\n", 1, 5);  // Latin-1
  expect_invalid("1,2\n\xC3\x28\n", 2, 1);          // bad continuation
  expect_invalid("1,2\n\xC0\xAF\n", 2, 1);          // overlong
  expect_invalid("1,2\n\xED\xA0\x80\n", 2, 1);      // surrogate
  expect_invalid("1,2\n\xF4\x90\x80\x80\n", 2, 1);  // beyond U+10FFFF
  expect_invalid("1,2\nx\xE2\x82", 2, 2);           // cut off at the end
  expect_invalid("\x93NUMPY", 1, 1);                // a broken .npy
  // Amid text, a byte that is not UTF-8 is a Windows code page (issue 18: say what to do, not
  // "binary"), shown as the character it is there.
  EXPECT_EQ(ParseError("Temp\xE9rature").problem(),
            "is not UTF-8 text: byte 0xE9 at byte offset 4 ('\xC3\xA9' in Windows-1252 and Latin-1) is not "
            "valid UTF-8, so the file is probably in a Windows code page (Excel's plain \"CSV\" saves in one); "
            "save it as UTF-8 (Excel: \"CSV UTF-8\")");
  EXPECT_NE(ParseError("a,b\n1,\x80\n").problem().find("('\xE2\x82\xAC' in Windows-1252)"), std::string::npos);
  EXPECT_NE(ParseError("a,b\n1,\x81\n").problem().find("save it as UTF-8"), std::string::npos);
  // Next to control characters it is binary, and a damaged .npy header says so.
  EXPECT_EQ(ParseError("1,2\n\xE9\x01\n").problem(),
            "looks like a binary file, not text (byte 0xE9 that is not valid UTF-8 at byte offset 4)");
  EXPECT_NE(ParseError("\x93NUMPY").problem().find("a .npy file with a damaged header"), std::string::npos);
}

TEST(IoHostileText, Utf16) {
  const DataError e =
      ParseError(std::string("\xFF\xFE"
                             "1\0,\0"
                             "2\0",
                             8));
  EXPECT_EQ(e.line(), 0u);
  EXPECT_NE(e.problem().find("UTF-16"), std::string::npos) << e.what();
  // Without a byte-order mark: a NUL every other byte, ASCII between.
  for (const std::string& text : {std::string("1\0,\0002\0\n\0", 8), std::string("\0001\0,\0002\0\n", 8)}) {
    EXPECT_NE(ParseError(text).problem().find("looks like UTF-16 text without a byte-order mark"), std::string::npos)
        << ParseError(text).what();
  }
}

// ---- Hostile input -----------------------------------------------------------------------------

TEST(IoHostileText, HugeTokenIsShortenedInTheMessage) {
  const std::string token(1000000, 'x');
  const DataError e = ParseError("1,2\n1," + token + "\n");
  EXPECT_EQ(e.column(), 3u);
  EXPECT_LT(e.problem().size(), 100u);
  EXPECT_EQ(e.problem(), "'" + std::string(40, 'x') + "...' is not a number");
}

TEST(IoHostileText, HugeTokenIsShortenedAtACharacterBoundary) {
  std::string token = "1";
  for (int i = 0; i < 100; ++i) token += "é";
  const DataError e = ParseError("1;2\n1;" + token + "\n");
  EXPECT_EQ(e.problem(), "'1" + std::string(token.substr(1, 38)) + "...' is not a number");
}

TEST(IoHostileText, HugeNumberTokens) {
  // A million digits: too large, found in linear time.
  const std::string digits(1000000, '7');
  const DataError e = ParseError("1," + digits + "\n");
  EXPECT_NE(e.problem().find("is too large for a double"), std::string::npos);
  // A million zeros after the point and then a digit: tiny, reads as zero.
  const MatrixXd X = Parse("1,0." + std::string(1000000, '0') + "1\n");
  EXPECT_EQ(X(0, 1), 0.0);
  // Absurd exponents.
  ExpectError("1,1e99999999999999999999999\n", 1, 3,
              "'1e99999999999999999999999' is too large for a double (it would be Inf)");
  EXPECT_EQ(Parse("1,1e-99999999999999999999999\n")(0, 1), 0.0);
}

TEST(IoHostileText, MillionsOfColumnsThenRagged) {
  std::string text;
  text.reserve(4000000);
  for (int j = 0; j < 1000000; ++j) text += "1,";
  text += "1\n1,2\n";
  const DataError e = ParseError(text);
  EXPECT_STREQ(e.what(), "A.csv:2: row has 2 fields, expected 1000001 (as in line 1)");
}

TEST(IoHostileText, HugeColumnNumberInError) {
  const std::string text = "1 2\n1" + std::string(1000000, ' ') + "x\n";
  ExpectError(text, 2, 1000002, "'x' is not a number");
}

TEST(IoHostileText, ManyQuotes) {
  const std::string text = "\"" + std::string(1000000, '"') + "\n1\n";
  EXPECT_NO_FATAL_FAILURE(ParseError(text));
}

// A line of separators only is a spreadsheet's empty row: a blank line (split_file.cpp's scan for
// mpirun counts it so too); a line that starts with one empty field is still an error.
TEST(IoHostileText, OnlySeparators) {
  EXPECT_STREQ(ParseError(",,,,\n").what(), "A.csv: no data rows (only comments and blank lines)");
  EXPECT_STREQ(ParseError(";\n ; ;\n").what(), "A.csv: no data rows (only comments and blank lines)");
  const std::string pandas = "; a missing value? pandas' to_csv writes NaN as an empty field (drop such rows first)";
  ExpectError("1,2\n,3\n", 2, 1, "empty field: the line starts with ','" + pandas);
}

}  // namespace
