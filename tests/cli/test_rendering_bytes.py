"""The rendered output, byte for byte: --json, --report and the tables of every command that
prints a result, against files recorded from the program (tests/cli/rendering/). The renderers
moved from the command line into the library; these files hold them to the bytes they printed,
so that a change of output is a visible change of a file here, never an accident.

Regenerate after an intended change of output (and review the diff):
    SPDFIT_REGENERATE_RENDERING=1 ctest --test-dir build -R '^cli$'

The inputs are small (n <= 6, the library's own small-problem path, not the BLAS's kernels), so
the numbers are the same on every CPU. The sanitizer build (clang) may round the last digit of a
long Monte Carlo run differently from the Release build (gcc) that recorded them: it skips them.
"""
import os
import pathlib
import re

import pytest

from spdfit_testing import SANITIZED, SOURCE_DIR, cli_path, run_cli

RECORDED = pathlib.Path(__file__).resolve().parent / "rendering"
REGENERATE = os.environ.get("SPDFIT_REGENERATE_RENDERING") == "1"

HEX = ["examples/hexapod/A.csv", "examples/hexapod/B.csv"]
P22 = ["examples/paper_2x2/A.csv", "examples/paper_2x2/B.csv"]
LOAD = ["examples/load_cell/loads.csv", "examples/load_cell/readings.csv"]
RANK = ["examples/bad/rank_deficient_A.csv", "examples/paper_2x2/B.csv"]
METHODS = ["ls", "procrustes", "tls", "tls-sym", "tls-psd", "spde", "spd-tls", "psd-ls", "auto"]

# name -> the command's arguments (run in the source tree; "{run}" is a simulated hexapod run).
CASES = {
    **{f"fit_json_{m}": ["fit", "--method", m, "--json", *HEX] for m in METHODS},
    **{f"fit_report_{m}": ["fit", "--method", m, "--report", *HEX] for m in ["spde", "auto", "psd-ls"]},
    "fit_json_2x2": ["fit", "--method", "spde", "--json", *P22],
    "fit_json_rank_deficient": ["fit", "--method", "ls", "--json", *RANK],
    "fit_json_tls_load_cell": ["fit", "--method", "tls", "--noise-ratio", "0.1", "--json", *LOAD],
    "fit_report_ls_load_cell": ["fit", "--method", "ls", "--report", *LOAD],
    "fit_json_bootstrap": ["fit", "--method", "auto", "--bootstrap", "200", "--json", *HEX],
    "fit_report_bootstrap": ["fit", "--method", "auto", "--bootstrap", "200", "--report", *HEX],
    "fit_report_bootstrap_ls": ["fit", "--method", "ls", "--bootstrap", "100", "--confidence", "0.9",
                                "--report", *LOAD],
    "fit_json_stream_bootstrap": ["fit", "--method", "spde", "--stream", "--block-rows", "2", "--bootstrap", "50",
                                  "--json", *HEX],
    "fit_report_stream_bootstrap": ["fit", "--method", "spde", "--stream", "--block-rows", "2", "--bootstrap", "50",
                                    "--report", *HEX],
    "compare_text": ["compare", "--truth", "examples/hexapod/truth.csv", *HEX],
    "compare_json": ["compare", "--truth", "examples/hexapod/truth.csv", "--json", *HEX],
    "compare_load_cell": ["compare", *LOAD],
    "compare_rank_deficient_json": ["compare", "--json", *RANK],
    "nearest_json": ["nearest", "--json", "examples/covariance/S.csv"],
    "nearest_json_min_eig": ["nearest", "--min-eig", "0.01", "--json", "examples/covariance/S.csv"],
    "nearest_json_rel": ["nearest", "--min-eig-rel", "1e-3", "--json", "examples/covariance/S.csv"],
    "nearest_json_keep_diag": ["nearest", "--keep-diag", "--json", "examples/covariance/S.csv"],
    "nearest_json_corr": ["nearest", "--corr", "--json", "examples/covariance/C.csv"],
    "nearest_json_corr_keep_diag": ["nearest", "--corr", "--keep-diag", "--json", "examples/covariance/C.csv"],
    "nearest_json_via_corr_alpha": ["nearest", "--via-corr", "--alpha", "0.01", "--json",
                                    "examples/covariance/S.csv"],
    "nearest_csv": ["nearest", "examples/covariance/S.csv"],
    "nearest_header_named": ["nearest", "--header", "examples/covariance/S_named.csv"],
    "nearest_json_named": ["nearest", "--json", "examples/covariance/S_named.csv"],
    **{f"solve_text_ex{k}": ["solve", f"examples/linkage/notes_ex{k}_A.csv", f"examples/linkage/notes_ex{k}_b.csv"]
       for k in range(1, 7)},
    **{f"solve_json_ex{k}": ["solve", "--json", f"examples/linkage/notes_ex{k}_A.csv",
                             f"examples/linkage/notes_ex{k}_b.csv"] for k in range(1, 7)},
    "solve_text_many": ["solve", *LOAD],
    "solve_json_many": ["solve", "--json", *LOAD],
    "model_text": ["hexapod", "model"],
    "model_json": ["hexapod", "model", "--json"],
    "identify_report": ["hexapod", "identify", "{run}/A.csv", "{run}/B.csv", "--truth", "{run}/truth.csv"],
    "identify_json": ["hexapod", "identify", "{run}/A.csv", "{run}/B.csv", "--truth", "{run}/truth.csv", "--json"],
    "identify_report_stiffness": ["hexapod", "identify", "{run}/A.csv", "{run}/B.csv", "--stiffness", "2e6"],
    "identify_report_bootstrap": ["hexapod", "identify", "{run}/A.csv", "{run}/B.csv", "--truth", "{run}/truth.csv",
                                  "--stiffness", "2e6", "--bootstrap", "60"],
    "identify_json_bootstrap": ["hexapod", "identify", "{run}/A.csv", "{run}/B.csv", "--truth", "{run}/truth.csv",
                                "--stiffness", "2e6", "--bootstrap", "60", "--json"],
    "identify_report_few": ["hexapod", "identify", "{few}/A.csv", "{few}/B.csv", "--truth", "{few}/truth.csv"],
    "experiment_thesis": ["experiment", "thesis", "--noise-var", "0.86", "--trials", "300"],
    "experiment_thesis_json": ["experiment", "thesis", "--noise-var", "0.86", "--trials", "300", "--json"],
    "experiment_paper_hexapod": ["experiment", "paper-hexapod", "--trials", "300"],
    "experiment_paper_hexapod_json": ["experiment", "paper-hexapod", "--trials", "300", "--json"],
    "experiment_paper_2x2": ["experiment", "paper-2x2", "--std-a", "1", "--trials", "500"],
    "experiment_paper_2x2_sweep": ["experiment", "paper-2x2", "--sweep", "--trials", "300"],
    "experiment_paper_2x2_json": ["experiment", "paper-2x2", "--std-a", "1", "--trials", "500", "--json"],
    "experiment_physical": ["experiment", "physical", "--samples", "12,100", "--trials", "50"],
    "experiment_physical_json": ["experiment", "physical", "--samples", "12,100", "--trials", "50", "--json"],
    "demo": ["demo", "--trials", "200", "--trials-2x2", "300", "--trials-samples", "50", "--trials-beyond", "40"],
}

# The demo says how long it ran.
VARIABLE = [(re.compile(r"in \d+\.\d s\."), "in TIME s.")]


def normalized(text):
    for pattern, replacement in VARIABLE:
        text = pattern.sub(replacement, text)
    return text


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The simulated hexapod runs the identify cases read: 200 samples, and 8 (fewer than most
    methods like)."""
    path = cli_path()
    out = {}
    for name, samples in [("run", 200), ("few", 8)]:
        directory = tmp_path_factory.mktemp(name)
        made = run_cli(path, "hexapod", "simulate", "--noise-var", "0.86", "--samples", samples, "--seed", "7",
                       "--out", directory)
        assert made.returncode == 0, made.stderr
        out[name] = directory
    return out


@pytest.mark.skipif(SANITIZED, reason="the files are the Release build's bytes (see the module's docstring)")
@pytest.mark.parametrize("name", sorted(CASES))
def test_output_is_byte_for_byte_the_recorded_one(name, runs):
    args = [str(a).format(run=runs["run"], few=runs["few"]) for a in CASES[name]]
    result = run_cli(cli_path(), *args, cwd=SOURCE_DIR)
    # The simulated runs live in a temporary folder whose name changes from run to run.
    stdout, stderr = (text.replace(str(runs["run"]), "{run}").replace(str(runs["few"]), "{few}")
                      for text in (normalized(result.stdout), result.stderr))
    got = f"exit status {result.returncode}\n--- stdout\n{stdout}--- stderr\n{stderr}"
    recorded = RECORDED / f"{name}.txt"
    if REGENERATE:
        RECORDED.mkdir(exist_ok=True)
        recorded.write_text(got)
    assert recorded.exists(), f"{recorded} is missing: regenerate (see the module's docstring)"
    assert got == recorded.read_text()


def test_every_recorded_file_has_a_case():
    stale = sorted(p.stem for p in RECORDED.glob("*.txt") if p.stem not in CASES)
    assert not stale, f"recorded outputs without a case (delete them): {stale}"
