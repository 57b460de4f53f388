// Files that hold named arrays: which files they are (decided by their first bytes), the
// "file:name" way of naming one, and standard input. The readers are mat_file.cpp (libmatio) and
// npz_file.cpp (libzip).
#include "containers.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "file_error.hpp"
#include "spdfit/named_arrays.hpp"

namespace spdfit::io::detail {

namespace {

bool exists(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0;
}

// A ZIP archive's first bytes: a local file header, or the end record of an archive with no
// entries (np.savez with no arrays).
bool is_zip(std::string_view first) {
  const std::string_view magic = first.substr(0, 4);
  return magic == std::string_view("PK\x03\x04", 4) || magic == std::string_view("PK\x05\x06", 4);
}

// Whether the file's name ends in .npz (any case).
bool named_npz(const std::string& path) {
  if (path.size() < 4) return false;
  std::string tail = path.substr(path.size() - 4);
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return std::tolower(c); });
  return tail == ".npz";
}

}  // namespace

std::string listed_names(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t k = 0; k < names.size() && k < 20; ++k) out += (k ? ", " : "") + names[k];
  if (names.size() > 20) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out;
}

std::uint64_t file_size(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 ? static_cast<std::uint64_t>(info.st_size) : 0;
}

bool is_mat(std::string_view first) {
  // A 128-byte header (text, subsystem offset, version 0x0100 or 0x0200, endian "IM" or "MI").
  if (first.size() < 128 || first.substr(0, 7) != "MATLAB ") return false;
  const std::string_view endian = first.substr(126, 2);
  return endian == "IM" || endian == "MI";
}

bool is_level5(std::string_view first) {
  if (!is_mat(first)) return false;
  // The version, 0x0100 for level 5 (0x0200: 7.3), in the byte order "IM" or "MI" says.
  const auto b124 = static_cast<unsigned char>(first[124]), b125 = static_cast<unsigned char>(first[125]);
  const unsigned version = first.substr(126, 2) == "IM" ? b124 | (b125 << 8) : (b124 << 8) | b125;
  return version == 0x0100;
}

// Up to `count` first bytes of the file ("" when it cannot be read: its reader then says why).
std::string first_bytes(const std::string& path, std::size_t count) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode)) return "";
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!file) return "";
  std::string out(count, '\0');
  out.resize(std::fread(out.data(), 1, count, file.get()));
  return out;
}

std::string read_standard_input(std::string bytes, std::size_t at_most) {
  char buffer[1 << 16];
  while (bytes.size() < at_most) {
    const std::size_t want = std::min(sizeof buffer, at_most - bytes.size());
    const std::size_t got = std::fread(buffer, 1, want, stdin);
    bytes.append(buffer, got);
    if (got < want) break;
  }
  if (std::ferror(stdin)) throw DataError(kStdinName, 0, 0, "read error");
  if (bytes.empty()) throw DataError(kStdinName, 0, 0, "is empty");
  return bytes;
}

NamedArrays named_arrays_kind(const FileSpec& spec) {
  if (spec.file == "-") return NamedArrays::None;
  const std::string head = first_bytes(spec.file, 128);
  if (is_mat(head)) return is_level5(head) ? NamedArrays::Mat : NamedArrays::Mat73;
  // A ZIP archive with .npy entries, or one named .npz (so that a damaged or empty one is called
  // that, not a spreadsheet saved in the wrong format, as text_scan says of other ZIP files).
  if (is_zip(head) && (named_npz(spec.file) || holds_npy(spec.file))) return NamedArrays::Npz;
  return NamedArrays::None;
}

std::optional<Table> read_named_arrays(const FileSpec& spec, const ReadOptions& options) {
  switch (named_arrays_kind(spec)) {
    case NamedArrays::Mat:
    case NamedArrays::Mat73:
      return read_mat(spec.file, spec.variable, options);
    case NamedArrays::Npz:
      return read_npz(spec.file, spec.variable, options);
    case NamedArrays::None:
      break;
  }
  return std::nullopt;
}

}  // namespace spdfit::io::detail

namespace spdfit::io {

FileSpec split_spec(const std::string& path) {
  if (path == "-" || detail::exists(path)) return {path, ""};
  const std::size_t colon = path.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == path.size()) return {path, ""};
  const std::string file = path.substr(0, colon);
  if (!detail::exists(file)) return {path, ""};
  return {file, path.substr(colon + 1)};
}

bool holds_named_arrays(const std::string& file) {
  if (file == "-" || !detail::exists(file)) return false;
  try {
    return detail::named_arrays_kind({file, ""}) != detail::NamedArrays::None;
  } catch (const DataError&) {
    return false;  // unreadable: the reader says why
  }
}

}  // namespace spdfit::io
