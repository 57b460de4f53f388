#include "spdfit/format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace spdfit {

namespace {
// "-0", "-0.000": a value that rounds to zero is shown without a sign it does not show.
std::string without_negative_zero(const char* text) {
  if (text[0] != '-') return text;
  for (const char* c = text + 1; *c != '\0' && *c != 'e'; ++c) {
    if (*c != '0' && *c != '.') return text;
  }
  return text + 1;
}
}  // namespace

std::string format_number(double value, Precision precision) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*g", static_cast<int>(precision), value);
  return without_negative_zero(buffer);
}

std::string format_fixed(double value, int decimals) {
  if (std::isnan(value)) return "-";
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, std::abs(value) < 1e5 ? "%.*f" : "%.*e", decimals, value);
  return without_negative_zero(buffer);
}

int interval_decimals(double standard_error) {
  if (!(standard_error > 0.0) || !std::isfinite(standard_error)) return 4;
  return std::clamp(2 - static_cast<int>(std::floor(std::log10(standard_error))), 0, 12);
}

std::string format_numbers(const Eigen::VectorXd& values, Precision precision) {
  std::string out;
  for (Eigen::Index i = 0; i < values.size(); ++i) out += (i ? ", " : "") + format_number(values(i), precision);
  return out;
}

std::string format_percent(double fraction, Precision precision) {
  return format_number(100.0 * fraction, precision) + "%";
}

std::string format_side_by_side(const std::vector<std::string>& titles, const std::vector<Eigen::MatrixXd>& matrices,
                                int digits, std::size_t width) {
  // Format every entry first so that each block's column width fits its widest entry. Fixed
  // point with `digits` decimals reads best when the entries are of ordinary size; otherwise
  // scientific notation.
  std::vector<std::vector<std::string>> cells(matrices.size());
  std::vector<std::size_t> cell_width(matrices.size(), 0);
  for (std::size_t k = 0; k < matrices.size(); ++k) {
    const Eigen::MatrixXd& M = matrices[k];
    const double biggest = M.size() ? M.cwiseAbs().maxCoeff() : 0.0;
    const bool fixed = biggest < 1e5 && biggest >= 1e-2;
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
      for (Eigen::Index j = 0; j < M.cols(); ++j) {
        char buffer[40];
        std::snprintf(buffer, sizeof buffer, fixed ? "%.*f" : "%.*e", digits, M(i, j));
        cells[k].emplace_back(buffer);
        cell_width[k] = std::max(cell_width[k], cells[k].back().size());
      }
    }
  }
  auto block_width = [&](std::size_t k) {
    const std::size_t body = static_cast<std::size_t>(matrices[k].cols()) * (cell_width[k] + 1);
    return std::max(body, titles[k].size()) + 3;
  };
  std::ostringstream out;
  std::size_t first = 0;
  while (first < matrices.size()) {
    std::size_t last = first, used = block_width(first);
    while (last + 1 < matrices.size() && used + block_width(last + 1) <= width) used += block_width(++last);
    Eigen::Index rows = 0;
    for (std::size_t k = first; k <= last; ++k) rows = std::max(rows, matrices[k].rows());
    for (std::size_t k = first; k <= last; ++k) {
      out << titles[k] << std::string(block_width(k) - titles[k].size(), ' ');
    }
    out << '\n';
    for (Eigen::Index i = 0; i < rows; ++i) {
      for (std::size_t k = first; k <= last; ++k) {
        std::string line;
        for (Eigen::Index j = 0; j < matrices[k].cols() && i < matrices[k].rows(); ++j) {
          const std::string& cell = cells[k][static_cast<std::size_t>(i * matrices[k].cols() + j)];
          line += std::string(cell_width[k] + 1 - cell.size(), ' ') + cell;
        }
        out << line << std::string(block_width(k) - line.size(), ' ');
      }
      out << '\n';
    }
    out << '\n';
    first = last + 1;
  }
  // Drop the padding at line ends.
  std::string text = out.str(), trimmed;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    line.erase(line.find_last_not_of(' ') + 1);
    trimmed += line + '\n';
    start = end + 1;
  }
  return trimmed;
}

}  // namespace spdfit
