"""Messages where new users meet them: a timestamp column names --index-col, an empty cell says it
may be pandas' NaN, an output file that cannot be written says why (CSV, .mat and .npy alike), and a
negative zero is printed as 0; a subnormal number given as an option is a number, as in a data
file."""
import json

import numpy as np
import pytest

X_TRUE = np.array([[2.0, 0.5], [0.5, 1.0]])


@pytest.fixture
def pair(tmp_path):
    rng = np.random.default_rng(35)
    A = rng.uniform(-5, 5, (12, 2))
    B = A @ X_TRUE + 1e-3 * rng.standard_normal(A.shape)
    np.savetxt(tmp_path / "A.csv", A, delimiter=",", fmt="%.17g")
    np.savetxt(tmp_path / "B.csv", B, delimiter=",", fmt="%.17g")
    return tmp_path


def test_a_timestamp_column_names_index_col(spdfit, pair):
    log = pair / "log.csv"
    log.write_text("time,a1,a2\n2024-01-31 10:15:02,1.5,2\n2024-01-31 10:15:03,3,4\n")
    result = spdfit("fit", "--method", "ls", str(log), str(pair / "B.csv"))
    assert result.returncode == 1
    assert ("log.csv:2:1: '2024-01-31 10:15:02' is not a number; a timestamp in the first column? --index-col "
            "drops it") in result.stderr


def test_an_empty_cell_may_be_pandas_nan(spdfit, pair):
    holes = pair / "holes.csv"
    holes.write_text("a1,a2\n1.5,\n3,4\n")
    result = spdfit("fit", "--method", "ls", str(holes), str(pair / "B.csv"))
    assert result.returncode == 1
    assert "holes.csv:2:4: empty field: the line ends with ','; a missing value? pandas' to_csv writes NaN" \
        in result.stderr


@pytest.mark.parametrize("name", ["X.csv", "X.mat", "X.npy"])
def test_an_output_file_that_cannot_be_written_says_why(spdfit, pair, name):
    target = pair / "missing" / name
    result = spdfit("fit", "--method", "spde", "-o", str(target), str(pair / "A.csv"), str(pair / "B.csv"))
    assert result.returncode == 1
    assert f"{target}: cannot be written (no such directory)" in result.stderr


def test_a_negative_zero_is_printed_as_0(spdfit, tmp_path):
    # A decoupled problem: spde's off-diagonal entries are zeros, whatever their sign in arithmetic.
    A = np.diag([1.0, 2.0, 4.0]).repeat(2, axis=0)
    (tmp_path / "A.csv").write_text("".join(",".join(repr(v) for v in r) + "\n" for r in A))
    (tmp_path / "B.csv").write_text("".join(",".join(repr(v) for v in r) + "\n" for r in -A @ -np.eye(3)))
    result = spdfit("fit", "--method", "procrustes", str(tmp_path / "A.csv"), str(tmp_path / "B.csv"))
    assert result.returncode == 0, result.stderr
    assert "-0," not in result.stdout and not any(cell == "-0" for line in result.stdout.split()
                                                    for cell in line.split(","))
    assert "-0.0000" not in spdfit("fit", "--method", "procrustes", "--report", str(tmp_path / "A.csv"),
                                   str(tmp_path / "B.csv")).stdout


def test_an_unknown_option_names_the_commands_help(spdfit, pair):
    for args, help in ((["nearest", "--bogus", "x.csv"], "spdfit nearest --help"),
                       (["-q", "nearest", "--bogus", "x.csv"], "spdfit nearest --help"),
                       (["hexapod", "simulate", "--bogus"], "spdfit hexapod simulate --help")):
        result = spdfit(*args)
        assert result.returncode == 2
        assert f"Run '{help}' for usage." in result.stderr, (args, result.stderr)


def test_a_sample_count_must_be_an_integer(spdfit, tmp_path):
    result = spdfit("hexapod", "simulate", "--noise-var", "1", "--samples", "2.5", "--out", str(tmp_path / "s"))
    assert result.returncode == 2
    assert "--samples: '2.5' is not an integer in [1, 100000000]" in result.stderr
    result = spdfit("experiment", "thesis", "--samples", "2.5")
    assert result.returncode == 2
    assert "'2.5' is not an integer in [6, 100000000]" in result.stderr


def test_too_few_samples_to_fit_warn_with_the_text_python_warns(spdfit, tmp_path):
    # spdfit.hexapod.simulate(2, ...) warns the same text (tests/python/test_hexapod_experiment.py).
    result = spdfit("hexapod", "simulate", "--noise-var", "0.86", "--samples", "2", "--out", str(tmp_path / "s"))
    assert result.returncode == 0, result.stderr
    assert "spdfit: warning: fewer samples (2) than M_p has columns (6): the estimators need m >= n" in result.stderr
    assert (tmp_path / "s" / "A.csv").exists()
    quiet = spdfit("hexapod", "simulate", "--noise-var", "0.86", "--samples", "6", "--out", str(tmp_path / "t"))
    assert quiet.returncode == 0 and "fewer samples" not in quiet.stderr


@pytest.mark.parametrize("value", ["1e-308", "1e-320"])
def test_a_subnormal_option_value_is_a_number_as_in_a_data_file(spdfit, pair, value):
    # Below the smallest normal double (2.2e-308): a data file's reader takes such a value, and so
    # does a numeric option (it was "is not a number"). Its square, the variance, is 0 in double
    # precision: the model of exact B.
    common = ("fit", "--method", "spd-tls", str(pair / "A.csv"), str(pair / "B.csv"), "--noise-std-a", "0.01", "--json")
    tiny = spdfit(*common, "--noise-std-b", f"{value},{value}")
    exact = spdfit(*common, "--noise-std-b", "0")
    assert tiny.returncode == 0, tiny.stderr
    assert exact.returncode == 0, exact.stderr
    np.testing.assert_allclose(json.loads(tiny.stdout)["X"], json.loads(exact.stdout)["X"], rtol=1e-12)


def test_an_overflowing_option_value_is_still_not_a_number(spdfit, pair):
    result = spdfit("fit", "--method", "spd-tls", str(pair / "A.csv"), str(pair / "B.csv"), "--noise-std-a", "0.01",
                    "--noise-std-b", "1e999")
    assert result.returncode == 2
    assert "--noise-std-b: '1e999' is not a number or a comma-separated list of numbers" in result.stderr
