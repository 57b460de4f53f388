// Turning the errno of a failed file operation into words for a DataError.
#pragma once

#include <string>

namespace spdfit::io::detail {

/// A short lower-case description of `error` (an errno value), e.g. "permission denied".
std::string describe_errno(int error);

}  // namespace spdfit::io::detail
