// The structure of a level-5 .mat file, checked the way libmatio (1.5) reads it. libmatio reads
// an array's parts in sequence: flags and the dimensions' tag as six words at fixed places, then
// the name (miINT8 only, in a tag of 8 bytes in struct fields), then what the class holds, and it
// allocates each size it meets before it reads the bytes: a damaged 200-byte file could ask for
// 2^64 bytes. So this check reads the parts in the same order, refuses the layouts in which the
// tags would put a part elsewhere than libmatio reads it, and bounds every size libmatio
// allocates from by the bytes that are there.
#include "mat_structure.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>

#include "spdfit/io.hpp"

namespace spdfit::io::detail {

namespace {

// Data types of elements.
constexpr std::uint32_t kMiInt8 = 1, kMiInt32 = 5, kMiUint32 = 6, kMiMatrix = 14, kMiCompressed = 15;
// Array classes (the low byte of an array's flags).
constexpr std::uint32_t kCell = 1, kStruct = 2, kObject = 3, kChar = 4, kSparse = 5, kFunction = 16, kOpaque = 17;
constexpr std::uint32_t kComplexFlag = 0x800;
constexpr int kMaxDepth = 32;
// MATLAB's field names have at most 63 characters and a NUL.
constexpr std::uint32_t kMaxFieldNameLength = 64;

// The size of one value of a numeric data type (0 for the others).
std::size_t value_size(std::uint32_t type) {
  switch (type) {
    case 1: case 2: return 1;            // miINT8, miUINT8
    case 3: case 4: return 2;            // miINT16, miUINT16
    case 5: case 6: case 7: return 4;    // miINT32, miUINT32, miSINGLE
    case 9: case 12: case 13: return 8;  // miDOUBLE, miINT64, miUINT64
    default: return 0;
  }
}

// Where an array sits: libmatio reads the name of each differently.
enum class Place { TopLevel, Cell, Field };

struct Element {
  std::uint32_t type = 0;
  std::uint32_t bytes = 0;
  std::string_view data;
  bool small = false;  // type, size and data in 8 bytes
};

std::string printable_name(std::string_view data) {
  std::string out;
  for (const char c : data.substr(0, std::min<std::size_t>(data.size(), 63))) {
    if (c == '\0') break;
    if (c < 0x20 || c > 0x7e) return "";
    out += c;
  }
  return out;
}

class Checker {
 public:
  Checker(std::string file, bool swap) : file_(std::move(file)), swap_(swap) {}

  // The top-level elements of the file's body (after the 128-byte header).
  void check_body(std::string_view body) {
    std::size_t at = 0;
    for (int number = 1; at + 8 <= body.size(); ++number) {
      variable_ = "variable number " + std::to_string(number);
      at = check_top_level(body, at, /*in_stream=*/false, 0, /*names_variable=*/true);
    }
  }

 private:
  [[noreturn]] void bad(const std::string& why) const {
    throw DataError(file_, 0, 0, "is a damaged .mat file (" + variable_ + ": " + why + ")");
  }

  std::uint32_t u32(std::string_view s, std::size_t at) const {
    std::uint32_t v = 0;
    std::memcpy(&v, s.data() + at, 4);
    return swap_ ? __builtin_bswap32(v) : v;
  }

  // The element at `*at`, which then moves past it: past its padding to 8 bytes, except for
  // arrays and compressed elements, which libmatio reads unpadded.
  Element next(std::string_view s, std::size_t* at) const {
    if (*at + 8 > s.size()) bad("an element's tag is cut off");
    Element e;
    const std::uint32_t word = u32(s, *at);
    if ((word >> 16) != 0) {
      e.type = word & 0xffff;
      e.bytes = word >> 16;
      e.small = true;
      if (e.bytes > 4) bad("a small element of more than 4 bytes");
      e.data = s.substr(*at + 4, e.bytes);
      *at += 8;
      return e;
    }
    e.type = word;
    e.bytes = u32(s, *at + 4);
    if (e.bytes > s.size() - *at - 8) bad("an element declares " + std::to_string(e.bytes) + " bytes, more than it holds");
    e.data = s.substr(*at + 8, e.bytes);
    const std::size_t end = *at + 8 + e.bytes;
    *at = e.type == kMiMatrix || e.type == kMiCompressed ? end : std::min(s.size(), (end + 7) / 8 * 8);
    return e;
  }

  // A variable as Mat_VarReadNextInfo reads it (at the top level of the file, of a compressed
  // element's stream, or in a function handle): an array, or (not in a stream) a compressed one.
  // Returns where the next one starts.
  std::size_t check_top_level(std::string_view s, std::size_t at, bool in_stream, int depth, bool names_variable) {
    if (depth > kMaxDepth) bad("arrays nested over " + std::to_string(kMaxDepth) + " deep");
    // Read as two words, never as a small element.
    const std::uint32_t type = u32(s, at);
    if (type != kMiMatrix && !(type == kMiCompressed && !in_stream)) {
      bad(type == kMiCompressed ? "a compressed element inside a compressed element"
                                : "a top-level element of type " + std::to_string(type) + ", not an array");
    }
    const Element e = next(s, &at);
    if (e.type == kMiMatrix) {
      if (e.data.empty()) bad("an empty top-level array element");
      check_array(e.data, in_stream, Place::TopLevel, depth, names_variable);
      return at;
    }
    const std::string body = inflate(e.data);
    if (body.size() < 8) bad("a compressed element without an array");
    for (std::size_t k = 0; k + 8 <= body.size();) k = check_top_level(body, k, true, depth, names_variable);
    return at;
  }

  std::string inflate(std::string_view data) const {
    const std::uint64_t most = std::uint64_t{kMaxExpansion} * (data.size() + 1024);
    z_stream z{};
    if (inflateInit(&z) != Z_OK) bad("cannot inflate a compressed element");
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
    z.avail_in = static_cast<uInt>(data.size());
    std::string out;
    char buffer[1 << 15];
    int status = Z_OK;
    while (status == Z_OK) {
      z.next_out = reinterpret_cast<Bytef*>(buffer);
      z.avail_out = sizeof buffer;
      status = ::inflate(&z, Z_NO_FLUSH);
      out.append(buffer, sizeof buffer - z.avail_out);
      if (out.size() > most) {
        inflateEnd(&z);
        bad("a compressed element expands beyond " + std::to_string(kMaxExpansion) + " times its size");
      }
    }
    inflateEnd(&z);
    // A stream that goes on past its element's bytes: libmatio would read on into what follows.
    if (status != Z_STREAM_END) bad("a compressed element does not inflate");
    return out;
  }

  // The contents of an array element.
  void check_array(std::string_view s, bool compressed, Place place, int depth, bool names_variable = false) {
    if (depth > kMaxDepth) bad("arrays nested over " + std::to_string(kMaxDepth) + " deep");
    if (s.empty()) return;  // an empty cell or field
    // libmatio reads 24 bytes at fixed places: the flags element and the dimensions' tag.
    if (s.size() < 24 || u32(s, 0) != kMiUint32 || u32(s, 4) != 8) bad("an array's flags are not one miUINT32 element of 8 bytes");
    const std::uint32_t flags = u32(s, 8);
    const std::uint32_t array_class = flags & 0xff;
    if (array_class < 1 || array_class > kOpaque) bad("an array of class " + std::to_string(array_class));
    const std::uint32_t nzmax = u32(s, 12);
    std::size_t at = 16;
    if (array_class == kOpaque) return check_opaque(s, compressed);

    if (u32(s, at) != kMiInt32) bad("an array without its dimensions");
    const Element dims = next(s, &at);
    if (dims.bytes < 8 || dims.bytes % 4 != 0) bad("an array without its dimensions");
    std::uint64_t count = 1, columns = 0;
    for (std::size_t k = 0; k < dims.bytes / 4; ++k) {
      const auto d = static_cast<std::int32_t>(u32(dims.data, 4 * k));
      if (d < 0) bad("a negative dimension");
      const auto n = static_cast<std::uint64_t>(d);
      if (k == 1) columns = n;
      count = n != 0 && count > UINT64_MAX / n ? UINT64_MAX : count * n;
    }

    const Element name = next(s, &at);
    if (name.type != kMiInt8) bad("the name of an array is an element of type " + std::to_string(name.type) + ", not miINT8");
    // libmatio reads 8 bytes of a field's name element, and the field's parts after them.
    if (place == Place::Field && !name.small && name.bytes > 0) bad("a struct field with a name of its own");
    if (names_variable) {
      const std::string printable = printable_name(name.data);
      if (!printable.empty()) variable_ = "variable '" + printable + "'";
    }

    const std::uint64_t rest = s.size() - std::min(s.size(), at);
    switch (array_class) {
      case kCell: {
        if (count > rest / 8) bad("a cell array declares " + std::to_string(count) + " cells in " + std::to_string(rest) + " bytes");
        for (std::uint64_t k = 0; k < count; ++k) {
          if (at >= s.size()) bad("a cell array declares " + std::to_string(count) + " cells and holds " + std::to_string(k));
          const Element cell = next(s, &at);
          if (cell.type != kMiMatrix || cell.small) bad("a cell that is not an array");
          check_array(cell.data, compressed, Place::Cell, depth + 1);
        }
        return;
      }
      case kStruct: {
        // The field name length as MATLAB writes it, one small miINT32 element: libmatio reads
        // the word after the tag's first as the length, whatever the tag says.
        if (at + 8 > s.size() || u32(s, at) != ((4u << 16) | kMiInt32)) bad("a struct without its field name length");
        const std::uint32_t name_length = u32(s, at + 4);
        at += 8;
        if (name_length < 1 || name_length > kMaxFieldNameLength) bad("a struct's field names of length " + std::to_string(name_length));
        const Element names = next(s, &at);
        if (names.type != kMiInt8 || names.bytes % name_length != 0) bad("a struct's field names that do not fit their length");
        const std::uint64_t fields = names.bytes / name_length;
        const std::uint64_t left = s.size() - std::min(s.size(), at);
        if (fields != 0 && count > left / 8 / fields) bad("a struct array declares more fields than it holds");
        const std::uint64_t total = count * fields;
        for (std::uint64_t k = 0; k < total; ++k) {
          if (at >= s.size()) bad("a struct array declares " + std::to_string(total) + " fields and holds " + std::to_string(k));
          const Element field = next(s, &at);
          if (field.type != kMiMatrix || field.small) bad("a field that is not an array");
          check_array(field.data, compressed, Place::Field, depth + 1);
        }
        return;
      }
      case kObject:
        return;  // libmatio reads nothing of an object past its name
      case kChar: {
        if (count > rest) bad("an array declares " + std::to_string(count) + " values in " + std::to_string(rest) + " bytes");
        // libmatio reads the char arrays of small compressed fields and cells as it lists the
        // variables, allocating what their data element's tag declares.
        if (at >= s.size()) bad("a char array without its data");
        next(s, &at);
        return;
      }
      case kSparse: {
        // Row indices (nzmax) and column starts (columns + 1), 4 bytes each; libmatio allocates
        // what each of the index and value elements declares.
        if (nzmax > rest / 4 || columns + 1 > rest / 4) bad("a sparse array declares more entries than it holds");
        for (int k = 0; k < 2; ++k) {
          const Element index = next(s, &at);
          if ((index.type != kMiInt32 && index.type != kMiUint32) || index.bytes % 4 != 0) bad("a sparse array's indices are not int32 elements");
        }
        const int parts = flags & kComplexFlag ? 2 : 1;
        for (int k = 0; k < parts; ++k) {
          const Element values = next(s, &at);
          const std::size_t size = value_size(values.type);
          // The imaginary part is read where the real part's values end.
          if (size == 0 || (parts == 2 && values.bytes % size != 0)) bad("a sparse array's values of type " + std::to_string(values.type));
        }
        return;
      }
      case kFunction: {
        // libmatio reads a function handle's elements only at the top level of the file, as
        // variables: one pointer for each, then each variable.
        if (compressed || place != Place::TopLevel) return;
        if (count > rest / 8) bad("a function handle declares " + std::to_string(count) + " elements in " + std::to_string(rest) + " bytes");
        for (std::uint64_t k = 0; k < count; ++k) {
          if (at + 8 > s.size()) bad("a function handle declares " + std::to_string(count) + " elements and holds " + std::to_string(k));
          at = check_top_level(s, at, false, depth + 1, false);
        }
        return;
      }
      default:  // numeric and logical arrays: at least one byte per value
        if (count > rest) bad("an array declares " + std::to_string(count) + " values in " + std::to_string(rest) + " bytes");
    }
  }

  // An opaque object (MATLAB's classdef objects: string, table, ...): flags, then its name and
  // class, no dimensions. libmatio reads nothing more of it in a compressed variable; in an
  // uncompressed one it reads the 8 bytes after the flags as the dimensions' tag, and the
  // dimensions after them when that tag is miINT32, then a name tag, allocating what each
  // declares.
  void check_opaque(std::string_view s, bool compressed) const {
    if (compressed) return;
    std::size_t at = 24;
    if (u32(s, 16) == kMiInt32) {
      at = 16;
      const Element dims = next(s, &at);
      if (dims.bytes % 4 != 0) bad("an array without its dimensions");
    }
    if (at + 8 > s.size()) bad("an element's tag is cut off");
    if (u32(s, at) == kMiInt8) next(s, &at);
  }

  std::string file_;
  bool swap_;
  std::string variable_;  // how messages name the variable being checked
};

}  // namespace

void check_level5_structure(const std::string& file, std::string_view bytes) {
  if (bytes.size() < 128) return;  // not level 5: the caller checked
  const bool swap = bytes.substr(126, 2) == "MI";
  Checker(file, swap).check_body(bytes.substr(128));
}

}  // namespace spdfit::io::detail
