// Fuzzes the MATLAB level-5 .mat reader (io::detail::read_mat: spdfit's check of the file's
// structure, then libmatio). libmatio reads from a
// file, so each input is written to a scratch file first. Properties: a non-empty matrix, or an
// io::DataError with a short message; NaN and Inf only when allowed.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "io/containers.hpp"
#include "spdfit/io.hpp"

namespace {

constexpr std::size_t kMaxProblemLength = 600;

const std::string& scratch_path() {
  static const std::string path = [] {
    char name[] = "/tmp/spdfit_fuzz_mat_XXXXXX";
    const int fd = ::mkstemp(name);
    SPDFIT_FUZZ_CHECK(fd >= 0);
    ::close(fd);
    return std::string(name);
  }();
  // Registered once `path` is made, so it runs before `path` is destroyed.
  static const bool removed_at_exit = std::atexit([] { std::remove(path.c_str()); }) == 0;
  (void)removed_at_exit;
  return path;
}

void check(const std::string& path, const std::string& variable, bool allow_nonfinite) {
  spdfit::io::ReadOptions options;
  options.allow_nonfinite = allow_nonfinite;
  try {
    const spdfit::io::Table t = spdfit::io::detail::read_mat(path, variable, options);
    SPDFIT_FUZZ_CHECK(t.values.rows() > 0 && t.values.cols() > 0);
    SPDFIT_FUZZ_CHECK(allow_nonfinite || t.values.allFinite());
  } catch (const spdfit::io::DataError& e) {
    SPDFIT_FUZZ_CHECK(!e.problem().empty());
    SPDFIT_FUZZ_CHECK(e.problem().size() <= kMaxProblemLength);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // Level-5 files only: spdfit checks their structure before libmatio reads them. A 7.3 file's
  // body is HDF5, parsed by libhdf5, which leaks memory on malformed files (docs/errors.md).
  if (!spdfit::io::detail::is_level5(bytes)) return 0;
  const std::string& path = scratch_path();
  std::FILE* file = std::fopen(path.c_str(), "wb");
  SPDFIT_FUZZ_CHECK(file != nullptr);
  SPDFIT_FUZZ_CHECK(std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size());
  std::fclose(file);
  check(path, "", false);
  check(path, "x", true);
  return 0;
}
