// The presentation options' table.
#include "spdfit/output_request.hpp"

namespace spdfit {

namespace {

using Spec = OptionSpec<OutputRequest>;

Spec flag(std::string_view name, std::string_view cli, std::string_view help,
          std::vector<std::string_view> excludes, bool OutputRequest::*member) {
  Spec spec;
  spec.name = name;
  spec.cli = cli;
  spec.type = OptionType::Flag;
  spec.help = help;
  spec.nullable = false;
  spec.excludes = std::move(excludes);
  spec.set = [member](OutputRequest& r, const OptionValue& v) { r.*member = std::get<bool>(v); };
  spec.get = [member](const OutputRequest& r) -> std::optional<OptionValue> { return r.*member; };
  return spec;
}

std::vector<Spec> make_table() {
  std::vector<Spec> table;
  table.push_back(flag("json", "--json", "Print the result as JSON", {"report", "header"}, &OutputRequest::json));
  table.push_back(flag("report", "--report", "Print the result as a report for people", {"json", "header"},
                       &OutputRequest::report));
  table.push_back(flag("header", "--header", "Print the result as CSV with a header row and row labels",
                       {"json", "report"}, &OutputRequest::header));
  Spec output;
  output.name = "output";
  output.cli = "-o,--output";
  output.type = OptionType::File;
  output.value_name = "FILE";
  output.help = "Write to FILE instead of stdout";
  output.set = [](OutputRequest& r, const OptionValue& v) { r.output = std::get<std::string>(v); };
  table.push_back(output);
  return table;
}

}  // namespace

const std::vector<OptionSpec<OutputRequest>>& output_option_table() {
  static const std::vector<OptionSpec<OutputRequest>> table = make_table();
  return table;
}

}  // namespace spdfit
