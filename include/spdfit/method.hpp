// The estimators spdfit provides, and their names on the command line.
#pragma once

#include <array>
#include <optional>
#include <string>
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

/// The six estimators of the source documents (the thesis' comparison), in report order.
inline constexpr std::array<Method, 6> kSourceDocumentMethods = {
    Method::LeastSquares,         Method::SymmetricProcrustes,
    Method::TotalLeastSquares,    Method::TotalLeastSquaresSymmetric,
    Method::TotalLeastSquaresPsd, Method::Spde};

namespace detail {
template <std::size_t N, std::size_t K>
constexpr std::array<Method, N + K> append(const std::array<Method, N>& head, const std::array<Method, K>& tail) {
  std::array<Method, N + K> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = head[i];
  for (std::size_t i = 0; i < K; ++i) out[N + i] = tail[i];
  return out;
}
}  // namespace detail

/// Every estimator, in the order reports list them: the seed methods, then spd-tls and psd-ls
/// (auto, which runs one of them, is not listed).
inline constexpr std::array<Method, 8> kAllMethods =
    detail::append(kSourceDocumentMethods, std::array<Method, 2>{Method::SpdTotalLeastSquares, Method::PsdLeastSquares});

/// The old name of kSourceDocumentMethods, which read as if it had to do with FitOptions::seed;
/// removed in the next release.
[[deprecated("use kSourceDocumentMethods")]] inline constexpr const std::array<Method, 6>& kSeedMethods =
    kSourceDocumentMethods;

/// Every value a method option accepts: the estimators, then auto.
inline constexpr std::array<Method, 9> kSelectableMethods =
    detail::append(kAllMethods, std::array<Method, 1>{Method::Auto});

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

/// Whether the method models noise in A (the total least-squares methods, spde, auto), unlike ls,
/// procrustes and psd-ls, which model noise in B only.
constexpr bool models_noise_in_a(Method method) { return uses_noise_ratio(method) || method == Method::Spde; }

/// Whether the method iterates, and so takes FitOptions::max_iterations: spd-tls, psd-ls, auto.
constexpr bool uses_max_iterations(Method method) {
  return method == Method::SpdTotalLeastSquares || method == Method::PsdLeastSquares || method == Method::Auto;
}

/// Whether the method takes the eigenvalue floor FitOptions::min_eig: psd-ls.
constexpr bool uses_min_eig(Method method) { return method == Method::PsdLeastSquares; }

/// Whether the method fits a non-square X (n x d, from B with d != n columns): ls and tls. Every
/// other method estimates a symmetric X and needs d = n.
constexpr bool fits_non_square(Method method) {
  return method == Method::LeastSquares || method == Method::TotalLeastSquares;
}

/// The message for `method` given A with n columns and B with d != n (a non-square X it does not
/// fit); it names ls and tls. Nothing when the method fits it.
inline std::optional<std::string> non_square_refusal(Method method, long long n, long long d) {
  if (d == n || fits_non_square(method)) return std::nullopt;
  return std::string(to_string(method)) + " estimates a symmetric X, so B needs as many columns as A, but A has " +
         std::to_string(n) + " and B " + std::to_string(d) + ": for the " + std::to_string(n) + "x" +
         std::to_string(d) + " X of A X ~= B use ls or tls";
}

/// The message for `method` given m rows of A (n columns) and B (d columns) that are too few for
/// it beyond the m >= n every method needs: tls with a non-square X needs m >= n + d (it corrects
/// [A B] to rank n, which needs the matrix to be tall). Nothing when there are enough.
inline std::optional<std::string> too_few_rows_refusal(Method method, long long m, long long n, long long d) {
  if (method != Method::TotalLeastSquares || d == n || m >= n + d) return std::nullopt;
  return "tls: the data has " + std::to_string(m) + " rows but [A B] has n + d = " + std::to_string(n + d) +
         " columns: a non-square X needs at least as many rows as that";
}

/// The options of FitOptions that apply to some methods only. Deprecated: fit_option_table()
/// (fit_request.hpp) says which methods take each option, and check_fit_request applies it; this
/// enum and misplaced_option(MethodOption, ...) go in the next release (docs/changes.md).
enum class [[deprecated("use fit_option_table() and check_fit_request (fit_request.hpp)")]] MethodOption {
  NoiseRatio,     ///< noise_ratio: uses_noise_ratio
  MaxIterations,  ///< max_iterations: uses_max_iterations
  MinEig,         ///< min_eig: uses_min_eig
};

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
#endif
/// Whether `option` applies to `method`. Deprecated with MethodOption.
[[deprecated("use fit_option_table() and check_fit_request (fit_request.hpp)")]]
constexpr bool applies(MethodOption option, Method method) {
  switch (option) {
    case MethodOption::NoiseRatio:
      return uses_noise_ratio(method);
    case MethodOption::MaxIterations:
      return uses_max_iterations(method);
    case MethodOption::MinEig:
      return uses_min_eig(method);
  }
  return false;
}

/// The message for `option`, spelled as the caller spells it ("--noise-ratio" on the command
/// line, "noise_ratio" in Python), given with a method it does not apply to; it names the
/// methods it applies to. Nothing when it applies. Deprecated with MethodOption.
[[deprecated("use fit_option_table() and check_fit_request (fit_request.hpp)")]]
inline std::optional<std::string> misplaced_option(MethodOption option, Method method, std::string_view spelling) {
  if (applies(option, method)) return std::nullopt;
  std::string names;
  for (Method m : kSelectableMethods) {
    if (applies(option, m)) names += (names.empty() ? "" : ", ") + std::string(to_string(m));
  }
  const char* kind = option == MethodOption::NoiseRatio      ? "the total least-squares methods and auto ("
                     : option == MethodOption::MaxIterations ? "the iterative methods ("
                                                             : "";
  return std::string(spelling) + " applies to " + kind + names + (*kind ? ")" : "") + ", not to " +
         std::string(to_string(method));
}
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

/// The method with the given command-line name, or nothing if there is none.
constexpr std::optional<Method> parse_method(std::string_view name) {
  for (Method method : kSelectableMethods) {
    if (to_string(method) == name) return method;
  }
  return std::nullopt;
}

}  // namespace spdfit
