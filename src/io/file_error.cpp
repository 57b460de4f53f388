#include "file_error.hpp"

#include <cerrno>
#include <cstring>

namespace spdfit::io::detail {

std::string describe_errno(int error) {
  // The common cases get wording of our own; strerror's is capitalized and varies by platform.
  switch (error) {
    case ENOENT:
      return "no such file";
    case ENOTDIR:
      return "no such file (a part of the path is not a directory)";
    case EACCES:
    case EPERM:
      return "permission denied";
    case EISDIR:
      return "is a directory";
    case ENOSPC:
      return "no space left on the device";
    case EROFS:
      return "the file system is read-only";
    default:
      break;
  }
  std::string text = std::strerror(error);
  if (!text.empty() && text[0] >= 'A' && text[0] <= 'Z') {
    text[0] = static_cast<char>(text[0] - 'A' + 'a');
  }
  return text;
}

}  // namespace spdfit::io::detail
