// The experiments' option tables and the options each experiment is run with.
#include "spdfit/experiment/experiment_request.hpp"

#include <cmath>
#include <deque>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

#include "interface/option_builders.hpp"

namespace spdfit::experiment {

namespace {

using ExperimentSpec = OptionSpec<ExperimentRequest>;

constexpr double kExperimentInfinity = std::numeric_limits<double>::infinity();

ExperimentSpec experiment_entry(std::string_view name, std::string_view cli, OptionType type,
                                std::string_view value_name, std::string_view help,
                                std::string_view default_text = {}) {
  return spdfit::detail::option_entry<ExperimentRequest>(name, cli, name, type, value_name, help, default_text);
}

// Text built when a table is (a default list of methods), kept for the program's life: a table's
// entries hold string_views.
std::string_view kept_text(std::string text) {
  static std::mutex mutex;
  static std::deque<std::string> kept;
  const std::lock_guard<std::mutex> lock(mutex);
  kept.push_back(std::move(text));
  return kept.back();
}

// `names` joined by `separator`.
template <typename Names>
std::string joined(const Names& names, std::string_view separator) {
  std::string out;
  for (const auto& name : names) {
    if (!out.empty()) out += separator;
    out += std::string(name);
  }
  return out;
}

std::vector<std::string> method_names(const std::vector<Method>& methods) {
  std::vector<std::string> names;
  for (Method m : methods) names.emplace_back(to_string(m));
  return names;
}

// The comma-separated items of `text`, spaces around each dropped.
std::vector<std::string> list_items(const std::string& text) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    std::string item = text.substr(start, end - start);
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    items.push_back(item);
    start = end + 1;
  }
  return items;
}

// The methods of a `methods` list (kSelectableMethods); `defaults` when it is empty. OptionError
// for an unknown name or a repeat.
std::vector<Method> listed_methods(const std::string& text, const std::vector<Method>& defaults) {
  if (text.empty()) return defaults;
  std::vector<Method> methods;
  for (const std::string& name : list_items(text)) {
    const std::optional<Method> method = parse_method(name);  // the selectable methods only
    if (!method) {
      throw OptionError("`methods`: " + name + " is not one of " + joined(method_names(
                            {kSelectableMethods.begin(), kSelectableMethods.end()}), ", "),
                        Code::OptionValue, "methods");
    }
    for (Method earlier : methods) {
      if (earlier == *method) throw OptionError("`methods`: " + name + " is listed twice", Code::OptionValue, "methods");
    }
    methods.push_back(*method);
  }
  return methods;
}

// The noise models of a `fit_noise` list; none when it is empty.
std::vector<FitNoise> listed_noise_models(const std::string& text) {
  if (text.empty()) return {FitNoise::None};
  std::vector<FitNoise> models;
  for (const std::string& name : list_items(text)) {
    const std::optional<FitNoise> noise = parse_fit_noise(name);
    if (!noise) {
      throw OptionError("`fit_noise`: " + name + " is not one of none, true, rest", Code::OptionValue, "fit_noise");
    }
    for (FitNoise earlier : models) {
      if (earlier == *noise) {
        throw OptionError("`fit_noise`: " + name + " is listed twice", Code::OptionValue, "fit_noise");
      }
    }
    models.push_back(*noise);
  }
  return models;
}

// The generator's message with its fields' names (noise_std_a, ...) as option names (`noise_std_a`).
std::string generator_message(std::string message) {
  for (const std::string field : {"noise_std_a", "noise_std_b", "force_noise_var", "noise_var", "signal_var",
                                  "rest_samples", "scale_b", "samples"}) {
    for (std::size_t at = message.find(field); at != std::string::npos; at = message.find(field, at + field.size() + 2)) {
      const bool inside = (at > 0 && (message[at - 1] == '_' || message[at - 1] == '`')) ||
                          (at + field.size() < message.size() && message[at + field.size()] == '_');
      if (inside) continue;
      message.replace(at, field.size(), "`" + field + "`");
    }
  }
  return message;
}

// The generator's options of a request, checked: OptionError naming the option.
hexapod::SimulationOptions simulation_of(const ExperimentRequest& request) {
  hexapod::SimulationOptions options = request.simulation.options;
  if (options.noise_std_a) options.noise_var = 0.0;  // the per-sensor deviations instead
  std::string error;
  if (!options.is_valid(&error)) throw OptionError(generator_message(error), Code::OptionValue);
  return options;
}

// The simulate table's entries `names`, as options of an experiment (its request's generator).
std::vector<ExperimentSpec> generator_entries(const std::vector<std::string_view>& names) {
  std::vector<ExperimentSpec> out;
  for (std::string_view name : names) {
    for (ExperimentSpec& spec : lifted_options(hexapod::simulate_option_table(), &ExperimentRequest::simulation, {name})) {
      out.push_back(std::move(spec));
    }
  }
  return out;
}

void add_generator(std::vector<ExperimentSpec>& table, ExperimentKind kind) {
  for (ExperimentSpec& spec : generator_entries({"noise_var", "force_noise_var", "samples", "signal_var",
                                                 "distribution", "noise_std_a", "noise_std_b", "rest_samples",
                                                 "scale_b"})) {
    if (spec.name == "noise_var") {
      spec.help = "Variance V of the noise in every entry of A and B (thesis: 0.082, 0.86, 1.28)";
      if (kind == ExperimentKind::PaperHexapod) spec.default_text = "0.86";
    } else if (spec.name == "samples") {
      spec.range = {6.0, 1e8};
    }
    table.push_back(std::move(spec));
  }
}

// trials, seed, threads, json, csv (unless `csv_help` is empty), output and methods.
void add_common(std::vector<ExperimentSpec>& table, std::string_view default_trials, std::string_view methods_help,
                std::string_view csv_help) {
  using spdfit::detail::integer_entry;
  table.push_back(integer_entry("trials", "--trials", "trials", "Number of Monte Carlo trials", default_trials,
                                {1.0, 1e8}, &ExperimentRequest::trials));
  table.push_back(integer_entry("seed", "--seed", "seed",
                                "Seed: the same seed gives the same numbers on any number of threads", "1",
                                {0.0, double(std::numeric_limits<std::int64_t>::max())}, &ExperimentRequest::seed));
  table.push_back(integer_entry("threads", "--threads", "threads",
                                "Worker threads (0: one per core); the numbers do not depend on it", "0",
                                {0.0, 1024.0}, &ExperimentRequest::threads));

  for (ExperimentSpec& spec :
       output_options(&ExperimentRequest::output, {"json"}, {"Print the results as JSON"})) {
    table.push_back(std::move(spec));
  }
  if (!csv_help.empty()) {
    ExperimentSpec csv = experiment_entry("csv", "--csv", OptionType::File, "FILE", csv_help);
    csv.python = "";
    csv.set = [](ExperimentRequest& r, const OptionValue& v) { r.csv = std::get<std::string>(v); };
    table.push_back(csv);
  }
  for (ExperimentSpec& spec : output_options(&ExperimentRequest::output, {"output"})) table.push_back(std::move(spec));

  ExperimentSpec methods = experiment_entry("methods", "--methods", OptionType::Names, "M,M,...", methods_help);
  methods.set = [](ExperimentRequest& r, const OptionValue& v) { r.methods = std::get<std::string>(v); };
  table.push_back(methods);
}

std::string_view methods_help(const std::vector<Method>& defaults) {
  return kept_text("Comma-separated methods to run, of " +
                   joined(method_names({kSelectableMethods.begin(), kSelectableMethods.end()}), ", ") +
                   " (default: " + joined(method_names(defaults), ",") + ")");
}

std::vector<ExperimentSpec> make_thesis_table() {
  std::vector<ExperimentSpec> table;
  add_generator(table, ExperimentKind::Thesis);
  add_common(table, "1000", methods_help(ThesisExperimentOptions{}.methods),
             "Also write each trial's error ||M_p - M_hat||_F per method to FILE (one row per trial)");
  ExperimentSpec noise = experiment_entry(
      "fit_noise", "--fit-noise", OptionType::Names, "MODEL,...",
      "Comma-separated noise models to fit every method with, each in turn: none (equal noise assumed), true "
      "(the generator's covariances), rest (the covariances of the trial's `rest_samples` rows); spde runs with "
      "none only",
      "none");
  noise.set = [](ExperimentRequest& r, const OptionValue& v) { r.fit_noise = std::get<std::string>(v); };
  table.push_back(noise);
  return table;
}

std::vector<ExperimentSpec> make_paper_hexapod_table() {
  std::vector<ExperimentSpec> table;
  add_generator(table, ExperimentKind::PaperHexapod);
  add_common(table, "100", methods_help(PaperHexapodOptions{}.methods),
             "Also write method,entry,true,mae,std,bias to FILE");
  return table;
}

std::vector<ExperimentSpec> make_paper_2x2_table() {
  std::vector<ExperimentSpec> table;
  ExperimentSpec std_a = experiment_entry("std_a", "--std-a", OptionType::Real, "S",
                                          "Standard deviation of the noise in A (or `sweep`)");
  std_a.range = {0.0, kExperimentInfinity};
  std_a.set = [](ExperimentRequest& r, const OptionValue& v) { r.std_a = std::get<double>(v); };
  table.push_back(std_a);
  ExperimentSpec std_b = experiment_entry("std_b", "--std-b", OptionType::Real, "S",
                                          "Standard deviation of the noise in B", "1");
  std_b.range = {0.0, kExperimentInfinity};
  std_b.nullable = false;
  std_b.set = [](ExperimentRequest& r, const OptionValue& v) { r.std_b = std::get<double>(v); };
  std_b.get = [](const ExperimentRequest& r) -> std::optional<OptionValue> { return r.std_b; };
  table.push_back(std_b);
  ExperimentSpec sweep = experiment_entry(
      "sweep", "--sweep", OptionType::Flag, "",
      "Run std_a = 0, 0.1, ..., 1.9 (Figure 3) and print the table as CSV (with `csv` FILE: write it there and print "
      "a readable table)");
  sweep.excludes = {"std_a"};
  sweep.set = [](ExperimentRequest& r, const OptionValue& v) { r.sweep = std::get<bool>(v); };
  sweep.get = [](const ExperimentRequest& r) -> std::optional<OptionValue> { return r.sweep; };
  table.push_back(sweep);
  add_common(table, "10000", methods_help(Paper2x2Options{}.methods),
             "Also write method,entry,true,mae,std,bias to FILE (with `sweep`: the sweep's table)");
  return table;
}

std::vector<ExperimentSpec> make_physical_table() {
  std::vector<ExperimentSpec> table;
  ExperimentSpec samples = experiment_entry("samples", "--samples", OptionType::RealList, "M,M,...",
                                            "Comma-separated numbers of samples m", "12,30,100,1000");
  samples.range = {6.0, 1e8};
  samples.set = [](ExperimentRequest& r, const OptionValue& v) {
    r.samples.clear();
    for (double m : std::get<std::vector<double>>(v)) {
      if (m != std::floor(m)) {
        throw OptionError("`samples`: " + value_text(m) + " is not a whole number", Code::OptionValue, "samples");
      }
      r.samples.push_back(Eigen::Index(m));
    }
  };
  table.push_back(samples);
  for (ExperimentSpec& spec : generator_entries({"noise_var", "force_noise_var", "distribution", "geometry",
                                                 "payload_mass", "payload_com", "payload_inertia"})) {
    if (spec.name == "noise_var") {
      spec.help = "Variance of the noise in every entry of A and B";
      spec.default_text = "3.2^2/12: uniform of width 3.2";
    } else if (spec.name == "geometry") {
      spec.help = "Hexapod geometry file";
      spec.default_text = "the built-in cubic hexapod";
      spec.excludes.clear();
    } else if (spec.name.substr(0, 8) == "payload_") {
      spec.needs.clear();  // the built-in hexapod's payload otherwise
      spec.needs_message = {};
    }
    table.push_back(std::move(spec));
  }
  std::vector<std::string> generic = method_names({kSelectableMethods.begin(), kSelectableMethods.end()});
  const PhysicalExperimentOptions defaults;
  std::vector<std::string> shown = method_names(defaults.methods);
  shown.insert(shown.end(), defaults.variants.begin(), defaults.variants.end());
  add_common(table, "200",
             kept_text("Comma-separated estimators: generic methods (" + joined(generic, ", ") +
                       ") and physical variants (" + joined(physical_variant_names(), ", ") +
                       ", with :common or :each to estimate the strut masses) (default: " + joined(shown, ",") + ")"),
             {});
  return table;
}

}  // namespace

std::string_view to_string(ExperimentKind kind) {
  switch (kind) {
    case ExperimentKind::Thesis:
      return "thesis";
    case ExperimentKind::PaperHexapod:
      return "paper-hexapod";
    case ExperimentKind::Paper2x2:
      return "paper-2x2";
    case ExperimentKind::Physical:
      return "physical";
  }
  return "unknown";
}

ExperimentRequest experiment_request(ExperimentKind kind) {
  ExperimentRequest request;
  request.kind = kind;
  switch (kind) {
    case ExperimentKind::Thesis:
      request.trials = 1000;
      break;
    case ExperimentKind::PaperHexapod:
      request.trials = 100;
      request.simulation.options = PaperHexapodOptions::default_simulation();
      request.simulation.noise_given = true;
      break;
    case ExperimentKind::Paper2x2:
      request.trials = 10000;
      break;
    case ExperimentKind::Physical:
      request.trials = 200;
      request.simulation.options = PhysicalExperimentOptions{}.simulation;
      request.simulation.noise_given = true;
      break;
  }
  return request;
}

const std::vector<OptionSpec<ExperimentRequest>>& experiment_option_table(ExperimentKind kind) {
  static const std::vector<ExperimentSpec> thesis = make_thesis_table();
  static const std::vector<ExperimentSpec> paper_hexapod = make_paper_hexapod_table();
  static const std::vector<ExperimentSpec> paper_2x2 = make_paper_2x2_table();
  static const std::vector<ExperimentSpec> physical = make_physical_table();
  switch (kind) {
    case ExperimentKind::Thesis:
      return thesis;
    case ExperimentKind::PaperHexapod:
      return paper_hexapod;
    case ExperimentKind::Paper2x2:
      return paper_2x2;
    case ExperimentKind::Physical:
      break;
  }
  return physical;
}

void check_experiment_request(const ExperimentRequest& request, const std::vector<std::string_view>& given) {
  check_option_combination(experiment_option_table(request.kind), given);
  switch (request.kind) {
    case ExperimentKind::Thesis: {
      if (!request.simulation.noise_given) {
        throw OptionError("give the noise: `noise_var` V, or `noise_std_a` S and `noise_std_b` S", Code::OptionConflict,
                          "noise_var");
      }
      listed_methods(request.methods, {});
      const std::vector<FitNoise> models = listed_noise_models(request.fit_noise);
      for (FitNoise model : models) {
        if (model == FitNoise::Rest && request.simulation.options.rest_samples < 2) {
          throw OptionError("`fit_noise` rest needs `rest_samples` N (N >= 2): the rows recorded at rest",
                            Code::OptionConflict, "fit_noise");
        }
      }
      break;
    }
    case ExperimentKind::PaperHexapod:
      listed_methods(request.methods, {});
      break;
    case ExperimentKind::Paper2x2:
      if (!request.sweep && !request.std_a) {
        throw OptionError("experiment paper-2x2: give `std_a` VA, or `sweep`", Code::OptionConflict, "std_a");
      }
      listed_methods(request.methods, {});
      break;
    case ExperimentKind::Physical:
      break;  // its methods and the rest in physical_options, with the geometry
  }
}

MonteCarloOptions monte_carlo_options(const ExperimentRequest& request) {
  MonteCarloOptions options;
  options.trials = request.trials;
  options.seed = request.seed;
  options.threads = request.threads;
  return options;
}

ThesisExperimentOptions thesis_options(const ExperimentRequest& request) {
  ThesisExperimentOptions options;
  options.simulation = simulation_of(request);
  options.methods = listed_methods(request.methods, options.methods);
  options.noise_models = listed_noise_models(request.fit_noise);
  if (request.simulation.truth.values.size() > 0) options.truth = request.simulation.truth.values;
  return options;
}

PaperHexapodOptions paper_hexapod_options(const ExperimentRequest& request) {
  PaperHexapodOptions options;
  options.simulation = simulation_of(request);
  options.methods = listed_methods(request.methods, options.methods);
  return options;
}

Paper2x2Options paper_2x2_options(const ExperimentRequest& request) {
  Paper2x2Options options;
  options.std_a = request.std_a.value_or(0.0);
  options.std_b = request.std_b;
  options.methods = listed_methods(request.methods, options.methods);
  return options;
}

PhysicalExperimentOptions physical_options(const ExperimentRequest& request) {
  PhysicalExperimentOptions options;
  if (!request.samples.empty()) options.samples = request.samples;
  options.simulation.noise_var = request.simulation.options.noise_var;
  options.simulation.force_noise_var = request.simulation.options.force_noise_var;
  options.simulation.distribution = request.simulation.options.distribution;
  const GeometryInput& geometry = request.simulation.geometry;
  if (geometry.given()) options.geometry = geometry.value ? *geometry.value : hexapod::read_geometry(geometry.path);
  if (request.simulation.payload.given()) {
    options.payload = hexapod::payload_with(options.geometry ? *options.geometry : hexapod::cubic_geometry(),
                                            request.simulation.payload);
  }
  if (!request.methods.empty()) {
    try {
      set_estimators(options, list_items(request.methods));
    } catch (const std::invalid_argument& e) {
      throw OptionError(std::string("`methods`: ") + e.what(), Code::OptionValue, "methods");
    }
  }
  std::string error;
  if (!options.is_valid(&error)) throw OptionError("experiment physical: " + error, Code::OptionValue);
  return options;
}

ExperimentRun run_experiment(const ExperimentRequest& request, const std::vector<std::string_view>& given,
                             const std::function<void(std::size_t, std::size_t)>& progress) {
  check_experiment_request(request, given);
  MonteCarloOptions monte_carlo = monte_carlo_options(request);
  monte_carlo.progress = progress;
  ExperimentRun run;
  run.kind = request.kind;
  run.trials = request.trials;
  run.seed = request.seed;
  switch (request.kind) {
    case ExperimentKind::Thesis:
      run.thesis = run_thesis_experiment(thesis_options(request), monte_carlo);
      break;
    case ExperimentKind::PaperHexapod:
      run.paper_hexapod = paper_hexapod_options(request);
      run.entries.push_back(run_paper_hexapod(run.paper_hexapod, monte_carlo));
      break;
    case ExperimentKind::Paper2x2:
      run.paper_2x2 = paper_2x2_options(request);
      run.sweep = request.sweep;
      if (run.sweep) {
        run.levels = request.levels.empty() ? paper_2x2_sweep_levels() : request.levels;
        run.entries = run_paper_2x2_sweep(run.paper_2x2, run.levels, monte_carlo);
      } else {
        run.entries.push_back(run_paper_2x2(run.paper_2x2, monte_carlo));
      }
      break;
    case ExperimentKind::Physical:
      run.physical = run_physical_experiment(physical_options(request), monte_carlo);
      break;
  }
  return run;
}

}  // namespace spdfit::experiment
