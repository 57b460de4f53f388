// Internal: the check of a level-5 .mat file's structure that runs before libmatio reads it.
#pragma once

#include <string>
#include <string_view>

namespace spdfit::io::detail {

/// Checks the whole of a level-5 .mat file (`bytes`, its 128-byte header first) as libmatio will
/// read it, so that libmatio allocates nothing the file does not hold: libmatio trusts each size
/// the file declares with an allocation before it reads the bytes, and reads some elements at
/// fixed places instead of where their tags put them. Every element must therefore sit where
/// libmatio looks for it (flags of 8 bytes, names as miINT8, a struct's field name length as one
/// small miINT32, unnamed struct fields, all the cells and fields an array declares), and every
/// size libmatio allocates from (dimensions, name and field name lengths, a char array's data,
/// a sparse array's indices and values, a function handle's elements) must fit in the bytes that
/// hold it. Compressed elements are inflated (at most kMaxExpansion times their size) and checked
/// the same way. Throws DataError naming `file` (and the variable, when its name was read):
/// "is a damaged .mat file (variable 'x': ...)".
void check_level5_structure(const std::string& file, std::string_view bytes);

/// How much larger than its compressed size a deflated element may become (deflate's own
/// limit is about 1032:1).
inline constexpr unsigned kMaxExpansion = 1100;

}  // namespace spdfit::io::detail
