"""The shipped examples run, and the estimates behave as the documents say on them."""
import json
import os
import pathlib

import numpy as np
import pytest

ROOT = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
EXAMPLES = ROOT / "examples"


@pytest.mark.parametrize("name", ["hexapod", "paper_2x2"])
def test_compare_runs_on_each_example(spdfit, name):
    d = EXAMPLES / name
    result = spdfit("compare", "--json", "--truth", d / "truth.csv", d / "A.csv", d / "B.csv")
    assert result.returncode == 0, result.stderr
    results = {r["method"]: r for r in json.loads(result.stdout)["results"]}
    spde = results["spde"]
    assert spde["diagnostics"]["positive_definite"]
    X = np.array(spde["X"])
    assert np.array_equal(X, X.T)


def test_covariance_example_is_repaired(spdfit):
    C = np.loadtxt(EXAMPLES / "covariance/C.csv", delimiter=",")
    assert np.linalg.eigvalsh(C)[0] < 0  # the example is indefinite
    out = json.loads(spdfit("nearest", "--json", "--min-eig", "1e-6", EXAMPLES / "covariance/C.csv").stdout)
    assert np.linalg.eigvalsh(np.array(out["X"]))[0] >= 1e-6 * (1 - 1e-9)


def test_examples_are_what_the_generator_makes(tmp_path):
    """examples/make_examples.py regenerates the committed files (numbers to rounding)."""
    import runpy
    import shutil
    copy = tmp_path / "examples"
    shutil.copytree(EXAMPLES, copy)
    runpy.run_path(str(copy / "make_examples.py"), run_name="__main__")
    for path in EXAMPLES.rglob("*.csv"):
        made = (copy / path.relative_to(EXAMPLES)).read_text().splitlines()
        committed = path.read_text().splitlines()
        assert len(made) == len(committed), path
        # Lines that differ must be rows of numbers equal to rounding: a matrix product such as
        # B = A @ M_p may round differently with the CPU's SIMD path (seen: regenerated on an
        # AVX-512 Xeon, hexapod/B.csv differs in the last bit). Comments and headers must match.
        differing = [(a, b) for a, b in zip(made, committed) if a != b]
        for a, b in differing:
            # (A log's timestamp field, not a number, must match exactly.)
            mine, theirs = a.split(","), b.split(",")
            assert len(mine) == len(theirs), f"{path}: {b}"
            numeric = [k for k, x in enumerate(theirs) if x[:1] in "-.0123456789" and "T" not in x]
            assert [x for k, x in enumerate(mine) if k not in numeric] == \
                [x for k, x in enumerate(theirs) if k not in numeric], f"{path}: {b}"
            np.testing.assert_allclose([float(mine[k]) for k in numeric], [float(theirs[k]) for k in numeric],
                                       rtol=1e-14, atol=0, err_msg=f"{path}: {b}")
