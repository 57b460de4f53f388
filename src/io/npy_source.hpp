// Internal, included by row_reader.cpp only: a .npy file read a block of rows at a time.
#pragma once

#include "row_source.hpp"

namespace spdfit::io {

using Eigen::Index;

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

}  // namespace spdfit::io
