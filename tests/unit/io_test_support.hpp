// Helpers shared by the delimited-text reader tests: parse a string as file "A.csv" and
// check the error it raises.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "io/parse.hpp"
#include "spdfit/io.hpp"

namespace spdfit::io::test {

using Eigen::MatrixXd;

inline MatrixXd Parse(std::string_view text, ReadOptions options = {}) {
  return parse_delimited(text, "A.csv", options).values;
}

// The DataError that parsing `text` throws (a failed test, and an empty error, if none).
inline DataError ParseError(std::string_view text, ReadOptions options = {}) {
  try {
    parse_delimited(text, "A.csv", options);
  } catch (const DataError& e) {
    return e;
  }
  ADD_FAILURE() << "no DataError for: " << text;
  return DataError("", 0, 0, "");
}

inline void ExpectError(std::string_view text, std::size_t line, std::size_t column, const std::string& problem) {
  const DataError e = ParseError(text);
  EXPECT_EQ(e.source(), "A.csv") << text;
  EXPECT_EQ(e.line(), line) << e.what();
  EXPECT_EQ(e.column(), column) << e.what();
  EXPECT_EQ(e.problem(), problem) << e.what();
}

}  // namespace spdfit::io::test
