#include <gtest/gtest.h>

#include <string>

#include "spdfit/io.hpp"

namespace {

using spdfit::io::DataError;

TEST(IoDataError, FormatsSourceLineAndColumn) {
  const DataError error("A.csv", 3, 7, "'abc' is not a number");
  EXPECT_STREQ(error.what(), "A.csv:3:7: 'abc' is not a number");
  EXPECT_EQ(error.source(), "A.csv");
  EXPECT_EQ(error.line(), 3u);
  EXPECT_EQ(error.column(), 7u);
  EXPECT_EQ(error.problem(), "'abc' is not a number");
}

TEST(IoDataError, LeavesOutColumnZero) {
  const DataError error("A.csv", 4, 0, "row has 5 fields, expected 6 (as in line 2)");
  EXPECT_STREQ(error.what(), "A.csv:4: row has 5 fields, expected 6 (as in line 2)");
}

TEST(IoDataError, LeavesOutLineZero) {
  const DataError error("X.npy", 0, 0, "entry (3, 2) is NaN");
  EXPECT_STREQ(error.what(), "X.npy: entry (3, 2) is NaN");
  // A column without a line would be meaningless, so it is dropped.
  const DataError no_line("X.npy", 0, 5, "problem");
  EXPECT_STREQ(no_line.what(), "X.npy: problem");
  EXPECT_EQ(no_line.column(), 0u);
}

TEST(IoDataError, IsARuntimeError) {
  try {
    throw DataError("f", 1, 2, "p");
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "f:1:2: p");
  }
}

}  // namespace
