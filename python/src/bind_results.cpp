// The result classes of the estimators and repairs (FitResult, Diagnostics, Bootstrap, NearestResult
// and their parts): read-only attributes, pickling and repr.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <sstream>

#include "bindings.hpp"
#include "pickle.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/nearest_spd.hpp"

namespace py = pybind11;

namespace spdfit::python {

namespace {

// Every Status, for unpickling it by name (pickle.hpp).
constexpr std::array<Status, 3> kStatuses = {Status::NotComputed, Status::Success, Status::NumericalFailure};

// Diagnostics has its own pickle, not pickle_fields: it also reads the 30-field state pickled
// before B could have d != n columns.
py::tuple diagnostics_state(const Diagnostics& d) {
  std::optional<std::string> chosen;
  if (d.chosen_method) chosen = std::string(to_string(*d.chosen_method));
  return py::make_tuple(d.m, d.n, d.rank_a, d.rank_b, d.cond_a, d.cond_b, d.singular_values_a, d.singular_values_b,
                        d.residual_norm, d.symmetric, d.min_eigenvalue, d.max_eigenvalue, d.positive_definite,
                        d.positive_semidefinite, d.area_criterion, d.area_criterion_minimum,
                        d.cross_term_positive_definite, d.tls_sigma_n, d.tls_sigma_n1, d.tls_correction_norm,
                        d.tls_v22_min_singular_value, d.noise_sigma, d.iterations, d.gradient_norm, d.converged,
                        d.certificate, chosen, d.reason, d.cond_a_scaled, d.cond_b_scaled, d.d);
}

Diagnostics diagnostics_from(const py::tuple& t) {
  // 30 fields: pickled before B could have d != n columns (then d = n).
  if (t.size() != 30) check_state(t, 31, "Diagnostics");
  Diagnostics d;
  d.m = t[0].cast<Eigen::Index>();
  d.n = t[1].cast<Eigen::Index>();
  d.rank_a = t[2].cast<Eigen::Index>();
  d.rank_b = t[3].cast<Eigen::Index>();
  d.cond_a = t[4].cast<double>();
  d.cond_b = t[5].cast<double>();
  d.singular_values_a = t[6].cast<Eigen::VectorXd>();
  d.singular_values_b = t[7].cast<Eigen::VectorXd>();
  d.residual_norm = t[8].cast<double>();
  d.symmetric = t[9].cast<bool>();
  d.min_eigenvalue = t[10].cast<std::optional<double>>();
  d.max_eigenvalue = t[11].cast<std::optional<double>>();
  d.positive_definite = t[12].cast<bool>();
  d.positive_semidefinite = t[13].cast<bool>();
  d.area_criterion = t[14].cast<std::optional<double>>();
  d.area_criterion_minimum = t[15].cast<std::optional<double>>();
  d.cross_term_positive_definite = t[16].cast<std::optional<bool>>();
  d.tls_sigma_n = t[17].cast<std::optional<double>>();
  d.tls_sigma_n1 = t[18].cast<std::optional<double>>();
  d.tls_correction_norm = t[19].cast<std::optional<double>>();
  d.tls_v22_min_singular_value = t[20].cast<std::optional<double>>();
  d.noise_sigma = t[21].cast<std::optional<double>>();
  d.iterations = t[22].cast<std::optional<int>>();
  d.gradient_norm = t[23].cast<std::optional<double>>();
  d.converged = t[24].cast<std::optional<bool>>();
  d.certificate = t[25].cast<std::optional<PsdCertificate>>();
  if (auto chosen = t[26].cast<std::optional<std::string>>()) {
    d.chosen_method = enum_from(*chosen, kSelectableMethods, "Diagnostics", "method");
  }
  d.reason = t[27].cast<std::optional<AutoReason>>();
  d.cond_a_scaled = t[28].cast<double>();
  d.cond_b_scaled = t[29].cast<double>();
  d.d = t.size() > 30 ? t[30].cast<Eigen::Index>() : d.n;
  return d;
}

// The getter of a FitResult attribute that is a field of its bootstrap: a copy, or None without one.
template <typename Member>
auto from_bootstrap(Member Bootstrap::*member) {
  return [member](const FitResult& r) -> std::optional<Member> {
    if (!r.bootstrap) return std::nullopt;
    return (*r.bootstrap).*member;
  };
}

std::string repr(const FitResult& r) {
  std::ostringstream out;
  out << "FitResult(method='" << to_string(r.method) << "', ";
  if (!r.ok()) {
    out << "failed: " << r.message << ")";
    return out.str();
  }
  const Diagnostics& d = r.diagnostics;
  out << "n=" << d.n << ", m=" << d.m << ", residual_norm=" << d.residual_norm;
  if (d.symmetric) out << ", positive_definite=" << (d.positive_definite ? "True" : "False");
  if (d.area_criterion) out << ", area_criterion=" << *d.area_criterion;
  if (!r.warnings.empty()) out << ", warnings=" << r.warnings.size();
  if (r.bootstrap) out << ", bootstrap=" << r.bootstrap->replicates - r.bootstrap->failed << " replicates";
  out << ")\nX =\n" << r.X;
  return out.str();
}

}  // namespace

void bind_results(py::module_& m) {
  py::class_<PsdCertificate>(m, "PsdCertificate",
                             "psd-ls's proof of optimality: X is optimal when primal_min_eig >= 0, "
                             "dual_min_eig >= 0 and complementarity = 0 (to rounding).")
      .def_property_readonly("primal_min_eig", copied(&PsdCertificate::primal_min_eig), "lambda_min(X - min_eig I)")
      .def_property_readonly("dual_min_eig", copied(&PsdCertificate::dual_min_eig), "lambda_min(S), S = sym(A^T A X - A^T B)")
      .def_property_readonly("complementarity", copied(&PsdCertificate::complementarity), "<X - min_eig I, S>")
      .def_property_readonly("duality_gap", copied(&PsdCertificate::duality_gap),
                    "|complementarity| / (||A^T A||_2 ||X||_F + ||A^T B||_F)")
      .def(pickle_fields<PsdCertificate>(
          "PsdCertificate", state_field(&PsdCertificate::primal_min_eig), state_field(&PsdCertificate::dual_min_eig),
          state_field(&PsdCertificate::complementarity), state_field(&PsdCertificate::duality_gap)))
      .def("__repr__", [](const PsdCertificate& c) {
        std::ostringstream out;
        out << "PsdCertificate(primal_min_eig=" << c.primal_min_eig << ", dual_min_eig=" << c.dual_min_eig
            << ", complementarity=" << c.complementarity << ", duality_gap=" << c.duality_gap << ")";
        return out.str();
      });
  py::class_<AutoReason>(m, "AutoReason", "Why auto chose its method: a stable code and a sentence.")
      .def_property_readonly("code", copied(&AutoReason::code))
      .def_property_readonly("text", copied(&AutoReason::text))
      .def(pickle_fields<AutoReason>("AutoReason", state_field(&AutoReason::code), state_field(&AutoReason::text)))
      .def("__repr__", [](const AutoReason& r) { return "AutoReason(code='" + r.code + "', text='" + r.text + "')"; });

  py::class_<Diagnostics>(m, "Diagnostics",
                          "What an estimate is checked by: ranks and condition numbers of A and B, the "
                          "residual, definiteness, the area criterion and method-specific values "
                          "(None where not defined).")
      .def_property_readonly("m", copied(&Diagnostics::m), "rows (samples)")
      .def_property_readonly("n", copied(&Diagnostics::n), "A's columns; X is n x d")
      .def_property_readonly("d", copied(&Diagnostics::d),
                             "B's columns; d = n (a square X) for every method but ls and tls")
      .def_property_readonly("rank_a", copied(&Diagnostics::rank_a))
      .def_property_readonly("rank_b", copied(&Diagnostics::rank_b))
      .def_property_readonly("cond_a", copied(&Diagnostics::cond_a), "sigma_max / sigma_min of A (inf when singular)")
      .def_property_readonly("cond_b", copied(&Diagnostics::cond_b))
      .def_property_readonly("cond_a_scaled", copied(&Diagnostics::cond_a_scaled),
                             "cond(A) with A's columns scaled to unit norm: the rank is decided on it")
      .def_property_readonly("cond_b_scaled", copied(&Diagnostics::cond_b_scaled))
      .def_property_readonly("singular_values_a", copied(&Diagnostics::singular_values_a))
      .def_property_readonly("singular_values_b", copied(&Diagnostics::singular_values_b))
      .def_property_readonly("residual_norm", copied(&Diagnostics::residual_norm), "||A X - B||_F")
      .def_property_readonly("symmetric", copied(&Diagnostics::symmetric))
      .def_property_readonly("positive_definite", copied(&Diagnostics::positive_definite))
      .def_property_readonly("positive_semidefinite", copied(&Diagnostics::positive_semidefinite))
      .def_property_readonly("min_eigenvalue", copied(&Diagnostics::min_eigenvalue))
      .def_property_readonly("max_eigenvalue", copied(&Diagnostics::max_eigenvalue))
      .def_property_readonly("area_criterion", copied(&Diagnostics::area_criterion),
                    "||A Y - B Y^-T||_F^2 with X = Y Y^T (Chen & McInroy, Definition II.1)")
      .def_property_readonly("area_criterion_minimum", copied(&Diagnostics::area_criterion_minimum),
                    "spde: 2 tr(Sigma_Q~ - A^T B) (Corollary III.4)")
      .def_property_readonly("cross_term_positive_definite", copied(&Diagnostics::cross_term_positive_definite),
                    "procrustes: A^T B + B^T A positive definite (thesis Theorem 3.2 (3))")
      .def_property_readonly("tls_sigma_n", copied(&Diagnostics::tls_sigma_n))
      .def_property_readonly("tls_sigma_n1", copied(&Diagnostics::tls_sigma_n1))
      .def_property_readonly("tls_correction_norm", copied(&Diagnostics::tls_correction_norm), "thesis eq. 4.33")
      .def_property_readonly("tls_v22_min_singular_value", copied(&Diagnostics::tls_v22_min_singular_value))
      .def_property_readonly("noise_sigma", copied(&Diagnostics::noise_sigma),
                    "noise standard deviation in A under the TLS model (noise_ratio times it in B); "
                    "None when m == n")
      .def_property_readonly("iterations", copied(&Diagnostics::iterations), "spd-tls, psd-ls: iterations taken")
      .def_property_readonly("gradient_norm", copied(&Diagnostics::gradient_norm),
                    "spd-tls: ||X^1/2 grad f X^1/2||_F; psd-ls: the relative KKT residual")
      .def_property_readonly("converged", copied(&Diagnostics::converged), "spd-tls, psd-ls: the stopping rule held")
      .def_property_readonly("certificate", copied(&Diagnostics::certificate), "psd-ls: the optimality certificate")
      .def_property_readonly(
          "chosen_method",
          [](const Diagnostics& d) -> std::optional<std::string> {
            if (!d.chosen_method) return std::nullopt;
            return std::string(to_string(*d.chosen_method));
          },
          "auto: the method it ran")
      .def_property_readonly("reason", copied(&Diagnostics::reason), "auto: why (code, text)")
      .def(py::pickle(&diagnostics_state, &diagnostics_from))
      .def("__repr__", [](const Diagnostics& d) {
        std::ostringstream out;
        out << "Diagnostics(m=" << d.m << ", n=" << d.n << ", rank_a=" << d.rank_a << ", rank_b=" << d.rank_b
            << ", cond_a=" << d.cond_a << ", cond_b=" << d.cond_b << ", residual_norm=" << d.residual_norm
            << ")";
        return out.str();
      });

  py::class_<Interval>(m, "Interval", "A bootstrap percentile interval: the central `level` fraction of the replicates.")
      .def_property_readonly("level", copied(&Interval::level))
      .def_property_readonly("lower", copied(&Interval::lower))
      .def_property_readonly("upper", copied(&Interval::upper))
      .def(pickle_fields<Interval>("Interval", state_field(&Interval::level), state_field(&Interval::lower),
                                   state_field(&Interval::upper)))
      .def("__repr__", [](const Interval& i) {
        std::ostringstream out;
        out << "Interval(level=" << i.level << ")\nlower =\n" << i.lower << "\nupper =\n" << i.upper;
        return out.str();
      });
  py::class_<SpectrumUncertainty>(m, "SpectrumUncertainty",
                                  "Bootstrap uncertainty of sorted values (eigenvalues, modes); values closer than "
                                  "their standard errors form a cluster that shares one interval.")
      .def_property_readonly("estimate", copied(&SpectrumUncertainty::estimate), "the values, ascending")
      .def_property_readonly("standard_errors", copied(&SpectrumUncertainty::standard_errors))
      .def_property_readonly("lower", copied(&SpectrumUncertainty::lower), "the interval (the cluster's)")
      .def_property_readonly("upper", copied(&SpectrumUncertainty::upper))
      .def_property_readonly("clusters", copied(&SpectrumUncertainty::clusters), "lists of 0-based indices")
      .def_property_readonly("failed", copied(&SpectrumUncertainty::failed), "replicates without the values")
      .def(pickle_fields<SpectrumUncertainty>(
          "SpectrumUncertainty", state_field(&SpectrumUncertainty::estimate),
          state_field(&SpectrumUncertainty::standard_errors), state_field(&SpectrumUncertainty::lower),
          state_field(&SpectrumUncertainty::upper), state_field(&SpectrumUncertainty::clusters),
          state_field(&SpectrumUncertainty::failed)))
      .def("__repr__", [](const SpectrumUncertainty& s) {
        std::ostringstream out;
        out << "SpectrumUncertainty(estimate=" << s.estimate.transpose()
            << ", standard_errors=" << s.standard_errors.transpose() << ")";
        return out.str();
      });
  py::class_<Bootstrap>(m, "Bootstrap", "How the bootstrap ran and what it found (FitResult.bootstrap).")
      .def_property_readonly("replicates", copied(&Bootstrap::replicates), "requested")
      .def_property_readonly("failed", copied(&Bootstrap::failed), "replicates without an estimate, left out")
      .def_property_readonly("seed", copied(&Bootstrap::seed))
      .def_property_readonly("method", [](const Bootstrap& b) { return std::string(to_string(b.method)); },
                             "the method every replicate ran")
      .def_property_readonly("scheme", copied(&Bootstrap::scheme), "'multinomial' (rows) or 'poisson_groups' (streaming)")
      .def_property_readonly("group_rows", copied(&Bootstrap::group_rows), "poisson_groups: rows per group")
      .def_property_readonly("groups", copied(&Bootstrap::groups), "poisson_groups: groups")
      .def_property_readonly("standard_errors", copied(&Bootstrap::standard_errors))
      .def_property_readonly("bias", copied(&Bootstrap::bias))
      .def_property_readonly("interval", copied(&Bootstrap::interval))
      .def_property_readonly("eigenvalues", copied(&Bootstrap::eigenvalues), "SpectrumUncertainty, when X is symmetric")
      .def(pickle_fields<Bootstrap>(
          "Bootstrap", state_field(&Bootstrap::replicates), state_field(&Bootstrap::failed),
          state_field(&Bootstrap::seed), enum_field(&Bootstrap::method, kSelectableMethods, "Bootstrap", "method"),
          state_field(&Bootstrap::scheme), state_field(&Bootstrap::group_rows), state_field(&Bootstrap::groups),
          state_field(&Bootstrap::standard_errors), state_field(&Bootstrap::bias), state_field(&Bootstrap::interval),
          state_field(&Bootstrap::eigenvalues)))
      .def("__repr__", [](const Bootstrap& b) {
        std::ostringstream out;
        out << "Bootstrap(replicates=" << b.replicates << ", failed=" << b.failed << ", seed=" << b.seed
            << ", method='" << to_string(b.method) << "', scheme='" << b.scheme << "')";
        return out.str();
      });

  py::class_<FitResult>(m, "FitResult", "An estimate of X in A X ~= B with its diagnostics and warnings.")
      .def_property_readonly("method", [](const FitResult& r) { return std::string(to_string(r.method)); })
      .def_property_readonly("ok", &FitResult::ok)
      .def_property_readonly("status", [](const FitResult& r) { return std::string(to_string(r.status)); },
                             "'success', 'numerical_failure', or 'not_computed' (no estimator filled it)")
      .def_property_readonly("message", copied(&FitResult::message), "why it failed ('' on success)")
      .def_property_readonly("X", copied(&FitResult::X), "the estimate (n x n ndarray; empty on failure)")
      .def_property_readonly("diagnostics", copied(&FitResult::diagnostics))
      .def_property_readonly("warnings", copied(&FitResult::warnings))
      .def_property_readonly("standard_errors", from_bootstrap(&Bootstrap::standard_errors),
                             "the bootstrap standard error of every entry of X (n x n), or None without bootstrap=N")
      .def_property_readonly("interval", from_bootstrap(&Bootstrap::interval),
                             "the bootstrap percentile interval (level, lower, upper), or None")
      .def_property_readonly("bias", from_bootstrap(&Bootstrap::bias),
                             "the bootstrap bias estimate (mean of the replicates minus X), or None")
      .def_property_readonly("bootstrap", copied(&FitResult::bootstrap),
                             "the bootstrap's details (replicates, failed, seed, eigenvalues, ...), or None")
      .def_property_readonly("row_names", copied(&FitResult::row_names),
                             "names of X's rows: A's column names from its file's header (fit_files), else []")
      .def_property_readonly("column_names", copied(&FitResult::column_names),
                             "names of X's columns: B's column names from its file's header, else []")
      .def(pickle_fields<FitResult>(
          "FitResult", enum_field(&FitResult::method, kSelectableMethods, "FitResult", "method"),
          enum_field(&FitResult::status, kStatuses, "FitResult", "status"), state_field(&FitResult::message),
          state_field(&FitResult::X), state_field(&FitResult::diagnostics), state_field(&FitResult::warnings),
          state_field(&FitResult::bootstrap), state_field(&FitResult::row_names),
          state_field(&FitResult::column_names)))
      .def("__repr__", &repr);


  py::class_<NearestResult>(m, "NearestResult",
                            "A repaired matrix and how it was reached (nearest_spd, nearest_correlation).")
      .def_property_readonly("X", copied(&NearestResult::X), "the nearest matrix, exactly symmetric")
      .def_property_readonly("distance", copied(&NearestResult::distance),
                             "||X_in - X||_F (||W^1/2 (X_in - X) W^1/2||_F with weights)")
      .def_property_readonly("clipped", copied(&NearestResult::clipped), "eigenvalues raised to the floor")
      .def_property_readonly("min_eigenvalue_before", copied(&NearestResult::min_eigenvalue_before),
                             "of the input's symmetric part")
      .def_property_readonly("min_eig", copied(&NearestResult::min_eig),
                             "the floor applied, in the input's units (a relative floor resolved)")
      .def_property_readonly("iterations", copied(&NearestResult::iterations), "Newton iterations (0: direct)")
      .def_property_readonly("gradient_norm", copied(&NearestResult::gradient_norm),
                             "||diag(X) - d||_2 of the last Newton iterate, before the diagonal rescaling")
      .def_property_readonly("converged", copied(&NearestResult::converged))
      .def_property_readonly("cholesky_ok", copied(&NearestResult::cholesky_ok),
                             "whether X has a Cholesky factorization (positive definite)")
      .def_property_readonly("warnings", copied(&NearestResult::warnings))
      .def("__repr__",
           [](const NearestResult& r) {
             std::ostringstream out;
             out << "NearestResult(distance=" << r.distance << ", clipped=" << r.clipped << ", min_eig=" << r.min_eig
                 << ", iterations=" << r.iterations << ", converged=" << (r.converged ? "True" : "False")
                 << ", cholesky_ok=" << (r.cholesky_ok ? "True" : "False") << ")\nX =\n"
                 << r.X;
             return out.str();
           })
      .def(pickle_fields<NearestResult>(
          "NearestResult", state_field(&NearestResult::X), state_field(&NearestResult::distance),
          state_field(&NearestResult::clipped), state_field(&NearestResult::min_eigenvalue_before),
          state_field(&NearestResult::min_eig), state_field(&NearestResult::iterations),
          state_field(&NearestResult::gradient_norm), state_field(&NearestResult::converged),
          state_field(&NearestResult::cholesky_ok), state_field(&NearestResult::warnings)));
}

}  // namespace spdfit::python
