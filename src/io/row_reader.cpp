// Reading a data file a block of rows at a time: .npy files by pread (or mapped), text in pieces of
// whole lines through the same parser as read_table.
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
#include "parse.hpp"
#include "read_file.hpp"
#include "split_file.hpp"

namespace spdfit::io {

using Eigen::Index;

struct RowReader::Source {
  explicit Source(std::string p) : path(std::move(p)) {}
  virtual ~Source() = default;
  Source(const Source&) = delete;
  Source& operator=(const Source&) = delete;
  virtual Index read(Index max_rows, Eigen::MatrixXd* rows) = 0;
  virtual Index columns() const = 0;
  virtual const std::vector<std::string>& column_names() const { return no_names; }
  virtual const std::vector<Warning>& warnings() const { return no_warnings; }
  virtual double fraction_read() const = 0;
  virtual std::optional<std::uint64_t> rows_declared() const { return std::nullopt; }
  virtual const std::vector<std::vector<std::size_t>>& selected_columns() const { return selected; }

  // ReadOptions::columns for a format without names read a block at a time (.npy, MATLAB 7.3):
  // the whole rows are read into `full`, and the selected columns copied out in order.
  void select(const ReadOptions& options) {
    if (options.columns.empty()) return;
    const auto chosen =
        detail::resolve_columns(options.columns, {}, static_cast<std::size_t>(columns()), false, path);
    for (std::size_t c : detail::concatenated(chosen)) projection.push_back(static_cast<Index>(c));
    selected = detail::one_based(chosen);
  }

  std::string path;
  std::uint64_t rows_read = 0;
  std::vector<std::string> no_names;
  std::vector<Warning> no_warnings;
  std::vector<std::vector<std::size_t>> selected;
  std::vector<Index> projection;
  Eigen::MatrixXd full;
};

namespace {

[[noreturn]] void fail_errno(const std::string& path, const std::string& doing) {
  throw DataError(path, 0, 0, doing + " (" + detail::describe_errno(errno) + ")");
}

}  // namespace

// A .npy file decoded a block at a time. In C order (NumPy's default) each block's rows are one
// run of bytes, read with pread into a buffer used again for every block: no page faults on a
// mapping, and no new memory per block. In Fortran order a block is one run per column: the file
// is mapped whole, the kernel reads ahead (MADV_SEQUENTIAL), and the pages of rows already decoded
// are dropped from the mapping (the page cache keeps them). Either way resident memory stays
// O(block) however long the file.
class RowReader::NpySource final : public RowReader::Source {
 public:
  NpySource(const std::string& path, int fd, std::size_t size, const ReadOptions& options)
      : NpySource(path, fd, size, options, 0, std::numeric_limits<std::uint64_t>::max()) {}
  // Rows [begin, min(end, the file's rows)) only: a process's part of a file split among processes.
  NpySource(const std::string& path, int fd, std::size_t size, const ReadOptions& options, std::uint64_t begin,
            std::uint64_t end)
      : Source(path), begin_(begin), size_(size), options_(options) {
    void* map = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (map == MAP_FAILED) fail_errno(path, "cannot be memory-mapped");
    map_ = static_cast<const char*>(map);
    ::madvise(map, size, MADV_SEQUENTIAL);
    try {
      const std::string_view bytes(map_, size_);
      layout_ = detail::npy_layout(detail::parse_npy_header(bytes, path), size_, path);
      select(options);
      end_ = std::min(end, layout_.rows);
      begin_ = std::min(begin_, end_);
      dropped_rows_ = begin_;
      if (!layout_.fortran_order) {
        fd_ = ::fcntl(fd, F_DUPFD_CLOEXEC, 0);  // the caller closes fd
        if (fd_ < 0) fail_errno(path, "cannot be read");
        ::posix_fadvise(fd_, 0, 0, POSIX_FADV_SEQUENTIAL);
        ::munmap(map, size_);
        map_ = nullptr;
        rows_.emplace(fd_, layout_, begin_, path, options_.allow_nonfinite);
      }
    } catch (...) {
      if (map_) ::munmap(map, size_);  // a constructor that throws runs no destructor
      throw;
    }
  }
  ~NpySource() override {
    if (map_) ::munmap(const_cast<char*>(map_), size_);
    if (fd_ >= 0) ::close(fd_);
  }

  Index read(Index max_rows, Eigen::MatrixXd* rows) override {
    const std::uint64_t at = begin_ + rows_read;
    const Index count = rows_ahead(max_rows);
    const bool finite = map_ ? detail::decode_npy_rows(layout_, map_ + layout_.data_offset, at, count, rows)
                             : read_rows(count, rows);
    if (!options_.allow_nonfinite && !finite) detail::check_npy_finite(*rows, at, path);
    rows_read += static_cast<std::uint64_t>(count);
    if (map_) drop_decoded_pages();
    return count;
  }
  /// Counts the next rows, at most max_rows, as read without reading them (their reader reads
  /// them later, through direct()) and returns how many.
  Index skip(Index max_rows) {
    const Index count = rows_ahead(max_rows);
    rows_read += static_cast<std::uint64_t>(count);
    return count;
  }
  /// The rows for any thread to read (C order only; nullptr in Fortran order).
  const detail::NpyRows* direct() const { return rows_ ? &*rows_ : nullptr; }
  Index columns() const override { return static_cast<Index>(layout_.cols); }
  std::uint64_t rows() const { return layout_.rows; }  ///< the file's, not only those read
  std::optional<std::uint64_t> rows_declared() const override { return end_ - begin_; }
  double fraction_read() const override {
    return end_ > begin_ ? static_cast<double>(rows_read) / static_cast<double>(end_ - begin_) : 1.0;
  }

 private:
  // The rows the next read takes: at most max_rows, fewer at the end.
  Index rows_ahead(Index max_rows) const {
    const std::uint64_t left = end_ - (begin_ + rows_read);
    return static_cast<Index>(std::min<std::uint64_t>(left, static_cast<std::uint64_t>(max_rows)));
  }

  // The next `count` rows of a C-order file, read into buffer_ and decoded from there; what
  // decode_npy_rows returns (true: every value seen finite).
  bool read_rows(Index count, Eigen::MatrixXd* rows) {
    const char* into = rows_->read_bytes(rows_read, count, &buffer_);
    detail::NpyLayout part = layout_;  // the block alone: its rows from the buffer's start
    part.rows = static_cast<std::uint64_t>(count);
    return detail::decode_npy_rows(part, into, 0, count, rows);
  }

  // The data are one run of rows (C order) or one run per column (Fortran order); in each, the
  // pages wholly before the first row not yet decoded are dropped.
  void drop_decoded_pages() {
    static const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    const bool fortran = layout_.fortran_order;
    const std::uint64_t runs = fortran ? layout_.cols : 1;
    const std::uint64_t run_values = fortran ? layout_.rows : layout_.rows * layout_.cols;
    const std::uint64_t per_row = fortran ? 1 : layout_.cols;
    const std::size_t size = layout_.item_size;
    for (std::uint64_t j = 0; j < runs; ++j) {
      const std::size_t start = layout_.data_offset + size * j * run_values;
      const std::size_t from = (start + size * dropped_rows_ * per_row) / page * page;
      const std::size_t to = (start + size * (begin_ + rows_read) * per_row) / page * page;
      if (to > from) ::madvise(const_cast<char*>(map_) + from, to - from, MADV_DONTNEED);
    }
    dropped_rows_ = begin_ + rows_read;
  }

  std::uint64_t begin_ = 0;  // the first row read (0 but for a part of a split file)
  std::uint64_t end_ = 0;    // one past the last
  std::uint64_t dropped_rows_ = 0;
  const char* map_ = nullptr;  // Fortran order only
  int fd_ = -1;                // C order only
  std::vector<double> buffer_;
  std::size_t size_;
  ReadOptions options_;
  detail::NpyLayout layout_;
  std::optional<detail::NpyRows> rows_;  // C order only
};

// Delimited text, read in pieces that end at a line end and parsed as they arrive.
class RowReader::TextSource final : public RowReader::Source {
 public:
  TextSource(const std::string& path, int fd, const ReadOptions& options)
      : Source(path), file_(::fdopen(fd, "rb")), parser_(path, options) {
    adopt(fd);
    struct stat info {};
    if (::fstat(fd, &info) == 0 && S_ISREG(info.st_mode)) size_ = static_cast<std::uint64_t>(info.st_size);
  }
  // The bytes [begin, end) of the file only, parsed as the file's first lines decided (`layout`):
  // a process's part of a file split among processes. `begin` is a line start after the first
  // data row, preceded by `lines_before` lines; `end` is a line start or the file's end.
  TextSource(const std::string& path, int fd, const ReadOptions& options, const detail::DelimitedParser::Layout& layout,
             std::uint64_t begin, std::uint64_t end, std::uint64_t lines_before)
      : Source(path), file_(::fdopen(fd, "rb")), parser_(path, options, layout, lines_before, begin) {
    adopt(fd);
    if (::fseeko(file_, static_cast<off_t>(begin), SEEK_SET) != 0) fail_errno(path, "read error");
    size_ = end - begin;
    limit_ = size_;
  }
  // Standard input (not closed here), whose first bytes `first` were read already to tell text
  // from .npy.
  // `keep`, when given, keeps a copy of the text read (KeptText).
  TextSource(std::FILE* input, std::string first, const ReadOptions& options,
             std::shared_ptr<detail::KeptText> keep = nullptr)
      : Source(detail::kStdinName), file_(input), owned_(false), parser_(detail::kStdinName, options),
        buffer_(std::move(first)), keep_(std::move(keep)) {
    bytes_ = buffer_.size();
    if (keep_) keep_->keep(buffer_.data(), buffer_.size());
  }
  ~TextSource() override {
    if (owned_) std::fclose(file_);
  }

  // Reads no further than byte `end` (a line start), and learns the file's layout from its first
  // lines: the first part of a file split among processes.
  void limit_to(std::uint64_t end) {
    limit_ = end;
    size_ = end;
  }
  detail::DelimitedParser::Layout layout() const { return parser_.layout(); }

  Index read(Index max_rows, Eigen::MatrixXd* rows) override {
    while (available() < static_cast<std::size_t>(max_rows) && !at_end_) read_piece();
    if (at_end_) parser_.finish();  // no data rows at all: the error read_table gives
    const Index count = static_cast<Index>(std::min(available(), static_cast<std::size_t>(max_rows)));
    const Index n = columns();
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    std::vector<double>& values = parser_.values();
    *rows = Eigen::Map<const RowMajor>(values.data() + taken_ * static_cast<std::size_t>(n), count, n);
    taken_ += static_cast<std::size_t>(count);
    // Drop the rows handed out once they are half the buffer, so that memory stays O(block).
    if (2 * taken_ * static_cast<std::size_t>(n) >= values.size()) {
      values.erase(values.begin(),
                   values.begin() + static_cast<std::ptrdiff_t>(taken_ * static_cast<std::size_t>(n)));
      taken_ = 0;
    }
    rows_read += static_cast<std::uint64_t>(count);
    return count;
  }
  Index columns() const override { return static_cast<Index>(parser_.columns()); }
  const std::vector<std::string>& column_names() const override { return parser_.column_names(); }
  const std::vector<Warning>& warnings() const override { return parser_.warnings(); }
  const std::vector<std::vector<std::size_t>>& selected_columns() const override {
    return parser_.selected_columns();
  }
  double fraction_read() const override {
    if (at_end_) return 1.0;
    return size_ > 0 ? std::min(1.0, static_cast<double>(bytes_) / static_cast<double>(size_)) : 0.0;
  }

 private:
  // Rows parsed but not yet handed out.
  std::size_t available() const {
    const std::size_t n = parser_.columns();
    return n == 0 ? 0 : parser_.values().size() / n - taken_;
  }

  // Owns `fd` through file_, or closes it and throws when fdopen failed.
  void adopt(int fd) {
    if (file_ != nullptr) return;
    const int error = errno;
    ::close(fd);
    errno = error;
    fail_errno(path, "cannot be opened");
  }

  // Reads about kTextPieceBytes more bytes and parses the whole lines among them; the bytes
  // after the last line end wait for the next piece. A CR at the very end waits too, since
  // an LF may follow it in the next piece (CR LF is one line end).
  void read_piece() {
    const std::size_t kept = buffer_.size();
    const auto want = static_cast<std::size_t>(std::min<std::uint64_t>(RowReader::kTextPieceBytes, limit_ - bytes_));
    buffer_.resize(kept + want);
    const std::size_t got = std::fread(buffer_.data() + kept, 1, want, file_);
    buffer_.resize(kept + got);
    bytes_ += got;
    if (keep_) keep_->keep(buffer_.data() + kept, got);
    if (std::ferror(file_)) fail_errno(path, "read error");
    if (got < RowReader::kTextPieceBytes) {  // the end (of the file or the part): the rest is the last line(s)
      parser_.feed(buffer_);
      buffer_.clear();
      at_end_ = true;
      return;
    }
    // The bytes kept from before hold no line end, bar a held-back CR as their last byte.
    auto line_end = [](char c) { return c == '\n' || c == '\r'; };
    std::size_t cut = buffer_.size() - (buffer_.back() == '\r' ? 1 : 0);
    const std::size_t floor = kept > 0 ? kept - 1 : 0;
    while (cut > floor && !line_end(buffer_[cut - 1])) --cut;
    if (cut == floor) {
      // No line end yet: the line goes on into the next piece.
      if (buffer_.size() > RowReader::kMaxLineBytes) {
        throw DataError(path, parser_.lines() + 1, 0,
                        "a line is longer than " + std::to_string(RowReader::kMaxLineBytes >> 20) +
                            " MiB; the streaming reader accepts lines up to that length");
      }
      return;
    }
    parser_.feed(std::string_view(buffer_.data(), cut));
    buffer_.erase(0, cut);
  }

  std::FILE* file_;
  bool owned_ = true;
  detail::DelimitedParser parser_;
  std::string buffer_;     // bytes read but not yet parsed (an incomplete last line)
  std::shared_ptr<detail::KeptText> keep_;  // standard input's text kept for a second reading
  std::size_t taken_ = 0;  // rows at the front of parser_.values() already handed out
  bool at_end_ = false;
  std::uint64_t bytes_ = 0;  // read from the file so far
  std::uint64_t size_ = 0;   // the file's size (0: not a regular file), or the part's
  std::uint64_t limit_ = std::numeric_limits<std::uint64_t>::max();  // bytes to read at most
};

// A variable of a MATLAB 7.3 file (HDF5), read a block of rows at a time. libmatio opens the
// dataset anew for each read, and so decompresses each chunk anew: it is read in slabs of about
// 8 MB (or the block, if larger), which the blocks are cut from.
class RowReader::MatSource final : public RowReader::Source {
 public:
  MatSource(const std::string& path, const detail::FileSpec& spec, const ReadOptions& options)
      : Source(path), blocks_(spec), options_(options) {
    select(options);
  }
  Index read(Index max_rows, Eigen::MatrixXd* rows) override {
    const auto count = static_cast<Index>(
        std::min<std::uint64_t>(blocks_.rows() - rows_read, static_cast<std::uint64_t>(max_rows)));
    if (rows_read + static_cast<std::uint64_t>(count) > slab_first_ + static_cast<std::uint64_t>(slab_.rows())) {
      const Index slab_rows = std::max<Index>(count, kSlabBytes / (8 * std::max<Index>(1, blocks_.columns())));
      slab_first_ = rows_read;
      blocks_.read(slab_first_,
                   static_cast<Index>(std::min<std::uint64_t>(blocks_.rows() - slab_first_,
                                                              static_cast<std::uint64_t>(slab_rows))),
                   &slab_);
    }
    *rows = slab_.middleRows(static_cast<Index>(rows_read - slab_first_), count);
    if (!options_.allow_nonfinite) detail::check_npy_finite(*rows, rows_read, blocks_.name());
    rows_read += static_cast<std::uint64_t>(count);
    return count;
  }
  Index columns() const override { return blocks_.columns(); }
  double fraction_read() const override {
    return static_cast<double>(rows_read) / static_cast<double>(blocks_.rows());
  }
  std::optional<std::uint64_t> rows_declared() const override { return blocks_.rows(); }

 private:
  static constexpr Index kSlabBytes = Index{8} << 20;
  detail::MatRowBlocks blocks_;
  ReadOptions options_;
  Eigen::MatrixXd slab_;
  std::uint64_t slab_first_ = 0;
};

// A .mat or .npz file, or a .npy file on standard input, read whole (their libraries read whole
// arrays; a pipe cannot be mapped) and handed out a block at a time, with a warning on memory.
class RowReader::TableSource final : public RowReader::Source {
 public:
  TableSource(const std::string& path, Table table) : Source(path), table_(std::move(table)) {
    table_.warnings.push_back(Warning(Code::FileNotice, 
        (path == "-" ? std::string("standard input") : path) +
        " is read whole, not a block at a time (text, MATLAB 7.3 files and .npy files named by path are "
        "streamed; .npz, older .mat files and .npy on standard input are not): memory grows with its rows"));
  }
  Index read(Index max_rows, Eigen::MatrixXd* rows) override {
    const Index left = table_.values.rows() - static_cast<Index>(rows_read);
    const Index count = std::min(max_rows, left);
    *rows = table_.values.middleRows(static_cast<Index>(rows_read), count);
    rows_read += static_cast<std::uint64_t>(count);
    return count;
  }
  Index columns() const override { return table_.values.cols(); }
  std::optional<std::uint64_t> rows_declared() const override {
    return static_cast<std::uint64_t>(table_.values.rows());
  }
  double fraction_read() const override {
    return static_cast<double>(rows_read) / static_cast<double>(table_.values.rows());
  }
  const std::vector<std::string>& column_names() const override { return table_.column_names; }
  const std::vector<Warning>& warnings() const override { return table_.warnings; }
  const std::vector<std::vector<std::size_t>>& selected_columns() const override {
    return table_.selected_columns;
  }

 private:
  Table table_;
};

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
