// The command line's options of a request, registered from the library's option table
// (spdfit/options.hpp): name, help, default and range come from there, so that a new option in
// the table is a new command-line option with nothing written here.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "cli.hpp"
#include "spdfit/option_spelling.hpp"
#include "spdfit/fit_request.hpp"
#include "spdfit/options.hpp"
#include "validators.hpp"

namespace spdfit::cli {

/// The names of `table`'s options but those in `keep`: the `leave_out` of a command that takes
/// only some of a table's options.
template <typename Request>
std::vector<std::string_view> all_but(const std::vector<OptionSpec<Request>>& table,
                                      const std::vector<std::string_view>& keep) {
  std::vector<std::string_view> out;
  for (const OptionSpec<Request>& spec : table) {
    bool kept = false;
    for (std::string_view k : keep) kept = kept || k == spec.name;
    if (!kept) out.push_back(spec.name);
  }
  return out;
}

/// A Choice option's values as its usage text shows them: "common|each|geometry".
std::string choices_text(const std::vector<std::string_view>& choices);

/// The validator of a number option with `range`: "'TEXT' is not a <what the range says>".
CLI::Validator range_validator(const NumberRange& range, bool integer);

/// An option's help as the command line shows it: the table's help with options spelled for the
/// command line, and its default.
std::string cli_help(std::string_view help, std::string_view default_text);

/// A library message about options (OptionError) as the command line says it: a UsageError with
/// the options spelled as here.
[[noreturn]] void throw_usage(const std::exception& error);

/// Runs `fn`; an error it throws is rethrown with its options spelled through `table` first (a
/// command whose option shares a library name with another table's: `criterion`) and its code
/// kept: a usage code as a UsageError (exit 2), any other as a DataFailure (exit 1).
template <typename Request, typename Fn>
auto run_spelled(const std::vector<OptionSpec<Request>>& table, Fn&& fn) -> decltype(fn()) {
  try {
    return fn();
  } catch (const UsageError&) {
    throw;
  } catch (const DataFailure&) {
    throw;
  } catch (const std::exception& e) {
    const Code code = code_of(e);
    const std::string message = spell_options_with(e.what(), Frontend::Cli, table);
    if (tier(code) == Tier::Usage) throw UsageError(message, code);
    throw DataFailure(message, code);
  }
}

/// A library warning printed with its option names spelled from the command's own table first
/// (their names may be another table's too).
template <typename Request>
void warn_spelled(const GlobalOptions& global, const Warning& w, const std::vector<OptionSpec<Request>>& table) {
  warn(global, Warning(w.code, spell_options_with(w.text, Frontend::Cli, table), w.subject));
}

/// The options of `table` that the command line offers, added to a subcommand; after parsing,
/// which were given and their values.
template <typename Request>
class TableOptions {
 public:
  /// Adds every option of `table` with a command-line spelling to `sub`, but those named in
  /// `leave_out` (library names), in the table's order. The table must outlive this object.
  TableOptions(CLI::App& sub, const std::vector<OptionSpec<Request>>& table,
               const std::vector<std::string_view>& leave_out = {})
      : table_(&table) {
    for (const OptionSpec<Request>& spec : table) {
      if (spec.cli.empty() || contains(leave_out, spec.name)) continue;
      auto entry = std::make_unique<Entry>();
      entry->spec = &spec;
      const std::string help = cli_help(spec.help, spec.default_text);
      if (spec.type == OptionType::Flag || spec.type == OptionType::Boolean) {
        entry->option = sub.add_flag(std::string(spec.cli), entry->flag, help);
      } else {
        entry->option = sub.add_option(std::string(spec.cli), entry->text, help);
        if (spec.required) entry->option->required();
        if (!spec.value_name.empty()) {
          entry->option->type_name(std::string(spec.value_name));
        } else if (spec.type == OptionType::Choice) {
          entry->option->type_name(choices_text(spec.choices));
        }
        if (spec.type == OptionType::Integer || spec.type == OptionType::Real) {
          entry->option->check(range_validator(spec.range, spec.type == OptionType::Integer));
        }
      }
      entries_.push_back(std::move(entry));
    }
    // The table's exclusions, as CLI11's own (its message: "--a excludes --b").
    for (const auto& entry : entries_) {
      for (std::string_view other : entry->spec->excludes) {
        if (CLI::Option* o = option(other)) entry->option->excludes(o);
      }
    }
  }

  /// The CLI11 option of the library name `name`, or nullptr when not offered.
  CLI::Option* option(std::string_view name) const {
    for (const auto& entry : entries_) {
      if (entry->spec->name == name) return entry->option;
    }
    return nullptr;
  }

  /// The library names of the options given on the command line.
  std::vector<std::string_view> given() const {
    std::vector<std::string_view> names;
    for (const auto& entry : entries_) {
      if (entry->option->count() > 0) names.push_back(entry->spec->name);
    }
    return names;
  }

  /// Whether the option `name` was given.
  bool was_given(std::string_view name) const { return contains(given(), name); }

  /// Stores each given option's value in `request` (set_option). A UsageError for a value the
  /// library refuses.
  void apply(Request& request) const {
    for (const auto& entry : entries_) {
      if (entry->option->count() == 0) continue;
      try {
        set_option(request, *entry->spec, value_of(*entry));
      } catch (const OptionError& e) {
        // Spelled with this table first: its names may be another table's too (`criterion`).
        throw UsageError(spell_options_with(e.what(), Frontend::Cli, *table_), e.code());
      }
    }
  }

 private:
  struct Entry {
    const OptionSpec<Request>* spec = nullptr;
    CLI::Option* option = nullptr;
    std::string text;
    bool flag = false;
  };

  static bool contains(const std::vector<std::string_view>& names, std::string_view name) {
    for (std::string_view n : names) {
      if (n == name) return true;
    }
    return false;
  }

  static OptionValue value_of(const Entry& entry);

  const std::vector<OptionSpec<Request>>* table_ = nullptr;
  std::vector<std::unique_ptr<Entry>> entries_;
};

/// The value a command-line text stands for, by the option's type: the text passed the range
/// validator already where there is one. A UsageError for text that is not a value of the type.
OptionValue parse_option_text(OptionType type, std::string_view spelling, const std::string& text);

template <typename Request>
OptionValue TableOptions<Request>::value_of(const Entry& entry) {
  const OptionSpec<Request>& spec = *entry.spec;
  if (spec.type == OptionType::Flag || spec.type == OptionType::Boolean) return entry.flag;
  if (spec.type == OptionType::Vector) return parse_option_text(OptionType::RealList, spec.cli, entry.text);
  return parse_option_text(spec.type, spec.cli, entry.text);
}

}  // namespace spdfit::cli
