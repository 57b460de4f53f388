// Internal, included by row_reader.cpp only: delimited text read a block of rows at a time.
#pragma once

#include "row_source.hpp"

namespace spdfit::io {

using Eigen::Index;

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

}  // namespace spdfit::io
