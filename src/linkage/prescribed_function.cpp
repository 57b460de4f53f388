#include "spdfit/linkage/prescribed_function.hpp"

#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

#include "linkage_format.hpp"

namespace spdfit::linkage {

using Eigen::Index;
using Eigen::VectorXd;

namespace {

constexpr double kPi = 3.14159265358979323846;

const std::map<std::string, std::function<double(double)>>& functions() {
  static const std::map<std::string, std::function<double(double)>> table = {
      {"linear", [](double x) { return x; }},
      {"square", [](double x) { return x * x; }},
      {"cube", [](double x) { return x * x * x; }},
      {"sqrt", [](double x) { return x >= 0.0 ? std::sqrt(x) : std::nan(""); }},
      {"reciprocal", [](double x) { return 1.0 / x; }},
      {"exp", [](double x) { return std::exp(x); }},
      // log(0) is -inf (std::log says so too); only a negative argument has no value.
      {"ln", [](double x) { return x >= 0.0 ? std::log(x) : std::nan(""); }},
      {"log10", [](double x) { return x >= 0.0 ? std::log10(x) : std::nan(""); }},
      {"sin", [](double x) { return std::sin(x); }},
      {"cos", [](double x) { return std::cos(x); }},
      {"tan", [](double x) { return std::tan(x); }},
  };
  return table;
}

void check_range(double lo, double hi, const char* what) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
    throw std::invalid_argument(std::string(what) + " must be finite with lo < hi");
  }
}

}  // namespace

VectorXd spaced_points(double lo, double hi, int n, Spacing spacing) {
  check_range(lo, hi, "the range");
  if (n < 1) throw std::invalid_argument("the number of points must be at least 1");
  VectorXd x(n);
  if (n == 1) {
    x(0) = 0.5 * (lo + hi);
    return x;
  }
  for (int j = 0; j < n; ++j) {
    const double t = spacing == Spacing::Uniform
                         ? static_cast<double>(j) / (n - 1)
                         : 0.5 * (1.0 - std::cos((2.0 * j + 1.0) * kPi / (2.0 * n)));  // Chebyshev node j + 1
    x(j) = lo + t * (hi - lo);
  }
  if (spacing == Spacing::Uniform) x(n - 1) = hi;  // exactly, not lo + (hi - lo) with rounding
  return x;
}

double steering_condition(double delta_psi, double delta_phi, double rho) {
  return std::sin(delta_phi - delta_psi) - rho * std::sin(delta_psi) * std::sin(delta_phi);  // eq. 3.5
}

double steering_output(double delta_psi, double rho) {
  // sin(dphi)(cos dpsi - rho sin dpsi) = cos(dphi) sin(dpsi), solved for dphi by atan2 so that
  // dphi passes through 0 with dpsi and stays continuous past 90 degrees.
  return std::atan2(std::sin(delta_psi), std::cos(delta_psi) - rho * std::sin(delta_psi));
}

PrescribedPairs steering_pairs(double rho, double lo, double hi, int n, Spacing spacing) {
  if (!std::isfinite(rho)) throw std::invalid_argument("rho must be finite");
  PrescribedPairs pairs;
  pairs.delta_psi = spaced_points(lo, hi, n, spacing);
  pairs.delta_phi = pairs.delta_psi.unaryExpr([rho](double p) { return steering_output(p, rho); });
  return pairs;
}

DialZeros trapezoid_dial_zeros(double rho) {
  if (!std::isfinite(rho)) throw std::invalid_argument("rho must be finite");
  const double gamma = std::atan(0.5 * rho);  // arm angle from the car's axis: arm lines meet mid rear axle
  return {0.5 * kPi - gamma, 0.5 * kPi + gamma};
}

const std::vector<std::string>& function_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const auto& entry : functions()) out.push_back(entry.first);
    return out;
  }();
  return names;
}

PrescribedPairs function_pairs(const std::string& name, double x_lo, double x_hi, double psi_lo, double psi_hi,
                               double phi_lo, double phi_hi, int n, Spacing spacing) {
  const auto found = functions().find(name);
  if (found == functions().end()) {
    std::string known;
    for (const std::string& f : function_names()) known += (known.empty() ? "" : ", ") + f;
    throw std::invalid_argument("unknown function '" + name + "' (known: " + known + ")");
  }
  check_range(x_lo, x_hi, "the x range");
  if (!std::isfinite(psi_lo) || !std::isfinite(psi_hi) || psi_lo == psi_hi) {
    throw std::invalid_argument("the input angle range must be finite and not empty");
  }
  if (!std::isfinite(phi_lo) || !std::isfinite(phi_hi) || phi_lo == phi_hi) {
    throw std::invalid_argument("the output angle range must be finite and not empty");
  }
  const auto& f = found->second;
  const double y_lo = f(x_lo), y_hi = f(x_hi);
  if (!std::isfinite(y_lo) || !std::isfinite(y_hi) || y_lo == y_hi) {
    throw std::invalid_argument(name + "(x) must be finite at both ends of the x range and differ there (" + name +
                                "(" + detail::format(x_lo) + ") = " + detail::format(y_lo) + ", " + name + "(" +
                                detail::format(x_hi) + ") = " + detail::format(y_hi) + ")");
  }
  const VectorXd x = spaced_points(x_lo, x_hi, n, spacing);
  PrescribedPairs pairs;
  pairs.delta_psi.resize(n);
  pairs.delta_phi.resize(n);
  for (Index i = 0; i < n; ++i) {
    const double y = f(x(i));
    if (!std::isfinite(y)) {
      throw std::invalid_argument(name + "(x) is not defined or not finite at x = " + detail::format(x(i)));
    }
    // Linear maps of x onto the input range and of y onto the output range.
    pairs.delta_psi(i) = psi_lo + (x(i) - x_lo) / (x_hi - x_lo) * (psi_hi - psi_lo);
    pairs.delta_phi(i) = phi_lo + (y - y_lo) / (y_hi - y_lo) * (phi_hi - phi_lo);
  }
  return pairs;
}

}  // namespace spdfit::linkage
