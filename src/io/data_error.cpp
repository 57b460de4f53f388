#include <string>
#include <utility>

#include "spdfit/io.hpp"

namespace spdfit::io {

namespace {

// The "file:line:column: problem" form that compilers use, so that editors and terminals can
// jump to the spot. Parts that are unknown (0) are left out rather than printed as 0.
std::string format_message(const std::string& source, std::size_t line, std::size_t column,
                           const std::string& problem) {
  std::string message = source;
  if (line > 0) {
    message += ':' + std::to_string(line);
    if (column > 0) message += ':' + std::to_string(column);
  }
  message += ": ";
  message += problem;
  return message;
}

}  // namespace

DataError::DataError(std::string source, std::size_t line, std::size_t column, const std::string& problem,
                     Code code)
    : std::runtime_error(format_message(source, line, column, problem)),
      Coded(code, source),
      source_(std::move(source)),
      line_(line),
      column_(line > 0 ? column : 0),
      problem_(problem) {}

}  // namespace spdfit::io
