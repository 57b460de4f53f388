"""docs/hexapod.md stays true: every `$ spdfit ...` command in it runs (in order, in one scratch
directory) with the exit status and the output lines the page shows and no warning that
contradicts the run, and its results tables are what the commands they name produce."""
import json
import re
import shlex
import subprocess

import numpy as np
import pytest

import spdfit_testing
from conftest import CLI_TIMEOUT_S, SOURCE_DIR, full_size

DOC = SOURCE_DIR / "docs" / "hexapod.md"

# The thesis' single-run errors (000, eq. 6.6-6.22), as the table quotes them.
THESIS_RUNS = {
    ("1", "procrustes"): "0.6755", ("1", "tls-sym"): "0.6899", ("1", "spde"): "0.6630",
    ("2", "procrustes"): "2.3610", ("2", "tls-sym"): "2.3007", ("2", "spde"): "1.9689",
    ("3", "procrustes"): "2.9120", ("3", "tls-sym"): "3.7761", ("3", "spde"): "2.0083",
}


def doc_commands():
    """[(command, [expected output lines])] from the page's code blocks; "..." elides lines."""
    return spdfit_testing.doc_commands(DOC)


def bad_geometry(spdfit_cli, directory):
    """The bad.json the page shows being rejected: the built-in geometry with every joint on the
    z axis, so that struts 1 and 2 lie on one line."""
    subprocess.run([spdfit_cli, "hexapod", "model", "--write-geometry", "cube.json"], cwd=directory, check=True,
                   capture_output=True)
    g = json.loads((directory / "cube.json").read_text())
    g["payload_points"] = [[0, 0, 0.01 * i] for i in range(6)]
    g["base_points"] = [[0, 0, -0.1 + 0.01 * i] for i in range(6)]
    (directory / "bad.json").write_text(json.dumps(g))


def test_the_page_shows_commands():
    assert len(doc_commands()) >= 12


@full_size
def test_every_command_runs_as_shown(spdfit_cli, tmp_path):
    bad_geometry(spdfit_cli, tmp_path)
    for command, expected in doc_commands():
        words = shlex.split(command)
        assert words[0] == "spdfit", command
        proc = subprocess.run([spdfit_cli, *words[1:]], cwd=tmp_path, capture_output=True, text=True,
                              timeout=CLI_TIMEOUT_S)
        shown_error = any(line.startswith("spdfit: error:") for line in expected)
        assert proc.returncode == (1 if shown_error else 0), f"{command}\n{proc.stderr}"
        produced = {line.rstrip() for line in (proc.stdout + proc.stderr).splitlines()}
        for line in expected:
            assert line in produced, f"{command}: the page shows\n{line}\nbut the command printed\n{proc.stdout}{proc.stderr}"
        # No warning that contradicts the method the run chose or the noise model it was given.
        bad = spdfit_testing.contradicting_warnings((proc.stdout + proc.stderr).splitlines(),
                                                    *spdfit_testing.command_context(words))
        assert not bad, f"{command}: prints what contradicts its method or noise model:\n" + "\n".join(bad)


def table_rows(name):
    text = DOC.read_text()
    body = re.search(rf"<!-- {name}:.*?-->\n(.*?)<!-- end {name} -->", text, re.S).group(1)
    rows = [[cell.strip() for cell in line.strip().strip("|").split("|")] for line in body.splitlines()]
    return [row for row in rows[2:] if row and row[0]]  # skip the header and the |---| line


@full_size
def test_thesis_table_is_what_the_commands_produce(cli_json):
    rows = table_rows("thesis-table")
    assert len(rows) == 18
    runs = {}
    for experiment, V, method, thesis, mean, se, std, median, largest in rows:
        if V not in runs:
            runs[V] = cli_json("experiment", "thesis", "--noise-var", V, "--trials", 2000, "--seed", 1)
        s = runs[V]["methods"][method]
        assert [mean, se, std, median, largest] == [f"{s[k]:.3f}" for k in
                                                    ("mean", "standard_error", "std", "median", "max")], (V, method)
        assert thesis == THESIS_RUNS.get((experiment, method), ""), (experiment, method)


@full_size
def test_paper_2x2_table_is_what_the_commands_produce(cli_json):
    rows = table_rows("paper-2x2-table")
    assert len(rows) == 9
    runs = {}
    for std_a, method, *mae in rows:
        if std_a not in runs:
            runs[std_a] = cli_json("experiment", "paper-2x2", "--std-a", std_a, "--seed", 1)
        assert runs[std_a]["trials"] == 10000
        assert mae == [f"{x:.3f}" for x in runs[std_a]["methods"][method]["mae"]], (std_a, method)


@full_size
def test_physical_table_is_what_the_command_produces(cli_json):
    rows = table_rows("physical-table")
    assert len(rows) == 4
    out = cli_json("experiment", "physical", "--trials", 1000, "--seed", 1, "--methods",
                   "spde,spd-tls,physical,physical-ls,grey-box-ls,grey-box-tls")
    assert out["trials"] == 1000
    for cells, row in zip(rows, out["rows"]):
        m, spde, spd_tls, physical, ratio, physical_ls, grey_ls, grey_tls, grey_tls_inconsistent = cells
        s = row["methods"]
        assert int(m) == row["samples"]
        assert [spde, spd_tls, physical_ls, grey_ls, grey_tls] == [
            f"{s[k]['mean']:.3f}" for k in ("spde", "spd-tls", "physical-ls", "grey-box-ls", "grey-box-tls")], m
        assert physical == f"{s['physical']['mean']:.3f} ± {s['physical']['standard_error']:.3f}", m
        assert ratio == f"{row['physical_ratio']:.3f}", m
        count = s["grey-box-tls"]["inconsistent"]
        assert grey_tls_inconsistent == (f"{count} of 1000" if count else "0"), m
        assert s["physical"]["inconsistent"] == 0, m


@full_size
def test_thin_rod_table_is_what_the_command_produces(cli_json):
    """The thin rod (11.973 kg, 0.45 m long, 4.5 mm thick) given as --payload-inertia."""
    rows = table_rows("thin-rod-table")
    assert len(rows) == 4
    out = cli_json("experiment", "physical", "--trials", 1000, "--seed", 1, "--payload-inertia",
                   "4.0408875e-05,0.20206457943750003,0.20206457943750003",
                   "--methods", "spde,spd-tls,physical,grey-box-tls,grey-box-ls")
    mass, length, thickness = 11.973, 0.45, 0.0045
    across, along = mass * thickness ** 2 / 12, mass * length ** 2 / 12
    np.testing.assert_allclose(np.diag(out["payload"]["inertia"]), [2 * across, along + across, along + across],
                               rtol=1e-15)
    for cells, row in zip(rows, out["rows"]):
        m, best, physical, physical_bad, grey_tls, grey_tls_bad, grey_ls, grey_ls_bad = cells
        s = row["methods"]
        assert int(m) == row["samples"]
        assert best == f"{s[row['best_generic']]['mean']:.3f} ({row['best_generic']})", m
        assert [physical, grey_tls, grey_ls] == [f"{s[k]['mean']:.3f}" for k in ("physical", "grey-box-tls",
                                                                                 "grey-box-ls")], m
        assert [physical_bad, grey_tls_bad, grey_ls_bad] == [
            str(s[k]["inconsistent"]) for k in ("physical", "grey-box-tls", "grey-box-ls")], m


@full_size
def test_readme_hexapod_commands_run(spdfit_cli, tmp_path):
    """The README's "The hexapod" block: each `spdfit ...` line (comments dropped) runs."""
    text = (SOURCE_DIR / "README.md").read_text()
    block = text.split("## The hexapod", 1)[1].split("\n## ", 1)[0]
    commands = [line.split("#", 1)[0].strip() for line in block.splitlines() if line.startswith("    spdfit ")]
    assert len(commands) >= 6
    for command in commands:
        words = shlex.split(command)
        proc = subprocess.run([spdfit_cli, *words[1:]], cwd=tmp_path, capture_output=True, text=True,
                              timeout=CLI_TIMEOUT_S)
        assert proc.returncode == 0, f"{command}\n{proc.stderr}"
