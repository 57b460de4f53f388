// Writes the type stubs of the spdfit package from their sources in python/spdfit/: a function
// whose keywords come from the library's option tables is written there with `**options: Any`
// and a trailing `# options: ENTRY [ENTRY...]` (entries.hpp), all on one line, and gets its keyword-only
// parameters here, each annotated from its option's type, so that a new option in a table is in
// the stubs too.
//
// A line `# warning classes: FORMAT` becomes one line per warning code of the library
// (spdfit/outcome.hpp), FORMAT with {} replaced by the code's Python class.
//
// Usage: spdfit_stubgen SOURCE.pyi OUTPUT.pyi
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "spdfit/outcome.hpp"
#include "src/entries.hpp"

namespace {

// The line with its `**options: Any` replaced by `entry`'s keyword-only parameters.
std::string expanded(const std::string& line, const std::string& entry_name) {
  const std::string marker = "**options: Any";
  const std::size_t at = line.find(marker);
  if (at == std::string::npos) throw std::runtime_error("no '" + marker + "' in: " + line);
  std::string parameters;
  const bool star = line.substr(0, at).find("*,") != std::string::npos;
  if (!star) parameters = "*, ";
  bool first = true;
  const std::string before = line.substr(0, at);
  // Several entries, space-separated, give their keywords in turn.
  std::vector<spdfit::python::Keyword> all;
  std::istringstream names(entry_name);
  for (std::string name; names >> name;) {
    for (const spdfit::python::Keyword& k : spdfit::python::keywords(name)) all.push_back(k);
  }
  for (const spdfit::python::Keyword& k : all) {
    // A keyword the function spells out itself (nearest_spd's positional min_eig) is not repeated.
    const std::string spelled = std::string(k.python) + ":";
    if (before.find(" " + spelled) != std::string::npos || before.find("(" + spelled) != std::string::npos) continue;
    parameters += (first ? "" : ", ") + std::string(k.python) + ": " + spdfit::python::annotation(k) + " = ...";
    first = false;
  }
  std::string out = line.substr(0, at) + parameters + line.substr(at + marker.size());
  return out.substr(0, out.find("  # options:"));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: spdfit_stubgen SOURCE.pyi OUTPUT.pyi\n";
    return 2;
  }
  std::ifstream in(argv[1]);
  if (!in) {
    std::cerr << "spdfit_stubgen: cannot read " << argv[1] << "\n";
    return 1;
  }
  std::ostringstream out;
  std::string line;
  const std::string tag = "  # options: ";
  try {
    while (std::getline(in, line)) {
      const std::string classes = "# warning classes: ";
      if (line.rfind(classes, 0) == 0) {
        const std::string format = line.substr(classes.size());
        for (const spdfit::CodeInfo& info : spdfit::outcome_codes()) {
          if (info.tier != spdfit::Tier::Warning || info.code == spdfit::Code::Warning) continue;
          std::string text = format;
          const std::string name = spdfit::python_class(info.code);
          for (std::size_t p = text.find("{}"); p != std::string::npos; p = text.find("{}", p + name.size())) {
            text.replace(p, 2, name);
          }
          out << text << '\n';
        }
        continue;
      }
      const std::size_t at = line.find(tag);
      out << (at == std::string::npos ? line : expanded(line, line.substr(at + tag.size()))) << '\n';
    }
  } catch (const std::exception& e) {
    std::cerr << "spdfit_stubgen: " << argv[1] << ": " << e.what() << "\n";
    return 1;
  }
  std::ofstream file(argv[2]);
  file << out.str();
  file.close();
  if (!file) {
    std::cerr << "spdfit_stubgen: cannot write " << argv[2] << "\n";
    return 1;
  }
  return 0;
}
