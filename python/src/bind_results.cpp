// The result classes of the estimators and repairs (FitResult, Diagnostics, Bootstrap, NearestResult
// and their parts): read-only attributes; pickling and repr from the library's rendering.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>


#include "bindings.hpp"
#include "pickle.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/nearest_spd.hpp"
#include "spdfit/render.hpp"

namespace py = pybind11;

namespace spdfit::python {

namespace {

// The getter of a FitResult attribute that is a field of its bootstrap: a copy, or None without one.
template <typename Member>
auto from_bootstrap(Member Bootstrap::*member) {
  return [member](const FitResult& r) -> std::optional<Member> {
    if (!r.bootstrap) return std::nullopt;
    return (*r.bootstrap).*member;
  };
}

// The repr of the parts: every field of the library's JSON.
template <typename Class>
auto json_repr(const char* name) {
  return [name](const Class& object) { return repr_from_json(name, to_json(object)); };
}

// A result's to_json as a pickle_json renderer.
template <typename Class>
std::string exact_json(const Class& object, JsonStyle style) {
  return to_json(object, style);
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
      .def(pickle_json<PsdCertificate>("PsdCertificate", &exact_json<PsdCertificate>))
      .def("__repr__", json_repr<PsdCertificate>("PsdCertificate"));
  py::class_<BoundaryCertificate>(
      m, "BoundaryCertificate",
      "spd-tls's proof of optimality on the boundary (a singular estimate): the first-order conditions of "
      "minimizing its criterion f (the likelihood with a noise model) over the positive semidefinite matrices, with X = "
      "V_r Lambda V_r^T, V_0 its null space and G = grad f(X), in the coordinates where X has a unit diagonal and "
      "relative to f. X satisfies them when stationarity = 0, cross_block = 0 and multiplier_min_eig >= 0 (to "
      "rounding).")
      .def_property_readonly("rank", copied(&BoundaryCertificate::rank), "X's rank r")
      .def_property_readonly("stationarity", copied(&BoundaryCertificate::stationarity),
                             "||Lambda^1/2 V_r^T G V_r Lambda^1/2||_F / f")
      .def_property_readonly("cross_block", copied(&BoundaryCertificate::cross_block),
                             "||Lambda^1/2 V_r^T G V_0||_F / f")
      .def_property_readonly("multiplier_min_eig", copied(&BoundaryCertificate::multiplier_min_eig),
                             "lambda_min(V_0^T G V_0) / f")
      .def(pickle_json<BoundaryCertificate>("BoundaryCertificate", &exact_json<BoundaryCertificate>))
      .def("__repr__", json_repr<BoundaryCertificate>("BoundaryCertificate"));
  py::class_<AutoReason>(m, "AutoReason", "Why auto chose its method: a stable code and a sentence.")
      .def_property_readonly("code", copied(&AutoReason::code))
      .def_property_readonly("text", copied(&AutoReason::text))
      .def(pickle_json<AutoReason>("AutoReason", &exact_json<AutoReason>))
      .def("__repr__", json_repr<AutoReason>("AutoReason"));

  py::class_<Diagnostics>(m, "Diagnostics",
                          "What an estimate is checked by: ranks and condition numbers of A and B, the "
                          "residual, definiteness, the area criterion and method-specific values "
                          "(None where not defined).")
      .def_property_readonly("noise_model", copied(&Diagnostics::noise_model),
                             "the noise model the estimate used (NoiseModel), or None: then it assumed equal noise "
                             "in every column of A and B, in the units given")
      .def_property_readonly("m", copied(&Diagnostics::m), "rows (samples)")
      .def_property_readonly("n", copied(&Diagnostics::n), "A's columns; X is n x d")
      .def_property_readonly("d", copied(&Diagnostics::d),
                             "B's columns; d = n (a square X) for every method but ls and tls")
      .def_property_readonly("rank_a", copied(&Diagnostics::rank_a))
      .def_property_readonly("rank_b", copied(&Diagnostics::rank_b))
      .def_property_readonly("cond_a", copied(&Diagnostics::cond_a), "sigma_max / sigma_min of A (inf when singular)")
      .def_property_readonly("cond_b", copied(&Diagnostics::cond_b))
      .def_property_readonly(
          "cond_a_scaled",
          [](const Diagnostics& d) {
            py::gil_scoped_release release;  // an SVD at the first read, unless the fit needed it
            return d.cond_a_scaled.get();
          },
          "cond(A) with A's columns scaled to unit norm: the rank is decided on it. Computed when first "
          "read where the rank did not need it")
      .def_property_readonly("cond_b_scaled",
                             [](const Diagnostics& d) {
                               py::gil_scoped_release release;
                               return d.cond_b_scaled.get();
                             })
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
      .def_property_readonly(
          "noise_sigma",
          [](const Diagnostics& d) {
            // Computed at the first read (an SVD of the whole factor), not by the fit; the SVD
            // runs without the GIL.
            py::gil_scoped_release release;
            return d.noise_sigma.get();
          },
          "noise standard deviation in A under the TLS model (noise_ratio times it in B); "
          "None when m == n. Computed when first read (an SVD of the (n + d) x (n + d) factor of "
          "[A B]), not by the fit")
      .def_property_readonly("iterations", copied(&Diagnostics::iterations), "spd-tls, psd-ls: iterations taken")
      .def_property_readonly("gradient_norm", copied(&Diagnostics::gradient_norm),
                    "spd-tls: ||X^1/2 grad f X^1/2||_F; psd-ls: the relative KKT residual")
      .def_property_readonly("converged", copied(&Diagnostics::converged), "spd-tls, psd-ls: the stopping rule held")
      .def_property_readonly(
          "certificate",
          [](const Diagnostics& d) -> py::object {
            if (d.certificate) return py::cast(*d.certificate);
            if (d.boundary_certificate) return py::cast(*d.boundary_certificate);
            return py::none();
          },
          "the optimality certificate: psd-ls's (PsdCertificate), or spd-tls's on the boundary "
          "(BoundaryCertificate)")
      .def_property_readonly(
          "chosen_method",
          [](const Diagnostics& d) -> std::optional<std::string> {
            if (!d.chosen_method) return std::nullopt;
            return std::string(to_string(*d.chosen_method));
          },
          "auto: the method it ran")
      .def_property_readonly("reason", copied(&Diagnostics::reason), "auto: why (code, text)")
      .def(pickle_json<Diagnostics>("Diagnostics", &exact_json<Diagnostics>))
      .def("__repr__", json_repr<Diagnostics>("Diagnostics"));

  py::class_<Interval>(m, "Interval",
                       "A bootstrap interval of each entry at `level`: 'percentile' (the central `level` fraction of "
                       "the replicates), 'basic' (that reflected about the estimate) or 'normal' (the bias-corrected "
                       "estimate -+ z standard errors), as `type` says (fit's interval=).")
      .def_property_readonly("level", copied(&Interval::level))
      .def_property_readonly("type", [](const Interval& i) { return std::string(to_string(i.type)); },
                             "'percentile', 'basic' or 'normal'")
      .def_property_readonly("lower", copied(&Interval::lower))
      .def_property_readonly("upper", copied(&Interval::upper))
      .def(pickle_json<Interval>("Interval", &exact_json<Interval>))
      .def("__repr__", json_repr<Interval>("Interval"));
  py::class_<SpectrumUncertainty>(m, "SpectrumUncertainty",
                                  "Bootstrap uncertainty of sorted values (eigenvalues, modes); values closer than "
                                  "their standard errors form a cluster that shares one interval.")
      .def_property_readonly("estimate", copied(&SpectrumUncertainty::estimate), "the values, ascending")
      .def_property_readonly("standard_errors", copied(&SpectrumUncertainty::standard_errors))
      .def_property_readonly("lower", copied(&SpectrumUncertainty::lower), "the interval (the cluster's)")
      .def_property_readonly("upper", copied(&SpectrumUncertainty::upper))
      .def_property_readonly("clusters", copied(&SpectrumUncertainty::clusters), "lists of 0-based indices")
      .def_property_readonly("failed", copied(&SpectrumUncertainty::failed), "replicates without the values")
      .def(pickle_json<SpectrumUncertainty>("SpectrumUncertainty", &exact_json<SpectrumUncertainty>))
      .def("__repr__", json_repr<SpectrumUncertainty>("SpectrumUncertainty"));
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
      .def(pickle_json<Bootstrap>("Bootstrap", &exact_json<Bootstrap>))
      .def("__repr__", json_repr<Bootstrap>("Bootstrap"));

  py::class_<FitResult>(m, "FitResult", "An estimate of X in A X ~= B with its diagnostics and warnings.")
      .def_property_readonly("method", [](const FitResult& r) { return std::string(to_string(r.method)); })
      .def_property_readonly("ok", &FitResult::ok)
      .def_property_readonly("status", [](const FitResult& r) { return std::string(to_string(r.status)); },
                             "'success', 'numerical_failure', or 'not_computed' (no estimator filled it)")
      .def_property_readonly("message", copied(&FitResult::message), "why it failed ('' on success)")
      .def_property_readonly("X", copied(&FitResult::X), "the estimate (n x n ndarray; empty on failure)")
      .def_property_readonly("diagnostics", copied(&FitResult::diagnostics))
      .def_property_readonly("warnings", warning_texts(&FitResult::warnings))
      .def_property_readonly("warning_codes", warning_codes(&FitResult::warnings), "each warning's code (spdfit.outcome_codes())")
      .def_property_readonly("standard_errors", from_bootstrap(&Bootstrap::standard_errors),
                             "the bootstrap standard error of every entry of X (n x n), or None without bootstrap=N")
      .def_property_readonly("interval", from_bootstrap(&Bootstrap::interval),
                             "the bootstrap interval (level, type, lower, upper), or None")
      .def_property_readonly("bias", from_bootstrap(&Bootstrap::bias),
                             "the bootstrap bias estimate (mean of the replicates minus X), or None")
      .def_property_readonly("bootstrap", copied(&FitResult::bootstrap),
                             "the bootstrap's details (replicates, failed, seed, eigenvalues, ...), or None")
      .def_property_readonly("row_names", copied(&FitResult::row_names),
                             "names of X's rows: A's column names from its file's header (fit_files), else []")
      .def_property_readonly("column_names", copied(&FitResult::column_names),
                             "names of X's columns: B's column names from its file's header, else []")
      .def_property_readonly("a_columns", copied(&FitResult::a_columns),
                             "A and B from one file (a_cols, b_cols): the file and A's columns, "
                             "'log.csv columns acc1..acc6 (2-7)'; else ''")
      .def_property_readonly("b_columns", copied(&FitResult::b_columns), "the same for B's columns")
      .def_property_readonly(
          "offsets",
          [](const FitResult& r) -> py::object {
            if (!r.offsets) return py::none();
            py::dict out;
            out["mode"] = std::string(to_string(r.offsets->mode));
            if (r.offsets->mode == Offsets::Estimate) out["c"] = r.offsets->c;
            if (r.offsets->mode == Offsets::Rest) {
              out["a"] = r.offsets->a;
              out["b"] = r.offsets->b;
            }
            return out;
          },
          "the offsets taken out of the data with offsets='estimate' ({'mode': 'estimate', 'c': ndarray}: "
          "A X + 1 c^T ~= B) or offsets='rest' ({'mode': 'rest', 'a': ..., 'b': ...}: the rest rows' means "
          "subtracted), or None")
      .def_property_readonly(
          "robust",
          [](const FitResult& r) -> py::object {
            if (!r.robust) return py::none();
            py::dict out;
            out["method"] = std::string(to_string(r.robust->method));
            out["tuning"] = r.robust->tuning;
            out["scale"] = r.robust->scale;
            out["rows_downweighted"] = r.robust->rows_downweighted;
            out["rows_downweighted_count"] = r.robust->rows_downweighted_count;
            out["weights_min"] = r.robust->weights_min;
            out["iterations"] = r.robust->iterations;
            out["converged"] = r.robust->converged;
            return out;
          },
          "what robust='huber' or 'tukey' did: {'method', 'tuning' (the loss's constant k), 'scale' (the robust "
          "scale of the whitened residuals), 'rows_downweighted' (1-based, weight below 0.5), "
          "'rows_downweighted_count', 'weights_min', 'iterations', 'converged'}, or None")
      .def(pickle_json<FitResult>("FitResult", &exact_json<FitResult>))
      .def("__repr__", [](const FitResult& r) {
        return "FitResult(method='" + std::string(to_string(r.method)) + "', status='" + to_string(r.status) +
               "')\n" + report(r, python_report_hints());
      });


  py::class_<NearestResult>(m, "NearestResult",
                            "A repaired matrix and how it was reached (nearest_spd, nearest_correlation, nearest_covariance).")
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
      .def_property_readonly("warnings", warning_texts(&NearestResult::warnings))
      .def_property_readonly("warning_codes", warning_codes(&NearestResult::warnings), "each warning's code (spdfit.outcome_codes())")
      .def_property_readonly("method", copied(&NearestResult::method), "which method ran")
      .def_property_readonly("fixed_entries", copied(&NearestResult::fixed_entries),
                             "entries kept exactly (pairs i < j; with a free diagonal, its kept entries too)")
      .def_property_readonly("lower_bound", copied(&NearestResult::lower_bound),
                             "a proven lower bound on distance (the dual's value; rank: the convex solution's "
                             "distance); NaN where none is computed")
      .def_property_readonly("optimality_residual", copied(&NearestResult::optimality_residual),
                             "the relative KKT residual (h_weights) or stationarity residual (rank, factors); NaN "
                             "where none is computed")
      .def_property_readonly("F", copied(&NearestResult::F),
                             "rank: X = F F^T; factors: X = diag(1 - ||f_i||^2) + F F^T (n x K); empty otherwise")
      .def_property_readonly(
          "starts",
          [](const NearestResult& r) {
            py::list out;
            for (const NearestStart& s : r.starts) out.append(py::make_tuple(s.name, s.distance, s.iterations));
            return out;
          },
          "rank: (start, distance, iterations) for every start tried")
      .def("__repr__", [](const NearestResult& r) { return "NearestResult\n" + report(r); })
      .def(pickle_json<NearestResult>("NearestResult", &exact_json<NearestResult>));
}

}  // namespace spdfit::python
