// Fuzzes io::parse_npy, the reader of NumPy's binary format. Properties: the bytes give a
// non-empty matrix whose values the file really holds, or an io::DataError with a short message;
// no allocation before the claimed size is checked against the bytes; NaN and Inf only when allowed.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_check.hpp"
#include "io/parse.hpp"
#include "spdfit/io.hpp"

namespace {

constexpr std::size_t kMaxProblemLength = 400;

void check(std::string_view bytes, bool allow_nonfinite) {
  spdfit::io::ReadOptions options;
  options.allow_nonfinite = allow_nonfinite;
  Eigen::MatrixXd X;
  try {
    X = spdfit::io::parse_npy(bytes, "fuzz.npy", options);
  } catch (const spdfit::io::DataError& e) {
    SPDFIT_FUZZ_CHECK(!e.problem().empty());
    SPDFIT_FUZZ_CHECK(e.problem().size() <= kMaxProblemLength);
    return;
  }
  SPDFIT_FUZZ_CHECK(X.rows() > 0 && X.cols() > 0);
  // At least one byte per value (8 for float64, 1 for int8 or bool), all of them in the input.
  SPDFIT_FUZZ_CHECK(static_cast<std::size_t>(X.size()) <= bytes.size());
  SPDFIT_FUZZ_CHECK(allow_nonfinite || X.allFinite());
  // parse_table picks the same reader by the magic bytes.
  const Eigen::MatrixXd Y = spdfit::io::parse_table(bytes, "fuzz.npy", options).values;
  SPDFIT_FUZZ_CHECK(Y.rows() == X.rows() && Y.cols() == X.cols());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  check(bytes, false);
  check(bytes, true);
  return 0;
}
