// Turning the errno of a failed file operation into words for a DataError.
#pragma once

#include <string>

namespace spdfit::io::detail {

/// A short lower-case description of `error` (an errno value), e.g. "permission denied".
std::string describe_errno(int error);

/// Opens `path` for writing (creating or truncating it) and closes it again, so that a writer
/// whose library gives no reason (libmatio) fails with one. Throws DataError "cannot be written
/// (no such directory)", "(permission denied)", ...
void check_writable(const std::string& path);

}  // namespace spdfit::io::detail
