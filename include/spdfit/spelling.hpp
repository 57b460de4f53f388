// How each front end spells an option: the library by its name (`max_iterations`), the command
// line as "--max-iter", Python as max_iter, MATLAB as 'MaxIterations' (the library name in
// CamelCase). The spellings come from the option tables (options.hpp); the core knows none of them.
#pragma once

#include <string>
#include <string_view>

namespace spdfit {

/// The front ends, each of which spells an option its own way.
enum class Frontend { Library, Cli, Python, Matlab };

/// The spelling of option `name` in `frontend`: the command line's and Python's from the tables,
/// MATLAB's the name in CamelCase; a name no table has follows the tables' convention ("--" and
/// the name with hyphens on the command line, the name in Python).
std::string spell_option(std::string_view name, Frontend frontend);

/// `message` with every backticked library name of an option (`max_iterations`) replaced by its
/// spelling in `frontend` ("--max-iter" on the command line). Backticks in the library's messages
/// are for option names only. The library's own spelling is the name without backticks.
std::string spell_options(std::string_view message, Frontend frontend);

/// MATLAB's spelling of a library name: "max_iterations" -> "MaxIterations".
std::string camel_case(std::string_view name);

}  // namespace spdfit
