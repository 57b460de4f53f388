#include "repair/fixed_entries.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "spdfit/format.hpp"
#include "spdfit/outcome.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

std::string entry_text(Index i, Index j) { return "(" + std::to_string(i + 1) + ", " + std::to_string(j + 1) + ")"; }

// The mask's lower triangle (diagonal included), checked.
Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> mask_of(const MatrixXd& fixed, int base, Index n) {
  Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> mask = Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>::Zero(n, n);
  if (fixed.rows() == n && fixed.cols() == n) {
    for (Index j = 0; j < n; ++j) {
      for (Index i = 0; i < n; ++i) {
        const double v = fixed(i, j);
        if (v != 0.0 && v != 1.0) {
          throw InputError("the mask of kept entries (`fixed`) has " + format_number(v) + " at " +
                                      entry_text(i, j) + ": a mask holds 1 (kept) and 0 (free)", Code::DataValue, "fixed");
        }
        if (v != fixed(j, i)) {
          throw InputError("the mask of kept entries (`fixed`) is not symmetric: " + entry_text(i, j) +
                                      " is " + format_number(v) + " but " + entry_text(j, i) + " is " +
                                      format_number(fixed(j, i)), Code::DataValue, "fixed");
        }
        if (v == 1.0 && i >= j) mask(i, j) = true;
      }
    }
    return mask;
  }
  if (fixed.cols() != 2) {
    throw InputError("the kept entries (`fixed`) are " + std::to_string(fixed.rows()) + "x" +
                                std::to_string(fixed.cols()) + ": give an " + std::to_string(n) + "x" +
                                std::to_string(n) + " mask (1: kept, 0: free), or index pairs i, j as two columns", Code::DataShape, "fixed");
  }
  for (Index k = 0; k < fixed.rows(); ++k) {
    Index ij[2];
    for (int c = 0; c < 2; ++c) {
      const double v = fixed(k, c);
      const double index = v - base;
      if (!(v == std::floor(v)) || !(index >= 0.0) || !(index < static_cast<double>(n))) {
        throw InputError("kept entry pair " + std::to_string(k + 1) + " of `fixed` has index " +
                                    format_number(v) + ": indices are integers from " + std::to_string(base) +
                                    " to " + std::to_string(n - 1 + base) + " (the matrix is " + std::to_string(n) +
                                    "x" + std::to_string(n) + ")", Code::DataValue, "fixed");
      }
      ij[c] = static_cast<Index>(index);
    }
    mask(std::max(ij[0], ij[1]), std::min(ij[0], ij[1])) = true;
  }
  return mask;
}

}  // namespace

FixedPattern fixed_pattern(const MatrixXd& fixed, int index_base, Index n, DiagonalRule rule) {
  Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> mask;
  if (fixed.size() > 0) {
    mask = mask_of(fixed, index_base, n);
    if (!mask.any()) {
      throw InputError("the mask of kept entries (`fixed`) is all zero: it keeps no entry (1 marks an "
                                  "entry kept exactly)", Code::DataValue, "fixed");
    }
  } else {
    mask = Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>::Zero(n, n);
  }
  if (rule != DiagonalRule::Free) mask.diagonal().setConstant(true);
  FixedPattern out;
  out.n = n;
  for (Index j = 0; j < n; ++j) {
    for (Index i = j; i < n; ++i) {
      if (!mask(i, j)) continue;
      out.row.push_back(i);
      out.col.push_back(j);
      (i == j ? out.diagonal : out.off_diagonal) += 1;
    }
  }
  return out;
}

void check_h_weights(const MatrixXd& H, const FixedPattern& pattern) {
  const Index n = pattern.n;
  if (H.rows() != n || H.cols() != n) {
    throw InputError("the elementwise weights (`h_weights`) are " + std::to_string(H.rows()) + "x" +
                                std::to_string(H.cols()) + ", not " + std::to_string(n) + "x" + std::to_string(n) +
                                " as the matrix", Code::DataShape, "h_weights");
  }
  double largest = 0.0;
  for (Index j = 0; j < n; ++j) {
    for (Index i = 0; i < n; ++i) {
      const double h = H(i, j);
      if (!std::isfinite(h) || h < 0.0) {
        throw InputError("the elementwise weight (`h_weights`) at " + entry_text(i, j) + " is " +
                                    format_number(h) + ": weights must be finite and >= 0 (0: the entry is free)", Code::DataValue, "h_weights");
      }
      largest = std::max(largest, h);
    }
  }
  for (Index j = 0; j < n; ++j) {
    for (Index i = j + 1; i < n; ++i) {
      if (std::abs(H(i, j) - H(j, i)) > 1e-10 * largest) {
        throw InputError("the elementwise weights (`h_weights`) are not symmetric: " + entry_text(i, j) +
                                    " is " + format_number(H(i, j)) + " but " + entry_text(j, i) + " is " +
                                    format_number(H(j, i)), Code::DataValue, "h_weights");
      }
    }
  }
  Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> kept = Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>::Zero(n, n);
  for (Index p = 0; p < pattern.size(); ++p) kept(pattern.row[p], pattern.col[p]) = true;
  for (Index j = 0; j < n; ++j) {
    for (Index i = j; i < n; ++i) {
      if (!kept(i, j) && H(i, j) > 0.0) return;
    }
  }
  throw InputError(largest == 0.0 ? "the elementwise weights (`h_weights`) are all zero: nothing to fit"
                                             : "the elementwise weights (`h_weights`) are zero on every entry the "
                                               "repair may change: nothing to fit", Code::DataValue, "h_weights");
}

void check_fixed_feasible(const MatrixXd& B, const FixedPattern& pattern, const VectorXd& f, const char* option) {
  const Index n = pattern.n;
  std::vector<bool> diagonal_kept(static_cast<std::size_t>(n), false);
  for (Index p = 0; p < pattern.size(); ++p) {
    if (pattern.row[p] == pattern.col[p]) diagonal_kept[static_cast<std::size_t>(pattern.row[p])] = true;
  }
  const bool floored = f.size() > 0 && f.maxCoeff() > 0.0;
  const std::string floor_hint =
      floored ? std::string(" (less the eigenvalue floor, ") + option + "; lower it if the entries are right)" : "";
  // A kept entry and its kept diagonal: the 2 x 2 minor of X - diag(f) must be >= 0.
  for (Index p = 0; p < pattern.size(); ++p) {
    const Index i = pattern.row[p], j = pattern.col[p];
    if (i == j || !diagonal_kept[i] || !diagonal_kept[j]) continue;
    const double a = B(i, i) - f(i), b = B(j, j) - f(j), c = B(i, j);
    const double rounding = 4.0 * kEps * (std::abs(B(i, i)) * std::abs(B(j, j)) + c * c);
    if (a < 0.0 || b < 0.0 || c * c - a * b > rounding) {
      throw InputError("the kept entry " + entry_text(i, j) + " = " + format_number(c) +
                                  " is larger in magnitude than the root of its kept diagonal entries' product (" +
                                  format_number(B(i, i)) + " at " + entry_text(i, i) + ", " + format_number(B(j, j)) +
                                  " at " + entry_text(j, j) + floor_hint +
                                  "): no positive semidefinite matrix has these entries", Code::DataValue, "fixed");
    }
  }
  // Fully kept blocks: the connected components of the graph of kept off-diagonal entries among
  // the rows whose diagonal is kept, when every pair of a component is kept.
  std::vector<Index> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), Index{0});
  const auto root = [&parent](Index i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<Index> edges(static_cast<std::size_t>(n), 0);
  for (Index p = 0; p < pattern.size(); ++p) {
    const Index i = pattern.row[p], j = pattern.col[p];
    if (i == j || !diagonal_kept[i] || !diagonal_kept[j]) continue;
    parent[root(i)] = root(j);
  }
  std::vector<std::vector<Index>> members(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) {
    if (diagonal_kept[i]) members[root(i)].push_back(i);
  }
  for (Index p = 0; p < pattern.size(); ++p) {
    const Index i = pattern.row[p], j = pattern.col[p];
    if (i != j && diagonal_kept[i] && diagonal_kept[j]) edges[root(i)] += 1;
  }
  for (Index r = 0; r < n; ++r) {
    const std::vector<Index>& block = members[r];
    const Index s = static_cast<Index>(block.size());
    if (s < 3 || edges[r] != s * (s - 1) / 2) continue;  // pairs: the minors above
    MatrixXd M(s, s);
    for (Index a = 0; a < s; ++a) {
      for (Index b = 0; b < s; ++b) M(a, b) = B(block[a], block[b]) - (a == b ? f(block[a]) : 0.0);
    }
    Eigen::SelfAdjointEigenSolver<MatrixXd> eig(M, Eigen::EigenvaluesOnly);
    if (eig.info() != Eigen::Success) continue;
    const double smallest = eig.eigenvalues()(0);
    const double rounding = 8.0 * static_cast<double>(s) * kEps * M.cwiseAbs().maxCoeff();
    if (smallest < -rounding) {
      throw InputError("the block of kept entries in rows and columns " + index_list(block) +
                                  " is not positive semidefinite" + floor_hint + ": its smallest eigenvalue is " +
                                  format_number(smallest) +
                                  "; no positive semidefinite matrix contains it (repair the block itself first, "
                                  "or keep fewer entries)", Code::DataValue, "fixed");
    }
  }
}

std::string index_list(const std::vector<Index>& indices, std::size_t shown) {
  std::string out;
  for (std::size_t k = 0; k < indices.size() && k < shown; ++k) {
    out += (k == 0 ? "" : ", ") + std::to_string(indices[k] + 1);
  }
  if (indices.size() > shown) out += ", ... (" + std::to_string(indices.size()) + " in all)";
  return out;
}

}  // namespace spdfit::detail
