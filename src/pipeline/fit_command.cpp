// `spdfit fit` as a request: its table (the fit's options with the data's files, the arrays named in
// them and the presentation) and the paths of A and B it names.
#include <sys/stat.h>

#include <cstdint>
#include <string>
#include <utility>

#include "spdfit/fit_request.hpp"
#include "spdfit/io.hpp"
#include "spdfit/named_arrays.hpp"

namespace spdfit {

namespace {

using Spec = OptionSpec<FitCommand>;

Spec data_file(std::string_view name, std::string_view cli, std::string_view help, bool required,
               MatrixInput FitCommand::*member) {
  Spec spec;
  spec.name = name;
  spec.cli = cli;
  spec.type = OptionType::File;
  spec.help = help;
  spec.positional = true;
  spec.required = required;
  spec.set = [member](FitCommand& c, const OptionValue& v) { (c.*member).path = std::get<std::string>(v); };
  return spec;
}

Spec variable(std::string_view name, std::string_view cli, std::string_view help, std::string FitCommand::*member) {
  Spec spec;
  spec.name = name;
  spec.cli = cli;
  spec.type = OptionType::Text;
  spec.value_name = "NAME";
  spec.help = help;
  spec.set = [member](FitCommand& c, const OptionValue& v) { c.*member = std::get<std::string>(v); };
  return spec;
}

std::vector<Spec> make_table() {
  std::vector<Spec> table;
  Spec method;
  method.name = "method";
  method.cli = "-m,--method";
  method.type = OptionType::Choice;
  method.help = "ls (least squares), procrustes (symmetric least squares), tls (total least squares), tls-sym, "
                "tls-psd, spde (area criterion, always SPD), spd-tls (total least squares over the SPD matrices), "
                "psd-ls (least squares over X >= min-eig I, with a certificate), auto (spde, spd-tls or psd-ls, "
                "chosen from the data)";
  for (Method m : kSelectableMethods) method.choices.push_back(to_string(m));
  method.required = true;
  method.set = [](FitCommand& c, const OptionValue& v) { c.fit.method = *parse_method(std::get<std::string>(v)); };
  table.push_back(method);
  for (Spec& spec : output_options(
           &FitCommand::output, {"json", "report", "header", "output"},
           {"Print the estimate, diagnostics, warnings and the bootstrap's numbers as JSON",
            "Print X with its bootstrap standard errors (with `bootstrap`), its eigenvalues and the noise estimate "
            "as a table for people",
            "Print X as CSV with a header row and row labels: rows named by A's columns, columns by B's (numbers "
            "where a file has no header row); `json` has them as row_names and column_names",
            "Write to FILE instead of stdout (X.npy: a NumPy file; X.mat: a MATLAB file with the variable X)"})) {
    table.push_back(std::move(spec));
  }
  for (Spec& spec : lifted_options(fit_option_table(), &FitCommand::fit, {}, true)) table.push_back(std::move(spec));
  table.push_back(variable("var_a", "--var-a", "The variable of A's .mat or .npz file (as A.mat:NAME)", &FitCommand::var_a));
  table.push_back(variable("var_b", "--var-b", "The variable of B's .mat or .npz file (as B.mat:NAME)", &FitCommand::var_b));
  table.push_back(data_file("a", "A",
                            "File of A (m x n): delimited text, .npy, .mat or .npz (FILE:NAME names an array), - for "
                            "standard input",
                            true, &FitCommand::a));
  table.push_back(data_file("b", "B",
                            "File of B (m x n; m x d for ls and tls, X n x d): as A. Without it, `a_cols` and "
                            "`b_cols` choose A's and B's columns in A's file",
                            false, &FitCommand::b));
  return table;
}

// The size of a file, 0 when it is not a regular file (standard input, a FILE:NAME array).
std::uint64_t file_bytes(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) ? static_cast<std::uint64_t>(info.st_size) : 0;
}

// "A.mat:accel" for `var_a` accel. A file named with its array already, standard input, or a file
// without named arrays (text, .npy) takes no variable (a usage error quoting the option as typed);
// a file that does not exist is left to the reader, which says so.
std::string with_variable(const std::string& path, const std::string& variable, const char* option) {
  if (variable.empty()) return path;
  const std::string typed = "`" + std::string(option) + "` " + variable;
  const auto fail = [&](const std::string& message) -> std::string {
    throw OptionError(message, Code::Argument, option);
  };
  if (path == "-") return fail(typed + " names an array in a file, but the file is standard input (-)");
  if (file_bytes(path) > 0 && !io::holds_named_arrays(path)) {
    struct stat info {};
    const bool names_a_file = ::stat(variable.c_str(), &info) == 0;
    return fail(typed + ": `" + option + "` names a variable inside a .mat or .npz file, but " + path +
                " is neither (it holds one matrix, no named arrays): drop " + typed +
                (names_a_file ? "; to read " + variable + " as the data file, give it in " + path + "'s place" : ""));
  }
  if (!io::split_spec(path).variable.empty()) {
    return fail(typed + " names the array, but " + path + " names one already: give one of them");
  }
  return path + ":" + variable;
}

}  // namespace

const std::vector<OptionSpec<FitCommand>>& fit_command_table() {
  static const std::vector<OptionSpec<FitCommand>> table = make_table();
  return table;
}

std::pair<std::string, std::string> fit_command_paths(const FitCommand& command) {
  const std::string& a = command.a.path;
  const std::string& b = command.b.path;
  if (a == "-" && b == "-") throw OptionError("A and B cannot both be standard input (-)", Code::Argument, "b");
  if (b.empty() && command.fit.a_cols.empty() && command.fit.b_cols.empty()) {
    throw OptionError("B's file is missing: give the files of A and B, or one file with `a_cols` and `b_cols` "
                      "choosing their columns",
                      Code::Argument, "b");
  }
  const bool one_file = b.empty();
  if (one_file && !command.var_a.empty() && !command.var_b.empty() && command.var_a != command.var_b) {
    throw OptionError("`var_a` " + command.var_a + " and `var_b` " + command.var_b +
                          " name two arrays, but `a_cols` and `b_cols` take A and B from one: give one of them",
                      Code::OptionConflict, "var_b");
  }
  const bool a_by_b = one_file && command.var_a.empty();
  return {with_variable(a, a_by_b ? command.var_b : command.var_a, a_by_b ? "var_b" : "var_a"),
          one_file ? std::string() : with_variable(b, command.var_b, "var_b")};
}

}  // namespace spdfit
