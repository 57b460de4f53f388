#include "linear_system/linear_system_explanation.hpp"

#include <cmath>

#include "spdfit/format.hpp"
#include "spdfit/rank.hpp"

namespace spdfit::detail {

using Eigen::Index;

namespace {

// What one equation in n unknowns is, geometrically (notes 002 3.3.2: "one linear equation in
// three unknowns represents a plane").
std::string objects(Index n, Index count) {
  const bool one = count == 1;
  if (n == 1) return one ? "point on the number line" : "points on the number line";
  if (n == 2) return one ? "line in the plane" : "lines in the plane";
  if (n == 3) return one ? "plane in space" : "planes in space";
  return (one ? "hyperplane in " : "hyperplanes in ") + std::to_string(n) + "-dimensional space";
}

std::string noun(Index n) {
  if (n == 1) return "points";
  if (n == 2) return "lines";
  if (n == 3) return "planes";
  return "hyperplanes";
}

// An affine set of dimension d.
std::string flat(Index d) {
  if (d == 0) return "a single point";
  if (d == 1) return "a line";
  if (d == 2) return "a plane";
  return "a " + std::to_string(d) + "-dimensional flat";
}

// A projective set of dimension e on the hyperplane at infinity.
std::string at_infinity(Index e) {
  if (e == 0) return "one point at infinity";
  if (e == 1) return "a line at infinity";
  if (e == 2) return "a plane at infinity";
  return "a " + std::to_string(e) + "-dimensional set of points at infinity";
}

// The hyperplane at infinity of n-dimensional space.
std::string hyperplane_at_infinity(Index n) {
  if (n == 2) return "the line at infinity";
  if (n == 3) return "the plane at infinity";
  return "the hyperplane at infinity";
}

std::string plural(Index count, const std::string& word) {
  return std::to_string(count) + " " + word + (count == 1 ? "" : "s");
}

std::string explain_column(const LinearSystemResult& r, const ColumnClassification& c) {
  const Index n = r.n, m = r.m, rank = r.rank;
  const std::string things = noun(n);
  const std::string residual = format_number(c.residual_norm, Precision::Medium);
  std::string out;
  if (rank == 0) {
    if (c.consistent) {
      return "A and b are zero: every x solves the system (the solution shown is x = 0, of minimum norm).";
    }
    return "A is zero but b is not: 0 = b has no finite solution; in the projective view its only solutions "
           "are all the points at infinity (" + at_infinity(n - 1) + "). The solution shown is x = 0, the "
           "minimum-norm least-squares approximation (residual norm " + residual + ").";
  }
  if (c.consistent) {
    if (c.finite_solution_dimension == 0) {
      out = m == 1 ? "The equation has exactly one solution" : "The " + things + " have exactly one point in common";
      out += ": a unique finite solution, and no solution at infinity.";
      if (m > n) out += " (There are more equations than unknowns, but they agree.)";
      return out;
    }
    const Index d = c.finite_solution_dimension;
    out = (m == 1 ? "The equation's solutions form " : "The " + things + " have ") + flat(d) +
          (m == 1 ? "" : " of finite points in common") + ": infinitely many solutions, a " +
          std::to_string(d) + "-parameter family x = x0 + N t (N the null-space basis).";
    if (rank == 1 && m > 1) out += " Every equation is a multiple of one: the " + things + " coincide.";
    out += " The solution shown is the one of minimum norm. In the projective view the solutions also include " +
           at_infinity(c.at_infinity_dimension) + ", where " + flat(d).replace(0, 1, "the") + " meets " +
           hyperplane_at_infinity(n) + ".";
    return out;
  }
  if (c.at_infinity_dimension < 0) {
    out = "The " + things + " have no point in common, finite or at infinity: the system is inconsistent "
          "(b is not in the range of A)";
    if (m > n) out += ", as an overdetermined system is in general";
    out += ". The solution shown is the least-squares approximation that comes closest to satisfying every "
           "equation (residual norm " + residual + ").";
    return out;
  }
  out = "The " + things + " have no finite point in common: the system is inconsistent (b is not in the "
        "range of A). In the projective view they still meet at infinity, in " +
        at_infinity(c.at_infinity_dimension) + " (the direction" + (r.nullity > 1 ? "s" : "") +
        " of the null space of A).";
  if (rank == 1 && m > 1) {
    out += " The left sides are all multiples of one: the " + things +
           " are parallel but not all coincident, and parallel " + things + " share only " +
           at_infinity(c.at_infinity_dimension) + ".";
  } else if (n == 3 && rank == 2 && m > 1) {
    out += " The lines in which pairs of planes intersect are parallel, and parallel lines meet at one point "
           "at infinity.";
  }
  out += " The solution shown is the minimum-norm least-squares approximation (residual norm " + residual + ").";
  return out;
}

}  // namespace

std::string explain(const LinearSystemResult& r) {
  std::string out = plural(r.m, "equation") + " in " + plural(r.n, "unknown") + " (" + to_string(r.shape) +
                    "): " + std::to_string(r.m) + " " + objects(r.n, r.m) + ". Rank " + std::to_string(r.rank) +
                    ", nullity " + std::to_string(r.nullity) + ".";
  Index edited_nonzero = 0;
  // The rank is decided on the column-scaled A (see solve()), so the values cut are its.
  const Eigen::VectorXd& s = r.scaled_singular_values;
  for (Index i = r.rank; i < s.size(); ++i) edited_nonzero += s(i) > 0.0;
  if (edited_nonzero > 0) {
    // Only the default cut-off, max(m, n) eps, marks a value as roundoff; a threshold the user
    // chose cuts values that may be real.
    const bool roundoff = r.rank_tolerance == default_rank_tolerance(r.m, r.n);
    const std::string was = edited_nonzero == 1 ? "was" : "were";
    if (roundoff) {
      out += " (" + plural(edited_nonzero, "nonzero singular value") + " of the column-scaled A below " + format_number(r.rank_tolerance, Precision::Medium) +
             " * sigma_max " + (edited_nonzero == 1 ? "is" : "are") + " roundoff and " + was +
             " edited to zero, notes 002 section 3.8.)";
    } else {
      out += " (" + plural(edited_nonzero, "nonzero singular value") + " of the column-scaled A below the chosen threshold " +
             format_number(r.rank_tolerance, Precision::Medium) + " * sigma_max " + was +
             " edited to zero, notes 002 section 3.8: not roundoff, so check that the threshold suits the data.)";
    }
  }
  for (std::size_t j = 0; j < r.columns.size(); ++j) {
    out += "\n";
    if (r.columns.size() > 1) out += "Right-hand side " + std::to_string(j + 1) + ": ";
    out += explain_column(r, r.columns[j]);
  }
  return out;
}

}  // namespace spdfit::detail
