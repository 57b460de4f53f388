// Internal: an option-table entry with its common fields, for the request files' tables.
#pragma once

#include <string_view>

#include "spdfit/options.hpp"

namespace spdfit::detail {

/// An entry named `name` (the library's), spelled `cli` and `python` (empty: not offered there),
/// of `type`; a flag has no "no value" (nullable false). The caller adds its range, choices, rules
/// and set/get.
template <typename Request>
OptionSpec<Request> option_entry(std::string_view name, std::string_view cli, std::string_view python, OptionType type,
                                 std::string_view value_name, std::string_view help,
                                 std::string_view default_text = {}) {
  OptionSpec<Request> spec;
  spec.name = name;
  spec.cli = cli;
  spec.python = python;
  spec.type = type;
  spec.value_name = value_name;
  spec.help = help;
  spec.default_text = default_text;
  if (type == OptionType::Flag) spec.nullable = false;
  return spec;
}

}  // namespace spdfit::detail
