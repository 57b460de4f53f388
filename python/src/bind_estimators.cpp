// The estimators and repairs (fit, fit_files, fit_all, nearest; their classes are bind_results.cpp's).
// The functions here never raise for a numerical failure: they return the result;
// python/spdfit/__init__.py raises NumericalError and warns.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "pickle.hpp"
#include "spdfit/area_criterion.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/nearest_correlation.hpp"
#include "spdfit/nearest_spd.hpp"
#include "spdfit/stream.hpp"

namespace py = pybind11;

namespace spdfit::python {

FitOptions options_from(const std::optional<double>& rank_tolerance, const std::optional<double>& noise_ratio,
                        std::optional<Method> method, const std::optional<int>& max_iter,
                        const std::optional<double>& min_eig, const BootstrapArgs& boot) {
  FitOptions options;
  options.bootstrap = boot.replicates;
  options.confidence = boot.confidence.value_or(options.confidence);
  options.seed = boot.seed.value_or(options.seed);
  options.threads = boot.threads;
  if (rank_tolerance) options.rank_tolerance = *rank_tolerance;
  // Each of these options applies to some methods only: a ValueError with the others.
  auto check = [&](bool given, MethodOption option, const char* spelling) {
    if (!given || !method) return;
    if (const auto why = misplaced_option(option, *method, spelling)) throw std::invalid_argument(*why);
  };
  check(noise_ratio.has_value(), MethodOption::NoiseRatio, "noise_ratio");
  check(max_iter.has_value(), MethodOption::MaxIterations, "max_iter");
  check(min_eig.has_value(), MethodOption::MinEig, "min_eig");
  options.noise_ratio = noise_ratio.value_or(options.noise_ratio);
  options.max_iterations = max_iter.value_or(options.max_iterations);
  options.min_eig = min_eig.value_or(options.min_eig);
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument(error);
  return options;
}

Method method_from(const std::string& name) {
  if (const auto method = parse_method(name)) return *method;
  std::string known;
  for (Method m : kSelectableMethods) known += (known.empty() ? "" : ", ") + std::string(to_string(m));
  throw std::invalid_argument("unknown method '" + name + "' (methods: " + known + ")");
}

namespace {

// StreamOptions' read options (not a Python class of their own) in its state: allow_nonfinite and
// the index column as read_table's index_col spells it (None: decided from the file, True: drop,
// False: keep).
auto stream_read_field() {
  return state_field(
      [](const StreamOptions& o) {
        const io::IndexColumn index = o.read.index_column;
        const py::object index_col = index == io::IndexColumn::kAuto ? py::object(py::none())
                                                                     : py::bool_(index == io::IndexColumn::kDrop);
        return py::make_tuple(o.read.allow_nonfinite, index_col);
      },
      [](StreamOptions& o, const py::object& value) {
        const auto read = value.cast<py::tuple>();
        check_state(read, 2, "StreamOptions' read options");
        o.read.allow_nonfinite = read[0].cast<bool>();
        const auto index_col = read[1].cast<std::optional<bool>>();
        o.read.index_column = !index_col ? io::IndexColumn::kAuto : *index_col ? io::IndexColumn::kDrop
                                                                               : io::IndexColumn::kKeep;
      });
}

}  // namespace

void bind_estimators(py::module_& m) {
  py::list names;
  for (Method method : kSelectableMethods) names.append(std::string(to_string(method)));
  m.attr("METHODS") = py::tuple(names);

  m.def(
      "fit",
      [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const std::string& method,
         std::optional<double> rank_tolerance, std::optional<double> noise_ratio, std::optional<int> max_iter,
         std::optional<double> min_eig, int bootstrap, std::optional<double> confidence,
         std::optional<std::uint64_t> seed, unsigned threads, bool reported_diagnostics) {
        const Method chosen = method_from(method);
        FitOptions options = options_from(rank_tolerance, noise_ratio, chosen, max_iter, min_eig,
                                          BootstrapArgs{bootstrap, confidence, seed, threads});
        options.reported_diagnostics = reported_diagnostics;
        py::gil_scoped_release release;
        return fit(A, B, chosen, options);
      },
      py::arg("A"), py::arg("B"), py::arg("method"), py::arg("rank_tolerance") = py::none(),
      py::arg("noise_ratio") = py::none(), py::arg("max_iter") = py::none(), py::arg("min_eig") = py::none(),
      py::arg("bootstrap") = 0, py::arg("confidence") = py::none(), py::arg("seed") = py::none(),
      py::arg("threads") = 0u, py::arg("reported_diagnostics") = true);
  py::class_<StreamOptions>(m, "StreamOptions",
                            "How fit_files streams its files; the defaults are the library's own.")
      .def(py::init<>())
      .def_readwrite("block_rows", &StreamOptions::block_rows, "rows per block")
      .def_readwrite("threads", &StreamOptions::threads, "threads; 0 means one per core")
      .def(pickle_fields<StreamOptions>("StreamOptions", state_field(&StreamOptions::block_rows),
                                        state_field(&StreamOptions::threads), stream_read_field()));
  m.def(
      "fit_files",
      [](const std::string& a_path, const std::string& b_path, const std::string& method, Eigen::Index block_rows,
         unsigned threads, std::optional<double> rank_tolerance, std::optional<double> noise_ratio,
         std::optional<int> max_iter, std::optional<double> min_eig, int bootstrap,
         std::optional<double> confidence, std::optional<std::uint64_t> seed, bool reported_diagnostics) {
        const Method chosen = method_from(method);
        FitOptions options = options_from(rank_tolerance, noise_ratio, chosen, max_iter, min_eig,
                                          BootstrapArgs{bootstrap, confidence, seed, threads});
        options.reported_diagnostics = reported_diagnostics;
        StreamOptions stream;
        stream.block_rows = block_rows;
        stream.threads = threads;
        py::gil_scoped_release release;
        return fit_files(a_path, b_path, chosen, options, stream);
      },
      py::arg("A_path"), py::arg("B_path"), py::arg("method"), py::arg("block_rows") = StreamOptions{}.block_rows,
      py::arg("threads") = StreamOptions{}.threads, py::arg("rank_tolerance") = py::none(),
      py::arg("noise_ratio") = py::none(), py::arg("max_iter") = py::none(), py::arg("min_eig") = py::none(),
      py::arg("bootstrap") = 0, py::arg("confidence") = py::none(), py::arg("seed") = py::none(),
      py::arg("reported_diagnostics") = true);
  m.def(
      "fit_all",
      [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, std::optional<double> rank_tolerance,
         std::optional<double> noise_ratio, std::optional<int> max_iter, std::optional<double> min_eig,
         bool reported_diagnostics) {
        FitOptions options = options_from(rank_tolerance, noise_ratio, std::nullopt, max_iter, min_eig);
        options.reported_diagnostics = reported_diagnostics;
        py::gil_scoped_release release;
        return fit_all(A, B, options);
      },
      py::arg("A"), py::arg("B"), py::arg("rank_tolerance") = py::none(), py::arg("noise_ratio") = py::none(),
      py::arg("max_iter") = py::none(), py::arg("min_eig") = py::none(), py::arg("reported_diagnostics") = true);

  // "via_corr"; the floor by EigenvalueFloor::chosen, as the nearest command's.
  m.def(
      "nearest",
      [](const Eigen::MatrixXd& C, const std::string& kind, std::optional<double> min_eig,
         std::optional<double> min_eig_rel, std::optional<double> alpha, std::optional<Eigen::VectorXd> weights,
         std::optional<int> max_iter, std::optional<double> tol) {
        const EigenvalueFloor floor = EigenvalueFloor::chosen(min_eig, min_eig_rel, alpha.has_value());
        if (kind == "spd") {
          for (const auto& [given, name] : {std::pair{bool(weights), "weights"}, std::pair{bool(alpha), "alpha"},
                                            std::pair{bool(max_iter), "max_iter"}, std::pair{bool(tol), "tol"}}) {
            if (given) throw std::invalid_argument(std::string(name) + " needs keep_diag=True or via_corr=True");
          }
          py::gil_scoped_release release;
          return nearest_spd(C, floor);
        }
        NearestCorrelationOptions options;
        options.floor = floor;
        if (weights) options.weights = *weights;
        options.alpha = alpha.value_or(options.alpha);
        options.max_iterations = max_iter.value_or(options.max_iterations);
        options.tolerance = tol.value_or(options.tolerance);
        if (kind != "corr" && kind != "keep_diag" && kind != "via_corr") {
          throw std::invalid_argument("unknown repair '" + kind + "'");
        }
        py::gil_scoped_release release;
        return kind == "corr"        ? nearest_correlation(C, options)
               : kind == "keep_diag" ? nearest_keep_diagonal(C, options)
                                     : nearest_via_correlation(C, options);
      },
      py::arg("C"), py::arg("kind"), py::arg("min_eig") = py::none(), py::arg("min_eig_rel") = py::none(),
      py::arg("alpha") = py::none(), py::arg("weights") = py::none(), py::arg("max_iter") = py::none(),
      py::arg("tol") = py::none());

  m.def(
      "area_criterion",
      [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& X) {
        return area_criterion(A, B, X);
      },
      py::arg("A"), py::arg("B"), py::arg("X"), py::call_guard<py::gil_scoped_release>());
}

}  // namespace spdfit::python
