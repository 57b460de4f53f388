// The estimators and repairs (fit, fit_files, fit_all, nearest; their classes are bind_results.cpp's).
// The functions here never raise for a numerical failure: they return the result;
// python/spdfit/__init__.py raises NumericalError and warns.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "keywords.hpp"
#include "pickle.hpp"
#include "spdfit/area_criterion.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/fit_request.hpp"
#include "spdfit/nearest_request.hpp"
#include "spdfit/stream.hpp"

namespace py = pybind11;

namespace spdfit::python {

namespace {

// StreamOptions' read options (not a Python class of their own) in its state: allow_nonfinite and
// the index column as read_table's index_col spells it (None: decided from the file, True: drop,
// False: keep).
auto stream_read_field() {
  return state_field(
      [](const StreamOptions& o) {
        const io::IndexColumn index = o.read.index_column;
        const py::object index_col = index == io::IndexColumn::Auto ? py::object(py::none())
                                                                     : py::bool_(index == io::IndexColumn::Drop);
        return py::make_tuple(o.read.allow_nonfinite, index_col);
      },
      [](StreamOptions& o, const py::object& value) {
        const auto read = value.cast<py::tuple>();
        check_state(read, 2, "StreamOptions' read options");
        o.read.allow_nonfinite = read[0].cast<bool>();
        const auto index_col = read[1].cast<std::optional<bool>>();
        o.read.index_column = !index_col ? io::IndexColumn::Auto : *index_col ? io::IndexColumn::Drop
                                                                               : io::IndexColumn::Keep;
      });
}

// A pandas DataFrame's labels for a result (fit, fit_all): X's row names (A's columns), its column
// names (B's) and, when A and B came from one table, the columns each came from; None: none.
using Labels = std::optional<std::tuple<std::vector<std::string>, std::vector<std::string>, std::string, std::string>>;

FitResult labelled(FitResult result, const Labels& labels) {
  if (labels) std::tie(result.row_names, result.column_names, result.a_columns, result.b_columns) = *labels;
  return result;
}

}  // namespace

void bind_estimators(py::module_& m) {
  py::list names;
  for (Method method : kSelectableMethods) names.append(std::string(to_string(method)));
  m.attr("METHODS") = py::tuple(names);

  // Every function below takes its options as one dict of keyword arguments, bound by name
  // through the library's option tables (keywords.hpp).
  m.attr("KEYWORDS") = keyword_table();
  m.def(
      "spell_options", [](const std::string& message) { return spell_options(message, Frontend::Python); },
      py::arg("message"), "A library message (a warning) with its options named as Python names them.");
  m.def(
      "fit",
      [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const py::handle& method, const py::dict& options,
         const Labels& labels) {
        std::vector<std::string_view> given;
        FitRequest base;
        base.method = method_from(method);
        const FitRequest request = fit_request("fit", options, base, given);
        check_fit_request(request, given);
        py::gil_scoped_release release;
        return labelled(fit(A, B, request.method, request.options), labels);
      },
      py::arg("A"), py::arg("B"), py::arg("method"), py::arg("options"), py::arg("labels") = py::none());
  py::class_<StreamOptions>(m, "StreamOptions",
                            "How fit_files streams its files; the defaults are the library's own.")
      .def(py::init<>())
      .def_readwrite("block_rows", &StreamOptions::block_rows, "rows per block")
      .def_readwrite("threads", &StreamOptions::threads, "threads; 0 means one per core")
      .def(pickle_fields<StreamOptions>("StreamOptions", state_field(&StreamOptions::block_rows),
                                        state_field(&StreamOptions::threads), stream_read_field()));
  m.def(
      "fit_files",
      [](const std::string& a_path, const std::string& b_path, const py::handle& method, const py::dict& options) {
        std::vector<std::string_view> given;
        FitRequest base;
        base.method = method_from(method);
        const FitRequest request = fit_request("fit_files", options, base, given);
        check_fit_request(request, given);
        py::gil_scoped_release release;
        return fit_files(a_path, b_path, request);
      },
      py::arg("A_path"), py::arg("B_path"), py::arg("method"), py::arg("options"));
  m.def(
      "fit_all",
      [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const py::dict& options, const Labels& labels) {
        std::vector<std::string_view> given;
        const FitRequest request = fit_request("fit_all", options, FitRequest{}, given);
        check_option_combination(fit_option_table(), given);
        py::gil_scoped_release release;
        auto results = fit_all(A, B, request.options);
        for (auto& result : results) result = labelled(std::move(result), labels);
        return results;
      },
      py::arg("A"), py::arg("B"), py::arg("options"), py::arg("labels") = py::none());

  m.attr("REPAIR_FLOOR_DEFAULT") = EigenvalueFloor::kRepairDefault;
  // nearest_spd, nearest_correlation and nearest_covariance (`entry`): the repair their keyword
  // arguments name, by the command's workflow (run_nearest), which reads the matrix options given
  // as files. Python counts the pairs of `fixed` from 0. The result carries every warning (the
  // files' readers' too).
  m.def(
      "nearest",
      [](Eigen::MatrixXd C, const std::string& entry, const py::dict& options) {
        std::vector<std::string_view> given;
        NearestCommand command;
        command.matrix.values = std::move(C);  // the caster's copy, moved on to the repair (run_nearest)
        command.repair = nearest_request(entry, options, given);
        command.repair.fixed_index_base = 0;
        check_nearest_request(given, python::entry(entry).unavailable);
        py::gil_scoped_release release;
        NearestRun run = run_nearest(std::move(command));
        run.result.warnings = std::move(run.warnings);
        return run.result;
      },
      py::arg("C"), py::arg("entry"), py::arg("options"));

  m.def(
      "area_criterion",
      [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& X) {
        return area_criterion(A, B, X);
      },
      py::arg("A"), py::arg("B"), py::arg("X"), py::call_guard<py::gil_scoped_release>());
}

}  // namespace spdfit::python
