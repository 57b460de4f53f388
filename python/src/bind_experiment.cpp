// spdfit.experiment: the Monte Carlo experiments of the thesis (ch. 6) and the paper (sec. IV).
// Trials run on threads with the GIL released; results do not depend on the thread count.
#include <array>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "keywords.hpp"
#include "pickle.hpp"
#include "spdfit/experiment/experiment_request.hpp"
#include "spdfit/experiment/monte_carlo.hpp"
#include "spdfit/experiment/paper.hpp"
#include "spdfit/experiment/physical.hpp"
#include "spdfit/experiment/statistics.hpp"
#include "spdfit/experiment/thesis.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/simulate.hpp"

namespace py = pybind11;

namespace spdfit::python {

using namespace spdfit::experiment;

namespace {

std::string method_name(Method m) { return std::string(to_string(m)); }

constexpr std::array<FitNoise, 3> kFitNoises = {FitNoise::None, FitNoise::True, FitNoise::Rest};

// The method a comparison names (keywords.hpp's method_from: a ValueError listing the methods).
Method named(const std::string& name) { return method_from(py::str(name)); }

// ThesisExperimentResult's options (not a Python class of their own) in its state: the simulation
// options (pickled as SimulationOptions), the truth and the methods' names.
auto thesis_options_field() {
  return state_field(
      [](const ThesisExperimentResult& r) {
        std::vector<std::string> methods;
        for (Method method : r.options.methods) methods.push_back(method_name(method));
        return py::make_tuple(r.options.simulation, r.options.truth, methods);
      },
      [](ThesisExperimentResult& r, const py::object& value) {
        const auto options = value.cast<py::tuple>();
        check_state(options, 3, "ThesisExperimentResult's options");
        r.options.simulation = options[0].cast<hexapod::SimulationOptions>();
        r.options.truth = options[1].cast<Eigen::MatrixXd>();
        r.options.methods.clear();
        for (const std::string& name : options[2].cast<std::vector<std::string>>()) {
          r.options.methods.push_back(enum_from(name, kSelectableMethods, "ThesisExperimentResult", "method"));
        }
      });
}

}  // namespace

void bind_experiment(py::module_& parent) {
  py::module_ m = parent.def_submodule("experiment", "Monte Carlo experiments of the thesis and the paper.");

  // The library's tables and defaults, so that spdfit/experiment.py does not retype them.
  py::list reported;
  for (const ThesisReportedRun& run : kThesisReportedRuns) {
    reported.append(py::make_tuple(run.experiment, run.noise_var, run.procrustes, run.tls_sym, run.spde));
  }
  m.attr("THESIS_REPORTED_RUNS") = reported;

  m.attr("SIGNIFICANCE") = kSignificance;
  py::class_<PairedComparison>(m, "PairedComparison",
                               "Two methods compared on the same trials: the differences a - b where both are "
                               "finite.")
      .def_property_readonly("count", copied(&PairedComparison::count), "trials compared")
      .def_property_readonly("mean_difference", copied(&PairedComparison::mean_difference), "mean of a - b")
      .def_property_readonly("standard_error", copied(&PairedComparison::standard_error),
                             "of mean_difference: std(a - b) / sqrt(count)")
      .def_property_readonly("fraction_lower", copied(&PairedComparison::fraction_lower),
                             "fraction of the trials with a < b")
      .def(
          "order", [](const PairedComparison& c, double significance) { return to_string(order_of(c, significance)); },
          py::arg("significance") = kSignificance,
          "'lower' when a's mean is below b's by more than `significance` standard errors of the difference, "
          "'higher' when above, 'tie' otherwise (the rule of `spdfit demo`'s statements)")
      .def(pickle_fields<PairedComparison>(
          "PairedComparison", state_field(&PairedComparison::count), state_field(&PairedComparison::mean_difference),
          state_field(&PairedComparison::standard_error), state_field(&PairedComparison::fraction_lower)))
      .def("__repr__", [](const PairedComparison& c) {
        return "PairedComparison(count=" + std::to_string(c.count) +
               ", mean_difference=" + format_number(c.mean_difference, Precision::Full) +
               ", standard_error=" + format_number(c.standard_error, Precision::Full) +
               ", fraction_lower=" + format_number(c.fraction_lower, Precision::Full) + ")";
      });

  py::class_<Summary>(m, "Summary")
      .def_property_readonly("count", copied(&Summary::count))
      .def_property_readonly("failures", copied(&Summary::failures))
      .def_property_readonly("mean", copied(&Summary::mean))
      .def_property_readonly("std", copied(&Summary::std))
      .def_property_readonly("median", copied(&Summary::median))
      .def_property_readonly("min", copied(&Summary::min))
      .def_property_readonly("max", copied(&Summary::max))
      .def_property_readonly("standard_error", &Summary::standard_error)
      .def(pickle_fields<Summary>("Summary", state_field(&Summary::count), state_field(&Summary::failures),
                                  state_field(&Summary::mean), state_field(&Summary::std),
                                  state_field(&Summary::median), state_field(&Summary::min),
                                  state_field(&Summary::max)));

  py::class_<MethodErrors>(m, "MethodErrors")
      .def_property_readonly("method", [](const MethodErrors& e) { return method_name(e.method); })
      .def_property_readonly("errors", [](const MethodErrors& e) {
        return Eigen::Map<const Eigen::VectorXd>(e.errors.data(), static_cast<Eigen::Index>(e.errors.size())).eval();
      })
      .def_property_readonly("summary", copied(&MethodErrors::summary))
      .def_property_readonly(
          "noise", [](const MethodErrors& e) { return std::string(to_string(e.noise)); },
          "the noise model the method was fitted with: none, true or rest (the option fit_noise)")
      .def(pickle_fields<MethodErrors>(
          "MethodErrors", enum_field(&MethodErrors::method, kSelectableMethods, "MethodErrors", "method"),
          state_field(&MethodErrors::errors), state_field(&MethodErrors::summary),
          enum_field(&MethodErrors::noise, kFitNoises, "MethodErrors", "noise")));

  py::class_<ThesisExperimentResult>(m, "ThesisExperimentResult")
      .def_property_readonly("trials", copied(&ThesisExperimentResult::trials))
      .def_property_readonly("seed", copied(&ThesisExperimentResult::seed))
      .def_property_readonly("methods", copied(&ThesisExperimentResult::methods))
      .def_property_readonly("truth", [](const ThesisExperimentResult& r) { return r.options.truth; })
      .def(
          "best_of",
          [](const ThesisExperimentResult& r, const std::vector<std::string>& among) {
            std::vector<Method> methods;
            for (const std::string& name : among) methods.push_back(named(name));
            return method_name(r.best_of(methods));
          },
          py::arg("among"), "The method among `among` (names) with the smallest mean error.")
      .def(
          "compare",
          [](const ThesisExperimentResult& r, const std::string& a, const std::string& b) {
            return r.compare(named(a), named(b));
          },
          py::arg("a"), py::arg("b"), "Method a against b trial by trial (PairedComparison of their errors).")
      .def(pickle_fields<ThesisExperimentResult>(
          "ThesisExperimentResult", thesis_options_field(), state_field(&ThesisExperimentResult::trials),
          state_field(&ThesisExperimentResult::seed), state_field(&ThesisExperimentResult::methods)));

  py::class_<EntryStatistics>(m, "EntryStatistics")
      .def_property_readonly("method", [](const EntryStatistics& s) { return method_name(s.method); })
      .def_property_readonly("count", copied(&EntryStatistics::count))
      .def_property_readonly("failures", copied(&EntryStatistics::failures))
      .def_property_readonly("mae", copied(&EntryStatistics::mae))
      .def_property_readonly("std", copied(&EntryStatistics::std))
      .def_property_readonly("bias", copied(&EntryStatistics::bias))
      .def_property_readonly("errors", copied(&EntryStatistics::errors))
      .def(pickle_fields<EntryStatistics>(
          "EntryStatistics", enum_field(&EntryStatistics::method, kSelectableMethods, "EntryStatistics", "method"),
          state_field(&EntryStatistics::count), state_field(&EntryStatistics::failures),
          state_field(&EntryStatistics::mae), state_field(&EntryStatistics::std), state_field(&EntryStatistics::bias),
          state_field(&EntryStatistics::errors)));

  py::class_<EntryExperimentResult>(m, "EntryExperimentResult")
      .def_property_readonly("trials", copied(&EntryExperimentResult::trials))
      .def_property_readonly("seed", copied(&EntryExperimentResult::seed))
      .def_property_readonly("truth", copied(&EntryExperimentResult::truth))
      .def_property_readonly("entries", copied(&EntryExperimentResult::entries))
      .def_property_readonly("methods", copied(&EntryExperimentResult::methods))
      .def(
          "compare",
          [](const EntryExperimentResult& r, const std::string& a, const std::string& b) {
            return r.compare(named(a), named(b));
          },
          py::arg("a"), py::arg("b"),
          "Method a against b on each entry, trial by trial: a PairedComparison of |e_a| and |e_b| per entry.")
      .def(
          "wins",
          [](const EntryExperimentResult& r, const std::string& a, const std::string& b) {
            const EntryExperimentResult::Wins wins = r.wins(named(a), named(b));
            py::dict out;
            out["mae"] = wins.mae;
            out["std"] = wins.std;
            out["entries"] = wins.entries;
            return out;
          },
          py::arg("a"), py::arg("b"),
          "{'mae': on how many entries a's mean absolute error is below b's, 'std': the same for the standard "
          "deviation of the error, 'entries': of how many}")
      .def(pickle_fields<EntryExperimentResult>(
          "EntryExperimentResult", state_field(&EntryExperimentResult::trials),
          state_field(&EntryExperimentResult::seed), state_field(&EntryExperimentResult::truth),
          state_field(&EntryExperimentResult::entries), state_field(&EntryExperimentResult::methods)));

  m.def(
      "run",
      [](const std::string& entry_name, const py::dict& options, std::optional<Eigen::MatrixXd> truth,
         std::vector<double> levels) -> py::object {
        std::vector<std::string_view> given;
        ExperimentRequest request = experiment_request_from(entry_name, options, given);
        if (truth) request.simulation.truth.values = *truth;
        request.levels = std::move(levels);
        ExperimentRun run;
        {
          py::gil_scoped_release release;
          run = run_experiment(request, given);  // as `spdfit experiment`
        }
        switch (run.kind) {
          case ExperimentKind::Thesis:
            return py::cast(*run.thesis);
          case ExperimentKind::PaperHexapod:
            return py::cast(run.entries.front());
          case ExperimentKind::Paper2x2:
            return run.sweep ? py::cast(run.entries) : py::cast(run.entries.front());
          case ExperimentKind::Physical:
            break;
        }
        return py::cast(to_json(*run.physical));
      },
      py::arg("entry"), py::arg("options"), py::arg("truth") = py::none(), py::arg("levels") = std::vector<double>{});
  m.def("paper_2x2_sweep_levels", &paper_2x2_sweep_levels);
  m.def("paper_2x2_truth", &paper_2x2_truth);
  m.def("paper_2x2_design", &paper_2x2_design);
}

}  // namespace spdfit::python
