// spdfit.experiment: the Monte Carlo experiments of the thesis (ch. 6) and the paper (sec. IV).
// Trials run on threads with the GIL released; results do not depend on the thread count.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "keywords.hpp"
#include "pickle.hpp"
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

MonteCarloOptions monte_carlo(std::size_t trials, std::uint64_t seed, unsigned threads) {
  MonteCarloOptions options;
  options.trials = trials;
  options.seed = seed;
  options.threads = threads;
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument(error);
  return options;
}

hexapod::SimulationOptions simulation(Eigen::Index samples, double noise_var, std::optional<double> force_noise_var,
                                      double signal_var, const std::string& distribution) {
  hexapod::SimulationOptions options;
  options.samples = samples;
  options.signal_var = signal_var;
  options.noise_var = noise_var;
  options.force_noise_var = force_noise_var;
  const auto parsed = hexapod::parse_noise_distribution(distribution);
  if (!parsed) throw std::invalid_argument("distribution must be 'uniform' or 'gaussian', got '" + distribution + "'");
  options.distribution = *parsed;
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument(error);
  return options;
}

std::string method_name(Method m) { return std::string(to_string(m)); }

// The method a comparison names (keywords.hpp's method_from: a ValueError listing the methods).
Method named(const std::string& name) { return method_from(py::str(name)); }

// The methods named (ValueError for an unknown name), or `defaults` when none are given; the
// library refuses an empty list or a repeat (experiment::check_methods).
std::vector<Method> methods_from(const std::optional<std::vector<std::string>>& names, std::vector<Method> defaults) {
  if (!names) return defaults;
  std::vector<Method> methods;
  for (const std::string& name : *names) {
    const auto method = parse_method(name);
    if (!method) throw std::invalid_argument("unknown method '" + name + "'");
    methods.push_back(*method);
  }
  return methods;
}

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
  const hexapod::SimulationOptions thesis_simulation;
  const hexapod::SimulationOptions paper_simulation = PaperHexapodOptions::default_simulation();
  py::dict defaults;
  defaults["samples"] = thesis_simulation.samples;
  defaults["signal_var"] = thesis_simulation.signal_var;
  defaults["distribution"] = std::string(hexapod::to_string(thesis_simulation.distribution));
  defaults["paper_hexapod_noise_var"] = paper_simulation.noise_var;
  defaults["paper_hexapod_samples"] = paper_simulation.samples;
  defaults["paper_2x2_std_b"] = Paper2x2Options{}.std_b;
  m.attr("DEFAULTS") = defaults;

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
      .def(pickle_fields<MethodErrors>(
          "MethodErrors", enum_field(&MethodErrors::method, kSelectableMethods, "MethodErrors", "method"),
          state_field(&MethodErrors::errors), state_field(&MethodErrors::summary)));

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
      "thesis",
      [](double noise_var, Eigen::Index samples, std::size_t trials, std::uint64_t seed, unsigned threads,
         std::optional<double> force_noise_var, double signal_var, const std::string& distribution,
         std::optional<Eigen::MatrixXd> truth, std::optional<std::vector<std::string>> methods) {
        ThesisExperimentOptions options;
        options.simulation = simulation(samples, noise_var, force_noise_var, signal_var, distribution);
        if (truth) options.truth = *truth;
        options.methods = methods_from(methods, options.methods);
        const MonteCarloOptions mc = monte_carlo(trials, seed, threads);
        py::gil_scoped_release release;
        return run_thesis_experiment(options, mc);
      },
      py::arg("noise_var"), py::arg("samples"), py::arg("trials"), py::arg("seed"), py::arg("threads"),
      py::arg("force_noise_var"), py::arg("signal_var"), py::arg("distribution"), py::arg("truth"),
      py::arg("methods") = py::none());

  m.def(
      "paper_hexapod",
      [](double noise_var, Eigen::Index samples, std::size_t trials, std::uint64_t seed, unsigned threads,
         std::optional<std::vector<std::string>> methods) {
        PaperHexapodOptions options;
        options.simulation.samples = samples;
        options.simulation.noise_var = noise_var;
        options.methods = methods_from(methods, options.methods);
        const MonteCarloOptions mc = monte_carlo(trials, seed, threads);
        py::gil_scoped_release release;
        return run_paper_hexapod(options, mc);
      },
      py::arg("noise_var"), py::arg("samples"), py::arg("trials"), py::arg("seed"), py::arg("threads"),
      py::arg("methods") = py::none());

  m.def(
      "paper_2x2",
      [](double std_a, double std_b, std::size_t trials, std::uint64_t seed, unsigned threads,
         std::optional<std::vector<std::string>> methods) {
        Paper2x2Options options;
        options.std_a = std_a;
        options.std_b = std_b;
        options.methods = methods_from(methods, options.methods);
        const MonteCarloOptions mc = monte_carlo(trials, seed, threads);
        py::gil_scoped_release release;
        return run_paper_2x2(options, mc);
      },
      py::arg("std_a"), py::arg("std_b"), py::arg("trials"), py::arg("seed"), py::arg("threads"),
      py::arg("methods") = py::none());

  m.def(
      "paper_2x2_sweep",
      [](std::vector<double> levels, double std_b, std::size_t trials, std::uint64_t seed, unsigned threads,
         std::optional<std::vector<std::string>> methods) {
        Paper2x2Options options;
        options.std_b = std_b;
        options.methods = methods_from(methods, options.methods);
        if (levels.empty()) levels = paper_2x2_sweep_levels();
        const MonteCarloOptions mc = monte_carlo(trials, seed, threads);
        py::gil_scoped_release release;
        return run_paper_2x2_sweep(options, levels, mc);
      },
      py::arg("levels"), py::arg("std_b"), py::arg("trials"), py::arg("seed"), py::arg("threads"),
      py::arg("methods") = py::none());
  m.def("paper_2x2_sweep_levels", &paper_2x2_sweep_levels);
  m.def("paper_2x2_truth", &paper_2x2_truth);
  m.def("paper_2x2_design", &paper_2x2_design);
  m.def(
      "physical",
      [](std::optional<std::vector<Eigen::Index>> samples, std::optional<double> noise_var,
         std::size_t trials, std::uint64_t seed, unsigned threads,
         std::optional<std::vector<std::string>> methods) {
        PhysicalExperimentOptions options;
        if (samples) options.samples = *samples;
        if (noise_var) options.simulation.noise_var = *noise_var;
        if (methods) set_estimators(options, *methods);
        std::string error;
        if (!options.is_valid(&error)) throw std::invalid_argument(error);
        const MonteCarloOptions mc = monte_carlo(trials, seed, threads);
        std::string text;
        {
          py::gil_scoped_release release;
          text = to_json(run_physical_experiment(options, mc));
        }
        return text;
      },
      py::arg("samples"), py::arg("noise_var"), py::arg("trials"), py::arg("seed"), py::arg("threads"),
      py::arg("methods"));
}

}  // namespace spdfit::python
