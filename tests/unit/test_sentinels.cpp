// The warning about loggers' codes for invalid readings (pipeline/sentinels.hpp): which rows it
// names, with which values, and the rows it says to keep; silent on large values that are data.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <string>

#include "pipeline/sentinels.hpp"

namespace spdfit::detail {
namespace {

Eigen::MatrixXd ramp(Eigen::Index m, Eigen::Index n) {
  Eigen::MatrixXd M(m, n);
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) M(i, j) = double(i + 1) * 0.1 + double(j);
  }
  return M;
}

TEST(Sentinels, NamesTheRowTheValueAndTheRowsToKeep) {
  Eigen::MatrixXd A = ramp(50, 3), B = ramp(50, 3);
  A(16, 1) = 9.9e37;
  const auto w = sentinel_warning(A, B);
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(w->code, Code::Outliers);
  EXPECT_NE(w->text.find("row 17 (9.9e+37 in A's column 2) holds a value of magnitude 1e30 or more"),
            std::string::npos)
      << w->text;
  EXPECT_NE(w->text.find("(the rows 1:16,18:50, as --rows takes them without --time-col)"), std::string::npos) << w->text;
}

TEST(Sentinels, CountsRowsBeyondTheFiveNamedAndOneRowOnce) {
  Eigen::MatrixXd A = ramp(20, 2), B = ramp(20, 2);
  for (Eigen::Index i = 0; i < 7; ++i) B(2 * i, 1) = -1e38;
  A(0, 0) = 1e31;  // the same row as B's first: named once, with its first value
  const auto w = sentinel_warning(A, B);
  ASSERT_TRUE(w.has_value());
  EXPECT_NE(w->text.find("rows 1 (1e+31 in A's column 1), 3 (-1e+38 in B's column 2), 5 (-1e+38 in B's column "
                         "2), 7 (-1e+38 in B's column 2), 9 (-1e+38 in B's column 2) and 2 more hold"),
            std::string::npos)
      << w->text;
  // Eight ranges of rows to keep are too many to list.
  EXPECT_EQ(w->text.find("fit rows"), std::string::npos) << w->text;
}

TEST(Sentinels, SilentBelowTheMagnitudeAndOnInfinityFreeData) {
  Eigen::MatrixXd A = ramp(10, 2), B = ramp(10, 2);
  A(3, 1) = 9.99e29;
  B(4, 0) = -1e29;
  EXPECT_FALSE(sentinel_warning(A, B).has_value());
  EXPECT_FALSE(sentinel_warning(Eigen::MatrixXd(0, 2), Eigen::MatrixXd(0, 2)).has_value());
  A(9, 0) = 1e30;  // the bound itself is a code
  const auto w = sentinel_warning(A, B);
  ASSERT_TRUE(w.has_value());
  EXPECT_NE(w->text.find("(the rows 1:9, as --rows takes them without --time-col)"), std::string::npos) << w->text;
}

}  // namespace
}  // namespace spdfit::detail
