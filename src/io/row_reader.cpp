// Reading a data file a block of rows at a time: which source reads it (npy_source.hpp: .npy files
// by pread or mapped; text_source.hpp: text in pieces of whole lines through read_table's parser;
// whole_sources.hpp: MATLAB 7.3 in slabs, the other containers whole), standard input, and the
// parts of a file split among processes (split_file.hpp).
#include "spdfit/row_reader.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "columns.hpp"
#include "containers.hpp"
#include "delimited_parser.hpp"
#include "file_error.hpp"
#include "kept_text.hpp"
#include "npy_layout.hpp"
#include "npy_rows.hpp"
#include "npy_source.hpp"
#include "parse.hpp"
#include "read_file.hpp"
#include "split_file.hpp"
#include "text_source.hpp"
#include "whole_sources.hpp"

namespace spdfit::io {

using Eigen::Index;

RowReader::RowReader(const std::string& path, const ReadOptions& options) {
  if (path == "-") {
    // Text is streamed from standard input as from a file; a .npy file (told by its first bytes)
    // is read whole.
    std::string first = detail::read_standard_input({}, detail::kNpyMagic.size());
    if (first != detail::kNpyMagic) {
      source_ = std::make_unique<TextSource>(stdin, std::move(first), options);
      return;
    }
    source_ = std::make_unique<TableSource>(path, parse_table(detail::read_standard_input(std::move(first)), detail::kStdinName, options));
    return;
  }
  const detail::FileSpec spec = detail::split_spec(path);
  if (detail::named_arrays_kind(spec) == detail::NamedArrays::Mat73) {
    source_ = std::make_unique<MatSource>(path, spec, options);
    return;
  }
  std::optional<Table> named = detail::read_named_arrays(spec, options);
  if (named) detail::select_table_columns(&*named, options, path);
  // FILE:NAME of a file without named arrays (whose error read_table gives).
  if (!named && !spec.variable.empty()) named = read_table(path, options);
  if (named) {
    source_ = std::make_unique<TableSource>(path, std::move(*named));
    return;
  }
  detail::check_regular_file(path);
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail_errno(path, "cannot be opened");
  struct stat info {};
  char magic[6] = {};
  ssize_t got = 0;
  if (::fstat(fd, &info) != 0 || (got = ::pread(fd, magic, sizeof(magic), 0)) < 0) {
    const int error = errno;
    ::close(fd);
    errno = error;
    fail_errno(path, "read error");
  }
  if (got == 0) {
    ::close(fd);
    throw DataError(path, 0, 0, "file is empty");
  }
  const bool npy = std::string_view(magic, static_cast<std::size_t>(got)) == detail::kNpyMagic;
  try {
    if (npy) {
      source_ = std::make_unique<NpySource>(path, fd, static_cast<std::size_t>(info.st_size), options);
      ::close(fd);  // the mapping stays valid
    } else {
      source_ = std::make_unique<TextSource>(path, fd, options);  // owns fd now, or closed it
    }
  } catch (...) {
    if (npy) ::close(fd);
    throw;
  }
}

namespace detail {

RowReader standard_input_reader(const ReadOptions& options, std::shared_ptr<KeptText> keep) {
  RowReader reader;
  std::string first = read_standard_input({}, kNpyMagic.size());
  if (first != kNpyMagic) {
    reader.source_ = std::make_unique<RowReader::TextSource>(stdin, std::move(first), options, std::move(keep));
    return reader;
  }
  std::string bytes = read_standard_input(std::move(first));
  keep->keep(bytes.data(), bytes.size());
  reader.source_ = std::make_unique<RowReader::TableSource>("-", parse_table(bytes, kStdinName, options));
  return reader;
}

SplitFile::SplitFile(const std::string& path, const ReadOptions& options, int part, int parts)
    : path_(path), options_(options), part_(part), parts_(parts) {
  if (parts < 1 || part < 0 || part >= parts) throw std::invalid_argument("SplitFile: part outside 0 .. parts - 1");
  const FileSpec spec = split_spec(path);
  if (path == "-" || !spec.variable.empty() || named_arrays_kind(spec) != NamedArrays::None) {
    const std::string what = path == "-" ? "standard input" : path;
    throw DataError(path, 0, 0,
                    what + " cannot be split among processes: only .npy files and text files are split; "
                           "convert it to .npy, or run spdfit without mpirun");
  }
  // The first rows, parsed here as the part starting at the file's start will parse them: the
  // layout every later part is parsed by, and the columns.
  RowReader probe(path, options);
  Eigen::MatrixXd first;
  probe.read(DelimitedParser::kIndexDecisionRows, &first);
  columns_ = probe.columns();
  selected_ = probe.selected_columns();
  if (auto* text = dynamic_cast<RowReader::TextSource*>(probe.source_.get())) {
    layout_ = text->layout();
  } else if (auto* npy = dynamic_cast<RowReader::NpySource*>(probe.source_.get())) {
    npy_ = true;
    rows_ = npy->rows();
  }
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0) size_ = static_cast<std::uint64_t>(info.st_size);
}

RowReader SplitFile::open(std::uint64_t first, std::uint64_t count, const LinePosition& begin,
                          const LinePosition& end) const {
  RowReader reader;
  const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail_errno(path_, "cannot be opened");
  if (npy_) {
    try {
      reader.source_ = std::make_unique<RowReader::NpySource>(path_, fd, static_cast<std::size_t>(size_), options_,
                                                              first, first + count);
    } catch (...) {
      ::close(fd);
      throw;
    }
    ::close(fd);
  } else if (first == 0) {
    // From the file's start, header and all, as a whole file is read.
    auto text = std::make_unique<RowReader::TextSource>(path_, fd, options_);
    text->limit_to(end.byte);
    reader.source_ = std::move(text);
  } else {
    reader.source_ = std::make_unique<RowReader::TextSource>(path_, fd, options_, layout_, begin.byte, end.byte,
                                                             begin.lines_before);
  }
  return reader;
}

}  // namespace detail

RowReader::~RowReader() = default;
RowReader::RowReader(RowReader&&) noexcept = default;
RowReader& RowReader::operator=(RowReader&&) noexcept = default;

Index RowReader::read(Index max_rows, Eigen::MatrixXd* rows) {
  Source& source = *source_;
  if (source.projection.empty()) return source.read(max_rows, rows);
  const Index got = source.read(max_rows, &source.full);
  rows->resize(got, static_cast<Index>(source.projection.size()));
  for (std::size_t j = 0; j < source.projection.size(); ++j) {
    rows->col(static_cast<Index>(j)) = source.full.col(source.projection[j]);
  }
  return got;
}

namespace detail {

const NpyRows* direct_rows(const RowReader& reader) {
  // Selected columns (ReadOptions::columns) are copied out of whole rows by RowReader::read.
  const auto* npy = dynamic_cast<const RowReader::NpySource*>(reader.source_.get());
  return npy && npy->projection.empty() ? npy->direct() : nullptr;
}

Index skip_rows(RowReader& reader, Index max_rows) {
  auto* npy = dynamic_cast<RowReader::NpySource*>(reader.source_.get());
  if (!npy || !npy->direct()) throw std::logic_error("skip_rows: not a C-order .npy file");
  return npy->skip(max_rows);
}

}  // namespace detail
const std::string& RowReader::path() const { return source_->path; }
Index RowReader::columns() const {
  return source_->projection.empty() ? source_->columns() : static_cast<Index>(source_->projection.size());
}
const std::vector<std::vector<std::size_t>>& RowReader::selected_columns() const {
  return source_->selected_columns();
}
const std::vector<std::string>& RowReader::column_names() const { return source_->column_names(); }
const std::vector<Warning>& RowReader::warnings() const { return source_->warnings(); }
std::uint64_t RowReader::rows_read() const { return source_->rows_read; }
double RowReader::fraction_read() const { return source_->fraction_read(); }
std::optional<std::uint64_t> RowReader::rows_declared() const { return source_->rows_declared(); }

}  // namespace spdfit::io
