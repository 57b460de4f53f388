// Spelling options per front end, from every command's option table.
#include "spdfit/spelling.hpp"

#include <cctype>
#include <map>
#include <utility>

#include "interface/tables.hpp"

namespace spdfit {

namespace {

// The command line's and Python's spelling of each library name, from every table (the first
// table that has a name gives its spellings: the tables agree where they share one).
using Spellings = std::map<std::string, std::pair<std::string, std::string>, std::less<>>;

template <typename Request>
void add_spellings(Spellings& out, const std::vector<OptionSpec<Request>>& table) {
  for (const OptionSpec<Request>& spec : table) {
    if (spec.positional) continue;
    // "-o,--output", "--threshold,--rank-tol": messages name the first long form.
    std::string_view cli = spec.cli.empty() ? spec.name : spec.cli;
    if (cli.find(',') != std::string_view::npos) {
      const std::size_t start = cli.find("--");
      cli = cli.substr(start, cli.find(',', start) - start);
    }
    out.emplace(std::string(spec.name), std::make_pair(std::string(cli),
                                                       std::string(spec.python.empty() ? spec.name : spec.python)));
  }
}

const Spellings& spellings() {
  static const Spellings map = [] {
    Spellings out;
    detail::for_each_option_table([&out](const auto& table) { add_spellings(out, table); });
    return out;
  }();
  return map;
}

}  // namespace

std::string camel_case(std::string_view name) {
  std::string out;
  bool upper = true;
  for (char c : name) {
    if (c == '_') {
      upper = true;
      continue;
    }
    out += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  return out;
}

std::string spell_option(std::string_view name, Frontend frontend) {
  if (frontend == Frontend::Library || (frontend == Frontend::Python && name.empty())) return std::string(name);
  if (frontend == Frontend::Matlab) return camel_case(name);
  const Spellings& map = spellings();
  if (const auto found = map.find(name); found != map.end()) {
    return frontend == Frontend::Cli ? found->second.first : found->second.second;
  }
  // A name no table has follows the convention the tables keep: "--max-iter" on the command
  // line, the name in Python.
  if (frontend == Frontend::Python) return std::string(name);
  std::string cli = "--";
  for (char c : name) cli += c == '_' ? '-' : c;
  return cli;
}

std::string spell_options(std::string_view message, Frontend frontend) {
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
    out += spell_option(message.substr(open + 1, close - open - 1), frontend);
    i = close + 1;
  }
  return out;
}

}  // namespace spdfit
