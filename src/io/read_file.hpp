// Reading a whole file into memory with the checks every reader of untrusted files needs
// (internal: the matrix readers in src/io and the geometry reader in src/hexapod use it).
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <string_view>

namespace spdfit::io::detail {

/// Throws DataError naming `path` unless it is a regular file (missing, a directory, a FIFO, a
/// device, a socket, or not reachable for lack of permission). Checked with stat before
/// opening, because opening a FIFO for reading blocks until someone writes to it.
void check_regular_file(const std::string& path);

/// How many bytes read_file shows `inspect` before reading the rest.
inline constexpr std::size_t kInspectBytes = std::size_t{1} << 16;

/// The bytes of the regular file at `path`. Throws DataError naming `path` when it is missing,
/// a directory, a FIFO, a device or a socket (checked before opening, so that a FIFO does not
/// block and /dev/zero is not read forever), unreadable, or longer than `max_bytes` (checked
/// before reading, with `what` naming the kind of file in the message). `inspect`, when given,
/// sees the first kInspectBytes bytes (or the whole file, if shorter) before the rest is read,
/// and may throw to refuse the file without reading it all: a sparse file of gigabytes of zeros
/// takes no disk space. Memory: the file's size.
std::string read_file(const std::string& path,
                      std::size_t max_bytes = std::numeric_limits<std::size_t>::max(),
                      const std::string& what = "a file",
                      const std::function<void(std::string_view)>& inspect = nullptr);

}  // namespace spdfit::io::detail
