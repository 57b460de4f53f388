// The estimators spdfit provides, and their names on the command line.
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace spdfit {

/// An estimator of X in A X ~= B. The command-line names are those of `to_string`.
enum class Method {
  LeastSquares,                ///< "ls": X = A^+ B (thesis 000 section 3.1)
  SymmetricProcrustes,         ///< "procrustes": symmetric least squares (thesis eq. 3.15)
  TotalLeastSquares,           ///< "tls": X = -V12 V22^-1 (thesis eq. 4.37)
  TotalLeastSquaresSymmetric,  ///< "tls-sym": (X_TLS + X_TLS^T) / 2 (thesis eq. 4.38)
  TotalLeastSquaresPsd,        ///< "tls-psd": Higham's nearest PSD matrix to X_TLS (thesis eq. 4.39)
  Spde,                        ///< "spde": the area-criterion estimate (Chen & McInroy, Thm III.3)
  SpdTotalLeastSquares,        ///< "spd-tls": total least squares over the SPD matrices
  PsdLeastSquares,             ///< "psd-ls": least squares over X >= min_eig I, with a certificate
  Auto,                        ///< "auto": spde, spd-tls or psd-ls, chosen from the data (auto.hpp)
};

/// Every estimator, in the order reports list them (auto, which runs one of them, is not listed).
inline constexpr std::array<Method, 8> kAllMethods = {
    Method::LeastSquares,         Method::SymmetricProcrustes,
    Method::TotalLeastSquares,    Method::TotalLeastSquaresSymmetric,
    Method::TotalLeastSquaresPsd, Method::Spde,
    Method::SpdTotalLeastSquares, Method::PsdLeastSquares};

/// Every value a method option accepts: the estimators, then auto.
inline constexpr std::array<Method, 9> kSelectableMethods = {
    Method::LeastSquares,         Method::SymmetricProcrustes,
    Method::TotalLeastSquares,    Method::TotalLeastSquaresSymmetric,
    Method::TotalLeastSquaresPsd, Method::Spde,
    Method::SpdTotalLeastSquares, Method::PsdLeastSquares,
    Method::Auto};

/// The six estimators of the source documents (the thesis' comparison), in report order.
inline constexpr std::array<Method, 6> kSeedMethods = {
    Method::LeastSquares,         Method::SymmetricProcrustes,
    Method::TotalLeastSquares,    Method::TotalLeastSquaresSymmetric,
    Method::TotalLeastSquaresPsd, Method::Spde};

/// The method's command-line name: "ls", "procrustes", "tls", "tls-sym", "tls-psd", "spde",
/// "spd-tls", "psd-ls" or "auto".
constexpr std::string_view to_string(Method method) {
  switch (method) {
    case Method::LeastSquares:
      return "ls";
    case Method::SymmetricProcrustes:
      return "procrustes";
    case Method::TotalLeastSquares:
      return "tls";
    case Method::TotalLeastSquaresSymmetric:
      return "tls-sym";
    case Method::TotalLeastSquaresPsd:
      return "tls-psd";
    case Method::Spde:
      return "spde";
    case Method::SpdTotalLeastSquares:
      return "spd-tls";
    case Method::PsdLeastSquares:
      return "psd-ls";
    case Method::Auto:
      return "auto";
  }
  return "unknown";
}

/// Whether the method fits A and B as total least squares, and so takes FitOptions::noise_ratio
/// (the ratio of the noise in B to the noise in A): tls, tls-sym, tls-psd, spd-tls and auto.
constexpr bool uses_noise_ratio(Method method) {
  return method == Method::TotalLeastSquares || method == Method::TotalLeastSquaresSymmetric ||
         method == Method::TotalLeastSquaresPsd || method == Method::SpdTotalLeastSquares ||
         method == Method::Auto;
}

/// Whether the method iterates, and so takes FitOptions::max_iterations: spd-tls, psd-ls, auto.
constexpr bool uses_max_iterations(Method method) {
  return method == Method::SpdTotalLeastSquares || method == Method::PsdLeastSquares || method == Method::Auto;
}

/// Whether the method takes the eigenvalue floor FitOptions::min_eig: psd-ls.
constexpr bool uses_min_eig(Method method) { return method == Method::PsdLeastSquares; }

/// The method with the given command-line name, or nothing if there is none.
constexpr std::optional<Method> parse_method(std::string_view name) {
  for (Method method : kSelectableMethods) {
    if (to_string(method) == name) return method;
  }
  return std::nullopt;
}

}  // namespace spdfit
