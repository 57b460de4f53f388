// `spdfit fit --report`: a FitResult for people.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "spdfit/format.hpp"
#include "spdfit/render.hpp"

namespace spdfit {

namespace {

// Fixed-point decimals that show a standard error to two significant digits.
int decimals_for(double standard_error) {
  if (!(standard_error > 0.0) || !std::isfinite(standard_error)) return 4;
  return std::clamp(1 - static_cast<int>(std::floor(std::log10(standard_error))), 0, 12);
}

}  // namespace

std::string report(const SpectrumUncertainty& s, const std::string& indent) {
  std::ostringstream out;
  for (const std::vector<Eigen::Index>& cluster : s.clusters) {
    for (Eigen::Index i : cluster) {
      const int d = decimals_for(s.standard_errors(i));
      out << indent << std::setw(2) << i + 1 << "  " << std::setw(12) << format_fixed(s.estimate(i), d) << " +- "
          << format_fixed(s.standard_errors(i), d);
      if (i == cluster.front()) {
        out << "   [" << format_fixed(s.lower(i), d) << ", " << format_fixed(s.upper(i), d) << "]";
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

std::string report(const FitResult& result, const ReportHints& hints) {
  std::ostringstream out;
  const Diagnostics& d = result.diagnostics;
  out << to_string(result.method) << " estimate of X (" << d.n << " x " << d.d << ") from m = " << d.m << " rows";
  if (d.chosen_method && d.reason) out << " (chosen by auto: " << d.reason->code << ")";
  out << "\n";
  if (!result.ok()) {
    out << "failed: " << result.message << "\n";
    return out.str();
  }
  const auto& b = result.bootstrap;
  if (b) {
    out << "X +- standard error, bootstrap of " << b->replicates << " replicates (" << b->failed
        << " failed), seed " << b->seed << (b->scheme == "poisson_groups" ? ", Poisson counts on groups of rows" : "")
        << "\n";
  } else {
    out << "X (no standard errors: " << hints.bootstrap << ")\n";
  }
  std::vector<std::string> cells;
  std::size_t width = 0;
  for (Eigen::Index i = 0; i < result.X.rows(); ++i) {
    for (Eigen::Index j = 0; j < result.X.cols(); ++j) {
      std::string cell;
      if (b) {
        const int dec = decimals_for(b->standard_errors(i, j));
        cell = format_fixed(result.X(i, j), dec) + " +- " + format_fixed(b->standard_errors(i, j), dec);
      } else {
        cell = format_number(result.X(i, j), Precision::Full);
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
    out << "\neigenvalues (ascending) +- standard error   [" << format_percent(b->interval.level, Precision::Medium)
        << " interval]\n"
        << report(*b->eigenvalues, "  ");
  } else if (d.min_eigenvalue && d.max_eigenvalue) {
    out << "\neigenvalues: " << format_number(*d.min_eigenvalue, Precision::Full) << " to "
        << format_number(*d.max_eigenvalue, Precision::Full) << '\n';
  }
  if (b) {
    out << "\n" << format_percent(b->interval.level, Precision::Medium)
        << " percentile intervals of every entry and the bias estimate: " << hints.details << "\n";
  }
  if (d.noise_sigma) {
    out << "noise estimate: sigma = " << format_number(*d.noise_sigma, Precision::Full)
        << " in every entry of A (times the noise ratio in B)\n";
  }
  return out.str();
}

}  // namespace spdfit
