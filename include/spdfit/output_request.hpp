// What a command prints and where: the command line's presentation options (--json, --report,
// --header, -o), declared in a table as every other option is, so that each command registers
// them from it. Python and MATLAB return objects and take none of them.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "spdfit/options.hpp"

namespace spdfit {

namespace io {
struct ReadOptions;
}

/// The options every command takes (the command line's global options, given before or after the
/// command): whether warnings are printed and what is said, and how every data file's first column
/// and first line are read. Python and MATLAB have their own forms (the warnings module;
/// read_matrix's index_col and header).
struct GlobalRequest {
  bool quiet = false;         ///< no warnings on standard error
  bool verbose = false;       ///< say which BLAS kernels run
  bool index_col = false;     ///< every data file's first column holds row labels: dropped
  bool no_index_col = false;  ///< every data file's first column is data
  bool no_header = false;     ///< every text data file's first line is data
  bool header_row = false;    ///< every text data file's first line is a header row, whatever it holds
};

/// The global options: quiet and verbose (each excludes the other), index_col and no_index_col
/// (likewise), no_header and header_row (likewise); the command line's only.
const std::vector<OptionSpec<GlobalRequest>>& global_option_table();

/// The reading rules the global options set (index_column, header_row), in `read`.
void apply_global_options(const GlobalRequest& request, io::ReadOptions& read);

/// How a command's result is printed: as JSON, a report for people, a labelled CSV table, or its
/// plain form (X as CSV, a report); to a file or standard output.
struct OutputRequest {
  bool json = false;
  bool report = false;
  bool header = false;
  std::string output;  ///< a file instead of standard output; empty: standard output
};

/// The presentation options: json, report, header, output (the command line's only: no Python
/// spelling). A command takes those it offers (lifted_options with their names); `json`,
/// `report` and `header` exclude each other.
const std::vector<OptionSpec<OutputRequest>>& output_option_table();

/// The presentation options `names` of a command's request, whose OutputRequest is at `member`,
/// with the help texts `help` gives in the same order (empty: the table's).
template <typename Request>
std::vector<OptionSpec<Request>> output_options(OutputRequest Request::*member,
                                                const std::vector<std::string_view>& names,
                                                const std::vector<std::string_view>& help = {}) {
  std::vector<OptionSpec<Request>> out;
  for (std::size_t k = 0; k < names.size(); ++k) {
    std::vector<OptionSpec<Request>> one = lifted_options(output_option_table(), member, {names[k]});
    for (OptionSpec<Request>& spec : one) {
      if (k < help.size() && !help[k].empty()) spec.help = help[k];
      // Only the presentation options this command offers are excluded from each other.
      std::vector<std::string_view> excludes;
      for (std::string_view e : spec.excludes) {
        for (std::string_view n : names) {
          if (n == e) excludes.push_back(e);
        }
      }
      spec.excludes = excludes;
      out.push_back(std::move(spec));
    }
  }
  return out;
}

}  // namespace spdfit
