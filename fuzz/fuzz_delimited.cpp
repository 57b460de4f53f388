// Fuzzes io::parse_delimited, the reader of every text data file. Properties: the bytes give a
// non-empty table or an io::DataError with a short message; NaN and Inf only when allowed; the
// column names match the columns; and what write_csv makes of the table reads back bitwise (but
// for the sign of zero, which it writes as 0).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string_view>

#include "fuzz_check.hpp"
#include "io/parse.hpp"
#include "spdfit/io.hpp"

namespace {

// An error message quotes at most a short piece of the input (detail::quote_token), so that a
// hostile file cannot make a huge message.
constexpr std::size_t kMaxProblemLength = 400;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void check(std::string_view text, bool allow_nonfinite) {
  spdfit::io::ReadOptions options;
  options.allow_nonfinite = allow_nonfinite;
  spdfit::io::Table table;
  try {
    table = spdfit::io::parse_delimited(text, "fuzz.csv", options);
  } catch (const spdfit::io::DataError& e) {
    SPDFIT_FUZZ_CHECK(!e.problem().empty());
    SPDFIT_FUZZ_CHECK(e.problem().size() <= kMaxProblemLength);
    return;
  }
  const Eigen::MatrixXd& X = table.values;
  SPDFIT_FUZZ_CHECK(X.rows() > 0 && X.cols() > 0);
  SPDFIT_FUZZ_CHECK(allow_nonfinite || X.allFinite());
  SPDFIT_FUZZ_CHECK(table.column_names.empty() || table.column_names.size() == static_cast<std::size_t>(X.cols()));

  // write_csv writes no header row: read it back as such (a first row 0, 1, ..., k - 1 would
  // otherwise be taken for pandas' header, as the reader's Auto rule says).
  std::ostringstream csv;
  spdfit::io::write_csv(csv, X);
  spdfit::io::ReadOptions reread = options;
  reread.header_row = spdfit::io::HeaderRow::Absent;
  const Eigen::MatrixXd Y = spdfit::io::parse_delimited(csv.str(), "written.csv", reread).values;
  SPDFIT_FUZZ_CHECK(Y.rows() == X.rows() && Y.cols() == X.cols());
  for (Eigen::Index k = 0; k < X.size(); ++k) {
    // NaN payloads and signs are not kept by "nan", nor the sign of zero (-0 is written as 0);
    // every other value is, bit for bit.
    SPDFIT_FUZZ_CHECK(same_bits(X(k), Y(k)) || (std::isnan(X(k)) && std::isnan(Y(k))) ||
                      (X(k) == 0.0 && Y(k) == 0.0));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  check(text, false);
  check(text, true);
  return 0;
}
