// Writing matrices: shortest round-trip decimal text, CSV, and .npy.
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "file_error.hpp"
#include "npy_header.hpp"
#include "spdfit/io.hpp"

namespace spdfit::io {

namespace {

std::ofstream open_for_writing(const std::string& path) {
  errno = 0;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) {
    const int error = errno;
    throw DataError(path, 0, 0,
                    "cannot be written (" +
                        (error == ENOENT ? std::string("no such directory")
                         : error != 0    ? detail::describe_errno(error)
                                         : std::string("cannot be opened")) +
                        ")");
  }
  return out;
}

// Closing flushes, so a full disk may show up only here. A failed write earlier leaves the
// stream failed and errno (cleared before opening) set, so both cases are reported here.
void finish_writing(std::ofstream& out, const std::string& path) {
  out.close();
  if (!out) {
    const int error = errno;
    throw DataError(
        path, 0, 0,
        "writing failed (" + (error != 0 ? detail::describe_errno(error) : std::string("disk full?")) + ")");
  }
}

void append_double(std::string* text, double value) {
  char buffer[32];
  if (std::isnan(value)) {
    text->append("nan");
  } else if (std::isinf(value)) {
    text->append(value < 0 ? "-inf" : "inf");
  } else {
    // Without a precision, to_chars writes the shortest text that reads back exactly. A negative
    // zero (an estimate's off-diagonal entry of a decoupled problem) is written as 0, to which it
    // compares equal: "-0" in a result reads as a sign the number does not have.
    if (value == 0.0) value = 0.0;
    const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    text->append(buffer, result.ptr);
  }
}

}  // namespace

namespace detail {
void check_writable(const std::string& path) { open_for_writing(path).close(); }
}  // namespace detail

void write_text(const std::string& path, std::string_view text) {
  std::ofstream out = open_for_writing(path);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  finish_writing(out, path);
}

std::string format_double(double value) {
  std::string text;
  append_double(&text, value);
  return text;
}

void write_csv(std::ostream& out, const Eigen::Ref<const Eigen::MatrixXd>& X) {
  std::string line;
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    line.clear();
    for (Eigen::Index j = 0; j < X.cols(); ++j) {
      if (j > 0) line += ',';
      append_double(&line, X(i, j));
    }
    line += '\n';
    out.write(line.data(), static_cast<std::streamsize>(line.size()));
  }
}

void write_csv(std::ostream& out, const Eigen::Ref<const Eigen::MatrixXd>& X,
               const std::vector<std::string>& row_names, const std::vector<std::string>& column_names) {
  if (row_names.size() != static_cast<std::size_t>(X.rows()) ||
      column_names.size() != static_cast<std::size_t>(X.cols())) {
    throw std::invalid_argument("write_csv: " + std::to_string(row_names.size()) + " row names and " +
                                std::to_string(column_names.size()) + " column names for a " +
                                std::to_string(X.rows()) + "x" + std::to_string(X.cols()) + " matrix");
  }
  // Names are always quoted (as R's write.csv does), so that a name such as "1" stays a name.
  const auto quoted = [](const std::string& name) {
    std::string out = "\"";
    for (const char c : name) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
  };
  std::string line = "\"\"";
  for (const std::string& name : column_names) line += "," + quoted(name);
  line += '\n';
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    line += quoted(row_names[static_cast<std::size_t>(i)]);
    for (Eigen::Index j = 0; j < X.cols(); ++j) {
      line += ',';
      append_double(&line, X(i, j));
    }
    line += '\n';
    out.write(line.data(), static_cast<std::streamsize>(line.size()));
    line.clear();
  }
}

void write_csv(const std::string& path, const Eigen::Ref<const Eigen::MatrixXd>& X) {
  std::ofstream out = open_for_writing(path);
  write_csv(out, X);
  finish_writing(out, path);
}

void write_npy(const std::string& path, const Eigen::Ref<const Eigen::MatrixXd>& X) {
  // Format 1.0 as numpy.save writes it: the dict, padded with spaces and ending in '\n' so
  // that the data starts on a 64-byte boundary (which lets NumPy memory-map it aligned).
  std::string dict =
      "{'descr': '<f8', 'fortran_order': False, 'shape': " +
      detail::format_shape({static_cast<std::uint64_t>(X.rows()), static_cast<std::uint64_t>(X.cols())}) +
      ", }";
  constexpr std::size_t kPreamble = 10;  // magic, version, 2-byte header length
  const std::size_t unpadded = kPreamble + dict.size() + 1;
  dict.append((64 - unpadded % 64) % 64, ' ');
  dict += '\n';

  std::string head(detail::kNpyMagic);
  head += '\x01';
  head += '\x00';
  head += static_cast<char>(dict.size() & 0xFF);
  head += static_cast<char>((dict.size() >> 8) & 0xFF);
  head += dict;

  std::ofstream out = open_for_writing(path);
  out.write(head.data(), static_cast<std::streamsize>(head.size()));
  // C order, little-endian, one row at a time to keep the buffer small.
  std::vector<char> row(static_cast<std::size_t>(X.cols()) * 8);
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    for (Eigen::Index j = 0; j < X.cols(); ++j) {
      const double value = X(i, j);
      std::uint64_t bits;
      std::memcpy(&bits, &value, sizeof(bits));
      for (int k = 0; k < 8; ++k)
        row[static_cast<std::size_t>(j) * 8 + k] = static_cast<char>(bits >> (8 * k));
    }
    out.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
  finish_writing(out, path);
}

}  // namespace spdfit::io
