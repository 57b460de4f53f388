// Splitting a data file among processes by rows: the counting pass and finding a row's line.
// (Opening the file and its parts' readers is in row_reader.cpp, next to the readers.)
#include "split_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "file_error.hpp"

namespace spdfit::io::detail {

namespace {

constexpr std::size_t kScanBytes = std::size_t{1} << 20;

// An open file descriptor, closed on every path.
class Descriptor {
 public:
  explicit Descriptor(const std::string& path) : fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC)) {
    if (fd_ < 0) throw DataError(path, 0, 0, "cannot be opened (" + describe_errno(errno) + ")");
  }
  ~Descriptor() { ::close(fd_); }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

// The first byte of part `part` of `parts` of `size` bytes.
std::uint64_t part_begin(std::uint64_t size, int part, int parts) {
  return scaled_share(size, static_cast<std::uint64_t>(part), static_cast<std::uint64_t>(parts));
}

// Calls visit(start, has_content) for each line that starts in the bytes [begin, end) of the
// file, in order, until visit returns false. Lines end as the parser ends them (LF, CR LF or a
// lone CR); a line has content unless it is blank (spaces and tabs only, or a spreadsheet's empty
// row of commas and semicolons) or a comment ('#' or '%' first), as the parser decides, the UTF-8
// byte-order mark at the file's start not counting.
template <class Visit>
void scan_lines(const std::string& path, std::uint64_t begin, std::uint64_t end, Visit visit) {
  const Descriptor fd(path);
  std::vector<char> buffer(kScanBytes);
  std::uint64_t at = begin > 0 ? begin - 1 : 0;  // the byte before begin tells whether begin starts a line
  bool next_is_start = at == 0;
  bool after_cr = false;
  bool pending = false;  // a line has started and its content is not decided yet
  std::uint64_t start = 0;
  std::uint64_t bom_end = 0;
  for (;;) {
    const ssize_t got = ::pread(fd.get(), buffer.data(), buffer.size(), static_cast<off_t>(at));
    if (got < 0) throw DataError(path, 0, 0, "read error (" + describe_errno(errno) + ")");
    if (got == 0) break;
    const char* bytes = buffer.data();
    const auto count = static_cast<std::size_t>(got);
    if (at == 0 && count >= 3 && std::memcmp(bytes, "\xEF\xBB\xBF", 3) == 0) bom_end = 3;
    std::size_t k = 0;
    while (k < count) {
      if (!pending && !next_is_start && !after_cr) {
        // Inside a line whose content is decided: skip to its end.
        const char* lf = static_cast<const char*>(std::memchr(bytes + k, '\n', count - k));
        const std::size_t stop = lf ? static_cast<std::size_t>(lf - bytes) : count;
        const char* cr = static_cast<const char*>(std::memchr(bytes + k, '\r', stop - k));
        if (cr != nullptr) {
          k = static_cast<std::size_t>(cr - bytes) + 1;
          after_cr = true;
        } else if (lf != nullptr) {
          k = stop + 1;
          next_is_start = true;
        } else {
          k = count;
        }
        continue;
      }
      const char b = bytes[k];
      const std::uint64_t p = at + k;
      if (next_is_start || (after_cr && b != '\n')) {
        if (p >= end) return;
        if (p >= begin) {
          pending = true;
          start = p;
        }
      }
      next_is_start = false;
      after_cr = false;
      if (pending && p >= bom_end && b != ' ' && b != '\t' && b != ',' && b != ';') {
        pending = false;
        const bool content = b != '\n' && b != '\r' && b != '#' && b != '%';
        if (!visit(start, content)) return;
      }
      if (b == '\n') next_is_start = true;
      if (b == '\r') after_cr = true;
      ++k;
    }
    at += count;
  }
  if (pending) visit(start, false);  // spaces up to the end of the file
}

}  // namespace

std::vector<std::uint64_t> SplitFile::count() const {
  if (npy_) return {};
  std::uint64_t lines = 0;
  std::uint64_t content = 0;
  scan_lines(path_, part_begin(size_, part_, parts_), part_begin(size_, part_ + 1, parts_),
             [&](std::uint64_t, bool has_content) {
               ++lines;
               content += has_content ? 1 : 0;
               return true;
             });
  return {lines, content};
}

void SplitFile::set_counts(const std::vector<std::vector<std::uint64_t>>& counts) {
  if (npy_) return;
  if (counts.size() != static_cast<std::size_t>(parts_)) throw std::invalid_argument("SplitFile: a count per part");
  counts_ = counts;
  std::uint64_t content = 0;
  for (const std::vector<std::uint64_t>& c : counts_) {
    if (c.size() != 2) throw std::invalid_argument("SplitFile: two numbers per part");
    content += c[1];
  }
  const std::uint64_t header = (layout_.have_header ? 1 : 0) + (layout_.units_row ? 1 : 0);
  rows_ = content >= header ? content - header : 0;
}

LinePosition SplitFile::locate(std::uint64_t row) const {
  if (npy_) return {row, 0};
  if (row > rows_) throw std::invalid_argument("SplitFile::locate: row beyond the file");
  // among the lines with content: the header's, and a units row's under it
  const std::uint64_t wanted = row + (layout_.have_header ? 1 : 0) + (layout_.units_row ? 1 : 0);
  std::uint64_t lines_before = 0;
  std::uint64_t content_before = 0;
  int part = 0;
  while (part < parts_ && content_before + counts_[static_cast<std::size_t>(part)][1] <= wanted) {
    lines_before += counts_[static_cast<std::size_t>(part)][0];
    content_before += counts_[static_cast<std::size_t>(part)][1];
    ++part;
  }
  if (part == parts_) return {size_, lines_before};  // the end of the file
  LinePosition found;
  scan_lines(path_, part_begin(size_, part, parts_), part_begin(size_, part + 1, parts_),
             [&](std::uint64_t start, bool has_content) {
               if (has_content && content_before++ == wanted) {
                 found = {start, lines_before};
                 return false;
               }
               ++lines_before;
               return true;
             });
  return found;
}

}  // namespace spdfit::io::detail
