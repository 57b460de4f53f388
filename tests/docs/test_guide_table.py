"""docs/guide.md's "Which to use when" table is spdfit's own measurement: rows of it are rerun
here with another seed and every mean must agree within SIGMAS combined standard errors (the
table's and the rerun's). Also the claims drawn from it: auto within 10% of the best method."""
import json
import os
import pathlib
import re
import subprocess

import pytest

ROOT = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
SIGMAS = 4.5
TRIALS = 600
METHODS = ["procrustes", "tls-sym", "spde", "spd-tls", "psd-ls", "auto"]
CELL = re.compile(r"^\**([0-9.]+)\** \(([0-9.]+)\)$")


def table():
    """{(nm, m): {method: (mean, standard error)}} from the guide."""
    text = (ROOT / "docs/guide.md").read_text()
    rows = {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 3 + len(METHODS) or not re.fullmatch(r"[0-9.]+", cells[0]) or not cells[1].isdigit():
            continue
        values = {}
        for name, cell in zip(METHODS, cells[2:-1]):
            match = CELL.match(cell)
            assert match, cell
            values[name] = (float(match.group(1)), float(match.group(2)))
        rows[(float(cells[0]), int(cells[1]))] = values
    return rows


def test_the_table_covers_both_noise_levels_and_every_size():
    assert set(table()) == {(w, m) for w in (1.0, 3.2) for m in (12, 30, 100, 1000)}


@pytest.mark.parametrize("point", [(1.0, 30), (3.2, 12), (3.2, 100), (3.2, 1000)])
def test_rows_agree_with_a_rerun(cli, point):
    width, m = point
    out = subprocess.run([cli, "experiment", "thesis", "--noise-var", repr(width * width / 12), "--samples", str(m),
                          "--trials", str(TRIALS), "--seed", "97", "--methods", ",".join(METHODS), "--json"],
                         check=True, capture_output=True, text=True).stdout
    rerun = json.loads(out)["methods"]
    for name, (mean, se) in table()[point].items():
        mine = rerun[name]
        # tls-sym's and spd-tls's means at m = 12 are dominated by rare huge errors: their
        # standard error is itself unreliable there, so those two cells are compared by medians
        # of the rerun against the table's mean only loosely.
        if m == 12 and name in ("tls-sym", "spd-tls") and width > 1:
            assert mine["median"] < mean, name
            continue
        se_run = mine["std"] / TRIALS ** 0.5
        assert abs(mine["mean"] - mean) < SIGMAS * (se ** 2 + se_run ** 2) ** 0.5, (point, name, mine["mean"], mean)


def test_auto_is_within_ten_percent_of_the_best_everywhere():
    for point, values in table().items():
        best = min(mean for name, (mean, _) in values.items() if name != "auto")
        assert values["auto"][0] <= 1.10 * best, point
