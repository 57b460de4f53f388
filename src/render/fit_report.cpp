// `spdfit fit --report`: a FitResult for people.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "render/fit_result_json.hpp"
#include "render/labels.hpp"
#include "spdfit/format.hpp"
#include "spdfit/render.hpp"

namespace spdfit {

std::string detail::robust_line(const RobustReport& r) {
  std::ostringstream out;
  out << "robust: " << to_string(r.method) << " (k = " << format_number(r.tuning, Precision::Medium) << "), "
      << r.rows_downweighted_count << (r.rows_downweighted_count == 1 ? " row" : " rows")
      << " down-weighted below 0.5 (smallest weight " << format_number(r.weights_min, Precision::Medium)
      << "), residual scale " << format_number(r.scale, Precision::Medium) << ", " << r.iterations
      << (r.iterations == 1 ? " iteration" : " iterations") << (r.converged ? "" : " (not settled)") << "\n";
  return out.str();
}

namespace {

// Fixed-point decimals that show a standard error to two significant digits.
int decimals_for(double standard_error) {
  if (!(standard_error > 0.0) || !std::isfinite(standard_error)) return 4;
  return std::clamp(1 - static_cast<int>(std::floor(std::log10(standard_error))), 0, 12);
}

// The standard deviations of a covariance's diagonal, "0.2, 0.4, 0.8" (one value when all are
// equal), each after its column's name when there is one per column ("ax 0.2, ay 0.4, az 0.8").
std::string deviations(const Eigen::MatrixXd& cov, const std::vector<std::string>& names) {
  const Eigen::VectorXd s = cov.diagonal().cwiseMax(0.0).cwiseSqrt();
  if (s.size() > 0 && (s.array() == s(0)).all()) return format_number(s(0), Precision::Medium);
  const bool named = static_cast<Eigen::Index>(names.size()) == s.size();
  std::string text;
  for (Eigen::Index i = 0; i < s.size(); ++i) {
    text += (i == 0 ? "" : ", ") + (named ? names[static_cast<std::size_t>(i)] + " " : std::string()) +
            format_number(s(i), Precision::Medium);
  }
  return text;
}

std::size_t longest(const std::vector<std::string>& texts, std::size_t at_least) {
  for (const std::string& t : texts) at_least = std::max(at_least, t.size());
  return at_least;
}

// The noise model in one line: where it came from and the noise standard deviations per column.
std::string noise_model_line(const Diagnostics& d, const FitResult& result) {
  const std::vector<std::string>& a = result.row_names;
  const std::vector<std::string>& b = result.column_names;
  if (!d.noise_model) {
    return "noise model: assumed-equal (the same noise in every column of A and B, in the units given)\n";
  }
  const NoiseModel& m = *d.noise_model;
  std::string text = "noise model: " + std::string(to_string(m.source()));
  if (m.source() == NoiseSource::Rest && m.rest_rows()) {
    text += " (" + std::to_string(*m.rest_rows()) + " rows" +
            (m.rest_a_path().empty() ? std::string() : " of " + m.rest_a_path() + ", " + m.rest_b_path()) + ")";
  }
  if (m.is_resolved()) {
    text += "; noise std in A " + deviations(m.cov_a(), a) + "; in B " + deviations(m.cov_b(), b);
  } else {
    text += "; noise std in A " + deviations(Eigen::MatrixXd(m.std_a().cwiseAbs2().asDiagonal()), a) + "; in B " +
            deviations(Eigen::MatrixXd(m.std_b().cwiseAbs2().asDiagonal()), b);
  }
  return text + "\n";
}

}  // namespace

std::string report(const SpectrumUncertainty& s, const std::string& indent) {
  std::ostringstream out;
  for (const std::vector<Eigen::Index>& cluster : s.clusters) {
    for (Eigen::Index i : cluster) {
      const int d = interval_decimals(s.standard_errors(i));
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
  if (!result.a_columns.empty()) out << "A: " << result.a_columns << "\nB: " << result.b_columns << "\n";
  if (!result.ok()) {
    out << "failed: " << result.message << "\n";
    return out.str();
  }
  // A bootstrap whose replicates had no spread, or fewer than two estimates, has no standard
  // errors (NaN, with a warning): the estimate is shown alone rather than "+- nan" or "+- 0".
  const Bootstrap* b = result.bootstrap && result.bootstrap->standard_errors.allFinite() ? &*result.bootstrap : nullptr;
  if (result.bootstrap && !b) {
    out << "X (no standard errors: the bootstrap's " << result.bootstrap->replicates
        << " replicates gave fewer than two different estimates)\n";
  } else if (b) {
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
  // X maps A's columns to B's: its rows are named by A's columns, its columns by B's (numbers
  // where a file has no names).
  const std::vector<std::string> rows = detail::labels_or_numbers(result.row_names, result.X.rows());
  const std::vector<std::string> columns = detail::labels_or_numbers(result.column_names, result.X.cols());
  if (!result.row_names.empty() || !result.column_names.empty()) out << "rows: A's columns; columns: B's columns\n";
  const int row_width = static_cast<int>(longest(rows, 4));
  const int column_width = static_cast<int>(longest(columns, width)) + 2;
  out << std::string(static_cast<std::size_t>(row_width), ' ');
  for (const std::string& name : columns) out << std::setw(column_width) << name;
  out << '\n';
  for (Eigen::Index i = 0; i < result.X.rows(); ++i) {
    out << std::setw(row_width) << rows[static_cast<std::size_t>(i)];
    for (Eigen::Index j = 0; j < result.X.cols(); ++j) {
      out << std::setw(column_width) << cells[static_cast<std::size_t>(i * result.X.cols() + j)];
    }
    out << '\n';
  }
  if (b && b->eigenvalues) {
    // The eigenvalues' intervals are percentile intervals whatever the entries' type: said where it differs.
    out << "\neigenvalues (ascending) +- standard error   [" << format_percent(b->interval.level, Precision::Medium)
        << (b->interval.type == BootstrapInterval::Percentile ? " interval]\n" : " percentile interval]\n")
        << report(*b->eigenvalues, "  ");
  } else if (d.min_eigenvalue && d.max_eigenvalue) {
    out << "\neigenvalues: " << format_number(*d.min_eigenvalue, Precision::Full) << " to "
        << format_number(*d.max_eigenvalue, Precision::Full) << '\n';
  }
  if (b) {
    out << "\n" << format_percent(b->interval.level, Precision::Medium)
        << " " << to_string(b->interval.type) << " intervals of every entry and the bias estimate: " << hints.details
        << "\n";
  }
  // noise_sigma is the equal-noise model's estimate: beside a noise model it would contradict it.
  if (d.noise_sigma && !d.noise_model) {
    out << "noise estimate: sigma = " << format_number(*d.noise_sigma, Precision::Full)
        << " in every entry of A (times the noise ratio in B)\n";
  }
  out << noise_model_line(d, result);
  if (const auto& r = result.robust) out << detail::robust_line(*r);
  if (const auto& o = result.offsets) {
    if (o->mode == Offsets::Estimate) {
      out << "offsets: estimated with X (A X + 1 c^T ~= B), c = [" << format_numbers(o->c, Precision::Full) << "]\n";
    } else if (o->mode == Offsets::Rest) {
      out << "offsets: the rest rows' means subtracted, A [" << format_numbers(o->a, Precision::Full) << "], B ["
          << format_numbers(o->b, Precision::Full) << "]\n";
    }
  }
  return out.str();
}

}  // namespace spdfit
