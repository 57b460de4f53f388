#include "npy_rows.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <utility>

#include "file_error.hpp"
#include "spdfit/io.hpp"

namespace spdfit::io::detail {

using Eigen::Index;

NpyRows::NpyRows(int fd, const NpyLayout& layout, std::uint64_t begin, std::string path, bool allow_nonfinite)
    : fd_(fd), layout_(layout), begin_(begin), path_(std::move(path)), allow_nonfinite_(allow_nonfinite) {}

const char* NpyRows::read_bytes(std::uint64_t first, Index count, std::vector<double>* bytes) const {
  const std::size_t row_bytes = layout_.item_size * layout_.cols;
  const std::size_t size = row_bytes * static_cast<std::size_t>(count);
  bytes->resize((size + sizeof(double) - 1) / sizeof(double));  // doubles: aligned for any item
  char* into = reinterpret_cast<char*>(bytes->data());
  const std::uint64_t offset = layout_.data_offset + (begin_ + first) * row_bytes;
  for (std::size_t done = 0; done < size;) {
    const ssize_t got = ::pread(fd_, into + done, size - done, static_cast<off_t>(offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw DataError(path_, 0, 0, "read error (" + describe_errno(errno) + ")");
    if (got == 0) throw DataError(path_, 0, 0, "ends before the rows its header declares (was it truncated?)");
    done += static_cast<std::size_t>(got);
  }
  return into;
}

DecodedExtent NpyRows::read(std::uint64_t first, Index count, Eigen::Ref<Eigen::MatrixXd> out,
                            std::vector<double>* bytes) const {
  if (count == 0) return {};
  return decode_c_order_rows(layout_, read_bytes(first, count, bytes), count, out);
}

void NpyRows::check_finite(std::uint64_t first, Index count, std::vector<double>* bytes) const {
  if (allow_nonfinite_ || count == 0) return;
  // Only on the way to an error: a block's rows decoded whole, as RowReader::read decodes them.
  Eigen::MatrixXd rows(count, columns());
  if (!read(first, count, rows, bytes).finite) check_npy_finite(rows, begin_ + first, path_);
}

}  // namespace spdfit::io::detail
