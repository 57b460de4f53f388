"""Python and the CLI render and judge results with the same library code, so they show the same
numbers and warnings: a result's repr is the CLI's report (with Python's own hints), nearest_spd
warns as `spdfit nearest` does, and the experiments' comparisons (the demo's significance rule,
the best method, paper-hexapod's win counts, the error against a truth) are the library's."""
import json
import math
import warnings

import numpy as np
import pytest

import spdfit
import spdfit.experiment as ex
import spdfit.hexapod as hx
from spdfit_testing import SOURCE_DIR, cli_path, run_cli

HEX = [str(SOURCE_DIR / "examples/hexapod/A.csv"), str(SOURCE_DIR / "examples/hexapod/B.csv")]
LOAD = [str(SOURCE_DIR / "examples/load_cell/loads.csv"), str(SOURCE_DIR / "examples/load_cell/readings.csv")]
S_CSV = str(SOURCE_DIR / "examples/covariance/S.csv")

# The report's hints name each front-end's own means (the library's ReportHints).
CLI_HINTS = ("add --bootstrap N, e.g. 1000", "--json (interval, bias)")
PYTHON_HINTS = ("bootstrap=N, e.g. 1000", "the interval and bias attributes")


def cli(*args):
    result = run_cli(cli_path(), *args)
    assert result.returncode == 0, result.stderr
    return result


def quiet(function, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        return function(*args, **kwargs)


def in_python_words(report):
    for ours, theirs in zip(CLI_HINTS, PYTHON_HINTS):
        report = report.replace(ours, theirs)
    return report


@pytest.mark.parametrize("files,method,options", [
    (HEX, "spde", {}),
    (HEX, "psd-ls", {}),
    (HEX, "auto", {"bootstrap": 200}),
    (LOAD, "ls", {"bootstrap": 100, "confidence": 0.9}),
])
def test_a_fit_results_repr_is_the_clis_report(files, method, options):
    # From the files, as the command line reads them: the report names their columns.
    result = quiet(spdfit.fit_files, *files, method, **options)
    flags = [f"--{key}={value}" for key, value in options.items()]
    report = cli("fit", "--method", method, "--report", *flags, *files).stdout
    assert repr(result) == f"FitResult(method='{result.method}', status='success')\n" + in_python_words(report)
    # The hints are the front-ends' own; the numbers are the same.
    assert ("bootstrap=N" in repr(result)) == ("bootstrap" not in options)


def test_a_linear_system_results_repr_is_the_clis_text():
    A, b = (spdfit.read_matrix(str(SOURCE_DIR / f"examples/linkage/notes_ex3_{x}.csv")) for x in "Ab")
    result = quiet(spdfit.solve, A, b)
    text = cli("solve", *(str(SOURCE_DIR / f"examples/linkage/notes_ex3_{x}.csv") for x in "Ab")).stdout
    first, rest = repr(result).split("\n", 1)
    assert first.startswith("LinearSystemResult(rank=") and rest == text


def test_the_parts_reprs_show_the_librarys_json():
    A, B = (spdfit.read_matrix(f) for f in HEX)
    d = quiet(spdfit.fit, A, B, "spde").diagnostics
    text = repr(d)
    document = json.loads(spdfit._spdfit.Diagnostics.__getstate__(d)[1])
    assert text.startswith("Diagnostics(area_criterion=") and f"rank_a={document['rank_a']}" in text
    assert f"cond_a={d.cond_a!r}" in text  # a float as Python writes it: the shortest that reads back
    assert "positive_definite=True" in text and "'column-scaled'" in text


def test_nearest_spd_warns_as_the_cli_does():
    S = spdfit.read_matrix(S_CSV)
    for python_options, cli_options in [({"min_eig": 0.01}, ["--min-eig", "0.01"]),
                                        ({"min_eig_rel": 1e-3}, ["--min-eig-rel", "1e-3"]),
                                        ({}, [])]:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = spdfit.nearest_spd(S, full_output=True, **python_options)
        ours = [str(w.message) for w in caught if issubclass(w.category, spdfit.SpdfitWarning)]
        theirs = cli("nearest", *cli_options, S_CSV).stderr.splitlines()
        assert theirs and ours == [line.replace("spdfit: warning: ", "nearest_spd: ") for line in theirs]
        assert result.clipped >= 1
        assert any(f"{result.clipped} eigenvalue(s) of the symmetric part were below" in w for w in ours)


def test_nearest_spd_does_not_warn_when_nothing_is_clipped():
    with warnings.catch_warnings():
        warnings.simplefilter("error", spdfit.SpdfitWarning)
        result = spdfit.nearest_spd(np.diag([1.0, 2.0, 3.0]), full_output=True)
    assert result.clipped == 0 and result.warnings == []


def test_the_error_against_a_truth_is_compares_and_identifys():
    A, B = (spdfit.read_matrix(f) for f in HEX)
    truth = spdfit.read_matrix(str(SOURCE_DIR / "examples/hexapod/truth.csv"))
    identified = quiet(hx.identify, A, B, truth=truth)
    compared = json.loads(cli("compare", "--json", "--truth", str(SOURCE_DIR / "examples/hexapod/truth.csv"),
                              *HEX).stdout)
    on_the_cli = {r["method"]: r["error_vs_truth"] for r in compared["results"]}
    assert set(on_the_cli) == set(identified)
    for method, m in identified.items():
        assert m.error_vs_truth == on_the_cli[method], method
        assert m.error_vs_truth == pytest.approx(np.linalg.norm(m.result.X - truth), rel=1e-14)


def test_paper_hexapods_win_counts_are_the_clis():
    result = ex.paper_hexapod(trials=300, seed=4, threads=2)
    text = cli("experiment", "paper-hexapod", "--trials", "300", "--seed", "4").stdout
    wins = result.wins("spde", "procrustes")
    assert (f"spde has the smaller mean absolute error on {wins['mae']} of {wins['entries']} entries and the "
            f"smaller standard deviation on {wins['std']}.") in text
    # Against the per-entry statistics themselves.
    spde, procrustes = (next(s for s in result.methods if s.method == m) for m in ("spde", "procrustes"))
    assert wins == {"mae": int(np.sum(spde.mae < procrustes.mae)), "std": int(np.sum(spde.std < procrustes.std)),
                    "entries": 21}


def test_the_thesis_comparison_is_the_clis():
    result = ex.thesis(0.86, trials=300, seed=2, threads=2)
    text = cli("experiment", "thesis", "--noise-var", "0.86", "--trials", "300", "--seed", "2").stdout
    c = result.compare("spde", "procrustes")
    assert (f"spde - procrustes, trial by trial: mean difference {c.mean_difference:.4f} +- "
            f"{c.standard_error:.4f} (s.e.); spde lower in {100 * c.fraction_lower:.1f}% of {c.count} trials") in text
    # The comparison against NumPy on the trials' errors.
    errors = {m.method: m.errors for m in result.methods}
    d = errors["spde"] - errors["procrustes"]
    assert c.count == 300 and c.mean_difference == pytest.approx(d.mean(), rel=1e-12)
    assert c.standard_error == pytest.approx(d.std(ddof=1) / math.sqrt(300), rel=1e-12)
    assert c.fraction_lower == np.mean(d < 0)


def test_the_best_method_is_the_smallest_mean():
    result = ex.thesis(0.86, trials=200, seed=3, threads=2)
    means = {m.method: m.summary.mean for m in result.methods}
    for among in (["procrustes", "tls-sym", "spde"], list(means), ["ls", "tls"]):
        assert result.best_of(among) == min(among, key=lambda m: means[m])
    with pytest.raises(ValueError, match="no methods"):
        result.best_of([])


def paired(count, mean_difference, standard_error, fraction_lower=0.5):
    c = ex.PairedComparison.__new__(ex.PairedComparison)
    pickle_format = spdfit._spdfit.hexapod.SimulationOptions().__getstate__()[0]  # this build's (pickle.hpp)
    c.__setstate__((pickle_format, (count, mean_difference, standard_error, fraction_lower)))
    return c


def test_the_significance_rule_is_three_standard_errors():
    assert ex.SIGNIFICANCE == 3.0
    assert paired(100, -3.01, 1.0).order() == "lower"
    assert paired(100, -2.99, 1.0).order() == "tie"
    assert paired(100, 3.01, 1.0).order() == "higher"
    assert paired(100, 2.99, 1.0).order() == "tie"
    assert paired(100, -2.5, 1.0).order(significance=2.0) == "lower"
    assert paired(0, 0.0, 0.0).order() == "tie"


def test_entry_comparisons_are_those_of_the_absolute_errors():
    result = ex.paper_2x2(1.0, trials=400, seed=5, threads=2)
    comparisons = result.compare("spde", "procrustes")
    spde, procrustes = (next(s for s in result.methods if s.method == m) for m in ("spde", "procrustes"))
    assert len(comparisons) == len(result.entries) == 3
    for e, c in enumerate(comparisons):
        d = np.abs(spde.errors[:, e]) - np.abs(procrustes.errors[:, e])
        assert c.mean_difference == pytest.approx(d.mean(), rel=1e-12)
        assert c.standard_error == pytest.approx(d.std(ddof=1) / math.sqrt(len(d)), rel=1e-12)
        expected = "lower" if d.mean() + 3 * c.standard_error < 0 else "higher" if d.mean() - 3 * c.standard_error > 0 \
            else "tie"
        assert c.order() == expected
