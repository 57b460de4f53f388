// Spelling a command's messages with its own option table first: a command whose options share a
// library name with another table's (`criterion`: the hexapod's physical fit and payload identify)
// spells its own messages right.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "spdfit/options.hpp"

namespace spdfit {

/// spell_options with the names of `table` spelled from it first: a command whose options share a
/// library name with another table's (`criterion`) spells its own messages with its own table.
template <typename Request>
std::string spell_options_with(std::string_view message, Frontend frontend,
                               const std::vector<OptionSpec<Request>>& table) {
  std::string out;
  std::size_t i = 0;
  while (i < message.size()) {
    const std::size_t open = message.find('`', i);
    const std::size_t close = open == std::string_view::npos ? open : message.find('`', open + 1);
    if (close == std::string_view::npos) {
      out += message.substr(i);
      break;
    }
    out += message.substr(i, open - i);
    const std::string_view name = message.substr(open + 1, close - open - 1);
    const OptionSpec<Request>* spec = find_option(table, name);
    std::string_view own = spec == nullptr             ? std::string_view()
                                 : frontend == Frontend::Cli ? spec->cli
                                 : frontend == Frontend::Python ? spec->python
                                                                : std::string_view();
    // "-m,--method", "--threshold,--rank-tol": messages name the first long form.
    if (frontend == Frontend::Cli && own.find(',') != std::string_view::npos) {
      const std::size_t start = own.find("--");
      own = start == std::string_view::npos ? std::string_view() : own.substr(start, own.find(',', start) - start);
    }
    out += !own.empty() && !(spec != nullptr && spec->positional) ? std::string(own) : spell_option(name, frontend);
    i = close + 1;
  }
  return out;
}

}  // namespace spdfit
