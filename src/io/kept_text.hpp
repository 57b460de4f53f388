// Internal: standard input's text kept while it is streamed, so that it can be read a second time
// (the streaming bootstrap's in-memory fallback): standard input cannot be read again.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "spdfit/row_reader.hpp"

namespace spdfit::io::detail {

/// What a reader of standard input read, all of it while it fits in `at_most` bytes; once it does
/// not, `text` is released and `overflowed` set.
struct KeptText {
  std::size_t at_most = 0;
  std::string text;
  bool overflowed = false;

  /// Appends the bytes read next, or gives up keeping them when they pass at_most.
  void keep(const char* data, std::size_t size) {
    if (overflowed) return;
    if (size > at_most - text.size()) {
      overflowed = true;
      std::string().swap(text);
      return;
    }
    text.append(data, size);
  }
};

/// A reader of standard input ("-", as RowReader reads it) that keeps its text in `keep`.
RowReader standard_input_reader(const ReadOptions& options, std::shared_ptr<KeptText> keep);

}  // namespace spdfit::io::detail
