// The presentation options' table.
#include "spdfit/output_request.hpp"

#include "spdfit/io.hpp"

namespace spdfit {

namespace {

using Spec = OptionSpec<OutputRequest>;

// A flag stored in `member` (the command line's only: no Python spelling).
template <typename Request>
OptionSpec<Request> flag(std::string_view name, std::string_view cli, std::string_view help,
                         std::vector<std::string_view> excludes, bool Request::*member) {
  OptionSpec<Request> spec;
  spec.name = name;
  spec.cli = cli;
  spec.type = OptionType::Flag;
  spec.help = help;
  spec.nullable = false;
  spec.excludes = std::move(excludes);
  spec.set = [member](Request& r, const OptionValue& v) { r.*member = std::get<bool>(v); };
  spec.get = [member](const Request& r) -> std::optional<OptionValue> { return r.*member; };
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

std::vector<OptionSpec<GlobalRequest>> make_global_table() {
  return {
      flag("quiet", "-q,--quiet", "Do not print warnings on stderr (before or after the command)", {"verbose"},
           &GlobalRequest::quiet),
      flag("verbose", "-v,--verbose",
           "Say on stderr which BLAS kernels run (OpenBLAS's core, and whether spdfit chose it)", {"quiet"},
           &GlobalRequest::verbose),
      flag("index_col", "--index-col",
           "The first column of each data file holds row labels (an index, as pandas' to_csv and R's write.csv "
           "write one): drop it. Without this, a header whose first cell is empty says so, and a first column "
           "0, 1, 2, ... is refused",
           {"no_index_col"}, &GlobalRequest::index_col),
      flag("no_index_col", "--no-index-col", "The first column of each data file is data, whatever its header or values",
           {"index_col"}, &GlobalRequest::no_index_col),
      flag("no_header", "--no-header",
           "The first line of each text data file is data. Without this, a first line with no number in it is a "
           "header row of column names, and so is 0,1,...,k-1 (pandas' header of a frame without column names), "
           "with a warning",
           {"header_row"}, &GlobalRequest::no_header),
      flag("header_row", "--header-row",
           "The first line of each text data file is a header row of column names, whatever it holds (R's "
           "write.csv quotes numbered names: \"1\",\"2\",...)",
           {"no_header"}, &GlobalRequest::header_row),
  };
}

}  // namespace

const std::vector<OptionSpec<GlobalRequest>>& global_option_table() {
  static const std::vector<OptionSpec<GlobalRequest>> table = make_global_table();
  return table;
}

void apply_global_options(const GlobalRequest& request, io::ReadOptions& read) {
  if (request.index_col) read.index_column = io::IndexColumn::Drop;
  if (request.no_index_col) read.index_column = io::IndexColumn::Keep;
  if (request.no_header) read.header_row = io::HeaderRow::Absent;
  if (request.header_row) read.header_row = io::HeaderRow::Present;
}

const std::vector<OptionSpec<OutputRequest>>& output_option_table() {
  static const std::vector<OptionSpec<OutputRequest>> table = make_table();
  return table;
}

}  // namespace spdfit
