// Reading a matrix from a file: checks that the path is a readable regular file, reads it
// (refusing binary files from their first bytes), then hands the bytes to the .npy or the
// delimited-text parser.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "file_error.hpp"
#include "parse.hpp"
#include "npy_header.hpp"
#include "columns.hpp"
#include "containers.hpp"
#include "delimited_parser.hpp"
#include "read_file.hpp"
#include "spdfit/io.hpp"
#include "spdfit/labels.hpp"
#include "spdfit/row_reader.hpp"
#include "text_scan.hpp"

namespace spdfit::io {

namespace detail {

namespace fs = std::filesystem;

// Reading a directory or a device gives nothing useful either.
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

std::string read_file(const std::string& path, std::size_t max_bytes, const std::string& what,
                      const std::function<void(std::string_view)>& inspect) {
  check_regular_file(path);
  std::error_code error;
  const std::uintmax_t size = fs::file_size(path, error);
  if (!error && size > max_bytes) {
    throw DataError(path, 0, 0,
                    "is " + std::to_string(size) + " bytes long; at most " + std::to_string(max_bytes) +
                        " are accepted for " + what);
  }
  errno = 0;
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) {
    throw DataError(path, 0, 0, errno != 0 ? describe_errno(errno) : "cannot be opened");
  }
  std::string bytes;
  // Read until end of file rather than trusting the size: the file may change meanwhile, and
  // some files (in /proc, say) report size 0. The first block is inspected before the size is
  // reserved, so that a refused file never costs its size in memory.
  char buffer[1 << 16];
  bool inspected = !inspect;
  while (true) {
    const std::size_t got = std::fread(buffer, 1, sizeof(buffer), file.get());
    bytes.append(buffer, got);
    const bool done = got < sizeof(buffer);
    if (bytes.size() > max_bytes) {
      throw DataError(
          path, 0, 0,
          "is longer than " + std::to_string(max_bytes) + " bytes, the most accepted for " + what);
    }
    if (!inspected && (done || bytes.size() >= kInspectBytes)) {
      inspected = true;
      if (!std::ferror(file.get())) inspect(bytes);
      if (!error && size > bytes.size()) bytes.reserve(static_cast<std::size_t>(size));
    }
    if (done) break;
  }
  if (std::ferror(file.get())) {
    throw DataError(path, 0, 0, "read error (" + describe_errno(errno) + ")");
  }
  return bytes;
}

}  // namespace detail

namespace {

// A file that is not text from its first bytes on (a sparse file of zeros, a disk image) is
// refused from those bytes with the error the whole text would give, without reading the rest.
void refuse_binary_early(std::string_view first, const std::string& path) {
  if (first.substr(0, detail::kNpyMagic.size()) == detail::kNpyMagic) return;
  std::string description;
  const std::size_t offset = detail::find_non_text_byte(first, &description);
  // A multi-byte UTF-8 character may be cut at the end of the block: only judge well inside it.
  if (offset == std::string_view::npos || offset + 4 >= first.size()) return;
  // The delimited reader checks the bytes before anything else, so these first bytes fail as
  // the whole file would.
  parse_delimited(first, path);
}

}  // namespace

namespace {

// parse_table, with the labels of a dropped first column of text in `row_names` when given.
Table parse_bytes(std::string_view bytes, const std::string& source, const ReadOptions& options,
                  std::vector<std::string>* row_names) {
  if (bytes.empty()) throw DataError(source, 0, 0, "file is empty");
  // The magic bytes decide, not the name: a .npy file keeps its format when renamed.
  if (bytes.substr(0, detail::kNpyMagic.size()) == detail::kNpyMagic) {
    Table table;
    table.values = parse_npy(bytes, source, options);
    detail::select_table_columns(&table, options, source);
    return table;
  }
  return detail::parse_delimited_labelled(bytes, source, options, row_names);
}

// Whether the regular file `path` starts with .npy's magic bytes (false when it cannot be read:
// the whole-file reader then says why).
bool starts_as_npy(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return false;
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) return false;
  char first[8] = {};
  const std::size_t got = std::fread(first, 1, detail::kNpyMagic.size(), file.get());
  return std::string_view(first, got) == detail::kNpyMagic;
}

// A whole .npy file (no column selection) decoded a block of rows at a time into the matrix: the
// file's bytes are never held whole beside it, so a large matrix (nearest's n x n) costs its own
// size once. The values and every error are read_table's (RowReader's promise).
Table read_npy_by_blocks(const std::string& path, const ReadOptions& options) {
  RowReader reader(path, options);
  // A .npy header declares its rows (checked against the file's size when it was opened).
  const auto rows = static_cast<Eigen::Index>(reader.rows_declared().value_or(0));
  constexpr std::size_t kBlockBytes = std::size_t{1} << 22;
  Table table;
  Eigen::MatrixXd block;
  // The first read is one row: the column count is known after it.
  for (Eigen::Index at = 0, next = 1, got; (got = reader.read(next, &block)) > 0; at += got) {
    if (at == 0) table.values.resize(rows, block.cols());
    table.values.middleRows(at, got) = block;
    next = std::max<Eigen::Index>(static_cast<Eigen::Index>(kBlockBytes / sizeof(double)) / block.cols(), 1);
  }
  table.warnings = reader.warnings();
  return table;
}

// read_table, with the labels of a dropped first column of text in `row_names` when given.
Table read_bytes(const std::string& path, const ReadOptions& options, std::vector<std::string>* row_names) {
  if (path == "-") return parse_bytes(detail::read_standard_input(), detail::kStdinName, options, row_names);
  const detail::FileSpec spec = detail::split_spec(path);
  if (spec.variable.empty() && options.columns.empty() && starts_as_npy(spec.file)) {
    return read_npy_by_blocks(spec.file, options);
  }
  // The content decides, not the name: .mat and .npz files hold named arrays, and their
  // libraries read them from the file.
  if (std::optional<Table> named = detail::read_named_arrays(spec, options)) {
    detail::select_table_columns(&*named, options, path);
    return std::move(*named);
  }
  const std::string bytes =
      detail::read_file(spec.file, std::numeric_limits<std::size_t>::max(), "a data file",
                        [&spec](std::string_view first) { refuse_binary_early(first, spec.file); });
  if (!spec.variable.empty()) {
    throw DataError(spec.file, 0, 0,
                    "holds one array, not named ones (only .mat and .npz files do): '" + path +
                        "' names the array '" + spec.variable + "' in it");
  }
  return parse_bytes(bytes, path, options, row_names);
}

}  // namespace

Table parse_table(std::string_view bytes, const std::string& source, const ReadOptions& options) {
  return parse_bytes(bytes, source, options, nullptr);
}

Table read_table(const std::string& path, const ReadOptions& options) { return read_bytes(path, options, nullptr); }

LabelledTable read_labelled_table(const std::string& path, const ReadOptions& options) {
  LabelledTable out;
  out.table = read_bytes(path, options, &out.row_names);
  // Row labels that are the column names are a labelled matrix's layout (df.cov().to_csv()), which
  // the caller asked for: dropping them as labels is no news.
  if (!out.row_names.empty() && out.row_names == out.table.column_names) {
    auto& warnings = out.table.warnings;
    const std::string notice = detail::DelimitedParser::kIndexColumnNotice;
    warnings.erase(std::remove_if(warnings.begin(), warnings.end(),
                                  [&](const Warning& w) { return w.text.find(notice) != std::string::npos; }),
                   warnings.end());
  }
  return out;
}

Eigen::MatrixXd read_matrix(const std::string& path, const ReadOptions& options) {
  return read_table(path, options).values;
}

}  // namespace spdfit::io
