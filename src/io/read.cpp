// Reading a matrix from a file: checks that the path is a readable regular file, then hands
// the bytes to the .npy or the delimited-text parser.
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>

#include "file_error.hpp"
#include "npy_header.hpp"
#include "spdfit/io.hpp"

namespace spdfit::io {

namespace {

namespace fs = std::filesystem;

// Checked with stat before opening, because opening a FIFO for reading blocks until someone
// writes to it, and reading a directory or a device gives nothing useful.
void check_regular_file(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  std::string problem;
  switch (status.type()) {
    case fs::file_type::regular:
      return;
    case fs::file_type::not_found:
      problem = "no such file";
      break;
    case fs::file_type::directory:
      problem = "is a directory";
      break;
    case fs::file_type::fifo:
      problem = "is not a regular file (it is a named pipe)";
      break;
    case fs::file_type::socket:
      problem = "is not a regular file (it is a socket)";
      break;
    case fs::file_type::block:
    case fs::file_type::character:
      problem = "is not a regular file (it is a device)";
      break;
    default:
      // No type: stat itself failed, e.g. for lack of permission on a directory on the path.
      problem = error ? detail::describe_errno(error.value()) : "is not a regular file";
  }
  throw DataError(path, 0, 0, problem);
}

std::string read_file(const std::string& path) {
  check_regular_file(path);
  errno = 0;
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) {
    throw DataError(path, 0, 0, errno != 0 ? detail::describe_errno(errno) : "cannot be opened");
  }
  std::string bytes;
  std::error_code error;
  const std::uintmax_t size = fs::file_size(path, error);
  if (!error) bytes.reserve(static_cast<std::size_t>(size));
  // Read until end of file rather than trusting the size: the file may change meanwhile, and
  // some files (in /proc, say) report size 0.
  char buffer[1 << 16];
  while (true) {
    const std::size_t got = std::fread(buffer, 1, sizeof(buffer), file.get());
    bytes.append(buffer, got);
    if (got < sizeof(buffer)) break;
  }
  if (std::ferror(file.get())) {
    throw DataError(path, 0, 0, "read error (" + detail::describe_errno(errno) + ")");
  }
  return bytes;
}

}  // namespace

Table parse_table(std::string_view bytes, const std::string& source, const ReadOptions& options) {
  if (bytes.empty()) throw DataError(source, 0, 0, "file is empty");
  // The magic bytes decide, not the name: a .npy file keeps its format when renamed.
  if (bytes.substr(0, detail::kNpyMagic.size()) == detail::kNpyMagic) {
    Table table;
    table.values = parse_npy(bytes, source, options);
    return table;
  }
  return parse_delimited(bytes, source, options);
}

Table read_table(const std::string& path, const ReadOptions& options) {
  return parse_table(read_file(path), path, options);
}

Eigen::MatrixXd read_matrix(const std::string& path, const ReadOptions& options) {
  return read_table(path, options).values;
}

}  // namespace spdfit::io
