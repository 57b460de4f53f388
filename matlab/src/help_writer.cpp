// Writes an M-file of the spdfit package from its template: the line `%{options FUNCTION}` becomes
// the list of FUNCTION's name-value options from the library's option tables (mex_options.hpp),
// so that an option added to a table is in `help spdfit.fit` with nothing written here; the line
// `%{warnings}` becomes the list of warning identifiers from the library's outcome codes.
//
// Usage: spdfit_matlab_help TEMPLATE.m.in OUTPUT.m
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "mex_options.hpp"
#include "spdfit/outcome.hpp"

namespace {

constexpr std::size_t kWidth = 78;

// `text` as comment lines indented by `indent`, wrapped at kWidth columns.
std::string wrapped(const std::string& text, const std::string& indent) {
  std::istringstream words(text);
  std::string out, line = indent, word;
  while (words >> word) {
    if (line.size() > indent.size() && line.size() + 1 + word.size() > kWidth) {
      out += line + "\n";
      line = indent;
    }
    line += (line.size() > indent.size() ? " " : "") + word;
  }
  return out + line + "\n";
}

std::string options_text(const std::string& function) {
  std::string out = "%   Options, as name-value pairs (names are not case-sensitive; [] is the default):\n";
  for (const spdfit::matlab::MatlabOption& o : spdfit::matlab::option_help(function)) {
    out += "%     '" + o.name + "' (" + o.type + (o.default_text.empty() ? "" : ", default " + o.default_text) + ")\n";
    out += wrapped(o.help, "%         ");
  }
  return out;
}

// The warning identifiers of the library's codes (spdfit/outcome.hpp), with what each means.
std::string warnings_text() {
  std::string out;
  for (const spdfit::CodeInfo& info : spdfit::outcome_codes()) {
    if (info.tier != spdfit::Tier::Warning) continue;
    out += wrapped(spdfit::matlab_identifier(info.code) + ": " + std::string(info.meaning), "%     ");
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: spdfit_matlab_help TEMPLATE.m.in OUTPUT.m\n";
    return 2;
  }
  std::ifstream in(argv[1]);
  if (!in) {
    std::cerr << "spdfit_matlab_help: cannot read " << argv[1] << "\n";
    return 1;
  }
  std::ostringstream out;
  const std::string marker = "%{options ";
  std::string line;
  while (std::getline(in, line)) {
    if (line == "%{warnings}") {
      out << warnings_text();
    } else if (line.rfind(marker, 0) == 0 && line.back() == '}') {
      out << options_text(line.substr(marker.size(), line.size() - marker.size() - 1));
    } else {
      out << line << '\n';
    }
  }
  std::ofstream file(argv[2]);
  file << out.str();
  if (!file) {
    std::cerr << "spdfit_matlab_help: cannot write " << argv[2] << "\n";
    return 1;
  }
  return 0;
}
