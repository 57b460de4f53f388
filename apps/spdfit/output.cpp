#include "output.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "cli.hpp"
#include "spdfit/io.hpp"

namespace spdfit::cli {

using nlohmann::json;

json number_json(double value) {
  if (std::isfinite(value)) return value;
  return nullptr;
}

json vector_json(const Eigen::VectorXd& v) {
  json out = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(number_json(v(i)));
  return out;
}

json matrix_json(const Eigen::MatrixXd& M) {
  json rows = json::array();
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index j = 0; j < M.cols(); ++j) row.push_back(number_json(M(i, j)));
    rows.push_back(std::move(row));
  }
  return rows;
}

namespace {

json diagnostics_json(const Diagnostics& d) {
  json out;
  out["rank_a"] = d.rank_a;
  out["rank_b"] = d.rank_b;
  out["cond_a"] = number_json(d.cond_a);
  out["cond_b"] = number_json(d.cond_b);
  out["cond_a_scaled"] = number_json(d.cond_a_scaled);
  out["cond_b_scaled"] = number_json(d.cond_b_scaled);
  out["rank_decided_on"] = "column-scaled";
  out["singular_values_a"] = vector_json(d.singular_values_a);
  out["singular_values_b"] = vector_json(d.singular_values_b);
  out["residual_norm"] = number_json(d.residual_norm);
  out["symmetric"] = d.symmetric;
  out["positive_definite"] = d.positive_definite;
  out["positive_semidefinite"] = d.positive_semidefinite;
  auto optional_number = [&out](const char* key, const std::optional<double>& value) {
    if (value) out[key] = number_json(*value);
  };
  optional_number("min_eigenvalue", d.min_eigenvalue);
  optional_number("max_eigenvalue", d.max_eigenvalue);
  optional_number("area_criterion", d.area_criterion);
  optional_number("area_criterion_minimum", d.area_criterion_minimum);
  if (d.cross_term_positive_definite) out["cross_term_positive_definite"] = *d.cross_term_positive_definite;
  optional_number("tls_sigma_n", d.tls_sigma_n);
  optional_number("tls_sigma_n1", d.tls_sigma_n1);
  optional_number("tls_correction_norm", d.tls_correction_norm);
  optional_number("tls_v22_min_singular_value", d.tls_v22_min_singular_value);
  optional_number("noise_sigma", d.noise_sigma);
  if (d.iterations) out["iterations"] = *d.iterations;
  optional_number("gradient_norm", d.gradient_norm);
  if (d.converged) out["converged"] = *d.converged;
  if (d.certificate) {
    out["certificate"] = {{"primal_min_eig", number_json(d.certificate->primal_min_eig)},
                          {"dual_min_eig", number_json(d.certificate->dual_min_eig)},
                          {"complementarity", number_json(d.certificate->complementarity)},
                          {"duality_gap", number_json(d.certificate->duality_gap)}};
  }
  if (d.chosen_method) out["chosen_method"] = std::string(to_string(*d.chosen_method));
  if (d.reason) out["reason"] = {{"code", d.reason->code}, {"text", d.reason->text}};
  return out;
}

}  // namespace

json spectrum_json(const SpectrumUncertainty& s) {
  json clusters = json::array();
  for (const std::vector<Eigen::Index>& c : s.clusters) clusters.push_back(c);
  return {{"estimate", vector_json(s.estimate)}, {"standard_errors", vector_json(s.standard_errors)},
          {"lower", vector_json(s.lower)},       {"upper", vector_json(s.upper)},
          {"clusters", clusters},                {"failed", s.failed}};
}

json result_json(const FitResult& result) {
  json out;
  out["method"] = std::string(to_string(result.method));
  out["status"] = to_string(result.status);
  out["m"] = result.diagnostics.m;
  out["n"] = result.diagnostics.n;
  out["d"] = result.diagnostics.d;
  out["X"] = matrix_json(result.X);
  if (!result.row_names.empty()) out["row_names"] = result.row_names;
  if (!result.column_names.empty()) out["column_names"] = result.column_names;
  out["diagnostics"] = diagnostics_json(result.diagnostics);
  out["warnings"] = result.warnings;
  if (!result.ok()) out["error"] = result.message;
  if (const auto& b = result.bootstrap) {
    out["standard_errors"] = matrix_json(b->standard_errors);
    out["interval"] = {{"level", b->interval.level},
                       {"lower", matrix_json(b->interval.lower)},
                       {"upper", matrix_json(b->interval.upper)}};
    out["bias"] = matrix_json(b->bias);
    json boot = {{"replicates", b->replicates}, {"failed", b->failed},   {"seed", b->seed},
                 {"method", to_string(b->method)}, {"scheme", b->scheme}};
    if (b->scheme == "poisson_groups") {
      boot["group_rows"] = b->group_rows;
      boot["groups"] = b->groups;
    }
    if (b->eigenvalues) boot["eigenvalues"] = spectrum_json(*b->eigenvalues);
    out["bootstrap"] = std::move(boot);
  }
  return out;
}

namespace {

// Fixed-point decimals that show a standard error to two significant digits.
int decimals_for(double standard_error) {
  if (!(standard_error > 0.0) || !std::isfinite(standard_error)) return 4;
  return std::clamp(1 - static_cast<int>(std::floor(std::log10(standard_error))), 0, 12);
}

}  // namespace

std::string fixed(double value, int digits) {
  if (std::isnan(value)) return "-";
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, std::abs(value) < 1e5 ? "%.*f" : "%.*e", digits, value);
  return buffer;
}

std::string trimmed(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

std::string percent_text(double level) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g%%", 100.0 * level);
  return text;
}

std::string spectrum_text(const SpectrumUncertainty& s, const std::string& indent) {
  std::ostringstream out;
  for (const std::vector<Eigen::Index>& cluster : s.clusters) {
    for (Eigen::Index i : cluster) {
      const int d = decimals_for(s.standard_errors(i));
      out << indent << std::setw(2) << i + 1 << "  " << std::setw(12) << fixed(s.estimate(i), d)
          << " +- " << fixed(s.standard_errors(i), d);
      if (i == cluster.front()) {
        out << "   [" << fixed(s.lower(i), d) << ", " << fixed(s.upper(i), d) << "]";
        if (cluster.size() > 1) {
          out << " for " << cluster.front() + 1 << (cluster.size() == 2 ? " and " : " to ") << cluster.back() + 1
              << " together (closer than their standard errors)";
        }
      }
      out << '\n';
    }
  }
  return out.str();
}

std::string fit_report(const FitResult& result) {
  std::ostringstream out;
  const Diagnostics& d = result.diagnostics;
  out << to_string(result.method) << " estimate of X (" << d.n << " x " << d.d << ") from m = " << d.m << " rows";
  if (d.chosen_method) out << " (chosen by auto: " << d.reason->code << ")";
  out << "\n";
  const auto& b = result.bootstrap;
  if (b) {
    out << "X +- standard error, bootstrap of " << b->replicates << " replicates (" << b->failed
        << " failed), seed " << b->seed << (b->scheme == "poisson_groups" ? ", Poisson counts on groups of rows" : "")
        << "\n";
  } else {
    out << "X (no standard errors: add --bootstrap N, e.g. 1000)\n";
  }
  std::vector<std::string> cells;
  std::size_t width = 0;
  for (Eigen::Index i = 0; i < result.X.rows(); ++i) {
    for (Eigen::Index j = 0; j < result.X.cols(); ++j) {
      std::string cell;
      if (b) {
        const int dec = decimals_for(b->standard_errors(i, j));
        cell = fixed(result.X(i, j), dec) + " +- " + fixed(b->standard_errors(i, j), dec);
      } else {
        char text[40];
        std::snprintf(text, sizeof text, "%.6g", result.X(i, j));
        cell = text;
      }
      width = std::max(width, cell.size());
      cells.push_back(std::move(cell));
    }
  }
  out << "    ";
  for (Eigen::Index j = 0; j < result.X.cols(); ++j) out << std::setw(static_cast<int>(width) + 2) << j + 1;
  out << '\n';
  for (Eigen::Index i = 0; i < result.X.rows(); ++i) {
    out << std::setw(4) << i + 1;
    for (Eigen::Index j = 0; j < result.X.cols(); ++j) {
      out << std::setw(static_cast<int>(width) + 2) << cells[static_cast<std::size_t>(i * result.X.cols() + j)];
    }
    out << '\n';
  }
  if (b && b->eigenvalues) {
    out << "\neigenvalues (ascending) +- standard error   [" << percent_text(b->interval.level) << " interval]\n"
        << spectrum_text(*b->eigenvalues, "  ");
  } else if (d.min_eigenvalue && d.max_eigenvalue) {
    out << "\neigenvalues: " << *d.min_eigenvalue << " to " << *d.max_eigenvalue << '\n';
  }
  if (b) {
    out << "\n" << percent_text(b->interval.level)
        << " percentile intervals of every entry and the bias estimate: --json (interval, bias)\n";
  }
  if (d.noise_sigma) {
    out << "noise estimate: sigma = " << *d.noise_sigma << " in every entry of A (times the noise ratio in B)\n";
  }
  return out.str();
}

std::string matrix_csv(const Eigen::MatrixXd& M) {
  std::ostringstream out;
  io::write_csv(out, M);
  return out.str();
}

void emit(const std::string& text, const std::string& path) {
  if (path.empty()) {
    std::cout << text;
    std::cout.flush();
    return;
  }
  std::ofstream file(path, std::ios::binary);
  file << text;
  file.close();
  if (!file) throw io::DataError(path, 0, 0, "cannot write the output file");
}

namespace {
// ".npy" or ".mat" (any case) when the path ends so: the binary formats X is written in.
std::string binary_extension(const std::string& path) {
  if (path.size() < 4) return "";
  std::string tail = path.substr(path.size() - 4);
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return std::tolower(c); });
  return tail == ".npy" || tail == ".mat" ? tail : "";
}
}  // namespace

void emit_matrix(const Eigen::MatrixXd& X, const std::string& path) {
  const std::string binary = binary_extension(path);
  if (binary == ".npy") {
    io::write_npy(path, X);
  } else if (binary == ".mat") {
    io::write_mat(path, X);
  } else {
    emit(matrix_csv(X), path);
  }
}

std::string labelled_matrix_csv(const FitResult& result) {
  const auto or_numbers = [](const std::vector<std::string>& names, Eigen::Index count) {
    if (static_cast<Eigen::Index>(names.size()) == count) return names;
    std::vector<std::string> numbers;
    for (Eigen::Index k = 1; k <= count; ++k) numbers.push_back(std::to_string(k));
    return numbers;
  };
  std::ostringstream out;
  io::write_csv(out, result.X, or_numbers(result.row_names, result.X.rows()),
                or_numbers(result.column_names, result.X.cols()));
  return out.str();
}

void check_text_output(const std::string& path, const std::string& what) {
  const std::string binary = binary_extension(path);
  if (!binary.empty()) {
    throw UsageError("--output " + path + " names a " + binary + " file, which holds a matrix only, not " + what +
                     ": write " + what + " to another file name, or drop it to save X as " + binary);
  }
}

std::string side_by_side(const std::vector<std::string>& titles, const std::vector<Eigen::MatrixXd>& matrices,
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
    const std::size_t body = matrices[k].cols() * (cell_width[k] + 1);
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
          const std::string& cell = cells[k][i * matrices[k].cols() + j];
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

}  // namespace spdfit::cli
