// Internal: an option-table entry with its common fields, for the request files' tables.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <variant>

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

/// An integer entry stored in `member` (a count, a seed, a number of threads), with its default
/// shown; a front end's "no value" is refused rather than taken for the default (nullable false).
template <typename Request, typename T>
OptionSpec<Request> integer_entry(std::string_view name, std::string_view cli, std::string_view python,
                                  std::string_view help, std::string_view default_text, NumberRange range,
                                  T Request::*member) {
  OptionSpec<Request> spec = option_entry<Request>(name, cli, python, OptionType::Integer, "N", help, default_text);
  spec.range = range;
  spec.nullable = false;
  spec.set = [member](Request& r, const OptionValue& v) { r.*member = static_cast<T>(std::get<std::int64_t>(v)); };
  spec.get = [member](const Request& r) -> std::optional<OptionValue> {
    return static_cast<std::int64_t>(r.*member);
  };
  return spec;
}

}  // namespace spdfit::detail
