// Fuzzes io::parse_delimited, the reader of every text data file. Properties: the bytes give a
// non-empty table or an io::DataError with a short message; NaN and Inf only when allowed; the
// column names match the columns; and what write_csv makes of the table reads back bitwise.
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

  std::ostringstream csv;
  spdfit::io::write_csv(csv, X);
  const Eigen::MatrixXd Y = spdfit::io::parse_delimited(csv.str(), "written.csv", options).values;
  SPDFIT_FUZZ_CHECK(Y.rows() == X.rows() && Y.cols() == X.cols());
  for (Eigen::Index k = 0; k < X.size(); ++k) {
    // NaN payloads and signs are not kept by "nan"; every other value is, bit for bit.
    SPDFIT_FUZZ_CHECK(same_bits(X(k), Y(k)) || (std::isnan(X(k)) && std::isnan(Y(k))));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  check(text, false);
  check(text, true);
  return 0;
}
