"""Units (issue 42 item 2): --scale-a and --scale-b multiply A's and B's columns as they are read,
on fit (in memory, streamed, with the bootstrap), compare and hexapod identify, with the noise model
(rest rows, standard deviations, covariances: in the files' units) scaled with them.

Reference: the same fit of the data in the wanted units, written to files by NumPy. Forces logged
in kN (B / 1000) with --scale-b 1000 must give what the forces in N give, to rounding (the factors
are not powers of two, so the two runs differ in the last bits of the data: 1e-10 relative)."""
import json

import numpy as np
import pytest

SAME = 1e-10  # relative: the data differ by one rounding of each entry


def write(path, M):
    np.savetxt(path, np.atleast_2d(M), delimiter=",", fmt="%.17g")
    return str(path)


@pytest.fixture(scope="module")
def logs(tmp_path_factory):
    """A (m/s^2) and B in N and in kN, with 400 rest rows of each, per-column noise."""
    d = tmp_path_factory.mktemp("units")
    rng = np.random.default_rng(42)
    X = np.array([[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]])
    A0 = rng.uniform(-5, 5, (300, 3))
    A = A0 + rng.standard_normal(A0.shape) * [0.05, 0.1, 0.2]
    B = A0 @ X + rng.standard_normal(A0.shape) * [3.0, 1.0, 0.3]
    rest_A = rng.standard_normal((400, 3)) * [0.05, 0.1, 0.2]
    rest_B = np.array([20.0, -5.0, 2.0]) + rng.standard_normal((400, 3)) * [3.0, 1.0, 0.3]
    return {"A": write(d / "A.csv", A), "B": write(d / "B.csv", B), "B_kN": write(d / "B_kN.csv", B / 1000),
            "A_g": write(d / "A_g.csv", A / 9.80665), "rest_A": write(d / "rest_A.csv", rest_A),
            "rest_B": write(d / "rest_B.csv", rest_B), "rest_B_kN": write(d / "rest_B_kN.csv", rest_B / 1000),
            "B_mixed": write(d / "B_mixed.csv", B / [1000.0, 1.0, 1.0]), "dir": d}


def fit_json(spdfit, *args):
    r = spdfit("fit", "--json", *args)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def assert_same_x(got, want, rtol=SAME):
    got, want = np.asarray(got["X"]), np.asarray(want["X"])
    assert np.linalg.norm(got - want) <= rtol * np.linalg.norm(want), (got, want)


@pytest.mark.parametrize("method", ["ls", "procrustes", "spde", "spd-tls", "auto"])
def test_forces_in_kn_with_scale_b_give_the_newton_fit(spdfit, logs, method):
    want = fit_json(spdfit, "--method", method, logs["A"], logs["B"])
    assert_same_x(fit_json(spdfit, "--method", method, "--scale-b", "1000", logs["A"], logs["B_kN"]), want)
    # Accelerations in g, one factor per column (all equal here), and B's columns in mixed units.
    assert_same_x(fit_json(spdfit, "--method", method, "--scale-a", "9.80665,9.80665,9.80665", "--scale-b",
                           "1000,1,1", logs["A_g"], logs["B_mixed"]), want)


def test_the_noise_model_is_in_the_files_units(spdfit, logs):
    want = fit_json(spdfit, "--method", "spd-tls", "--rest-a", logs["rest_A"], "--rest-b", logs["rest_B"], logs["A"],
                    logs["B"])
    got = fit_json(spdfit, "--method", "spd-tls", "--scale-b", "1000", "--rest-a", logs["rest_A"], "--rest-b",
                   logs["rest_B_kN"], logs["A"], logs["B_kN"])
    assert_same_x(got, want, 1e-9)
    model, model_kn = want["diagnostics"]["noise_model"], got["diagnostics"]["noise_model"]
    np.testing.assert_allclose(model_kn["cov_b"], model["cov_b"], rtol=1e-12, atol=0)
    # Standard deviations given in kN, likewise.
    std = fit_json(spdfit, "--method", "spd-tls", "--noise-std-a", "0.05,0.1,0.2", "--noise-std-b", "3,1,0.3",
                   logs["A"], logs["B"])
    std_kn = fit_json(spdfit, "--method", "spd-tls", "--scale-b", "1000", "--noise-std-a", "0.05,0.1,0.2",
                      "--noise-std-b", "0.003,0.001,0.0003", logs["A"], logs["B_kN"])
    assert_same_x(std_kn, std, 1e-9)


@pytest.mark.parametrize("block", ["7", "1000"])
def test_streamed_and_bootstrapped_fits_take_the_units(spdfit, logs, block):
    want = fit_json(spdfit, "--method", "spd-tls", logs["A"], logs["B"])
    got = fit_json(spdfit, "--method", "spd-tls", "--stream", "--block-rows", block, "--scale-b", "1000", logs["A"],
                   logs["B_kN"])
    assert_same_x(got, want, 1e-9)
    boot = fit_json(spdfit, "--method", "ls", "--bootstrap", "50", logs["A"], logs["B"])
    boot_kn = fit_json(spdfit, "--method", "ls", "--bootstrap", "50", "--scale-b", "1000", logs["A"], logs["B_kN"])
    np.testing.assert_allclose(boot_kn["standard_errors"], boot["standard_errors"], rtol=1e-9)


def test_compare_and_identify_take_the_units(spdfit, logs):
    r = spdfit("compare", "--json", logs["A"], logs["B"])
    r_kn = spdfit("compare", "--json", "--scale-b", "1000", logs["A"], logs["B_kN"])
    assert r.returncode == 0 and r_kn.returncode == 0, r_kn.stderr
    want, got = json.loads(r.stdout)["results"], json.loads(r_kn.stdout)["results"]
    assert [x["method"] for x in got] == [x["method"] for x in want]
    for result, result_kn in zip(want, got):
        assert_same_x(result_kn, result, 1e-9)
    i = spdfit("hexapod", "identify", "--json", logs["A"], logs["B"])
    i_kn = spdfit("hexapod", "identify", "--json", "--scale-b", "1000", logs["A"], logs["B_kN"])
    assert i.returncode == 0 and i_kn.returncode == 0, i_kn.stderr
    for method, result in json.loads(i.stdout)["methods"].items():
        assert_same_x(json.loads(i_kn.stdout)["methods"][method], result, 1e-9)


@pytest.mark.parametrize("value,words", [("0", "> 0"), ("-1000", "> 0"), ("nan", ""), ("1,2", "2 values"),
                                         ("", "")])
def test_bad_factors_are_usage_errors_naming_the_option(spdfit, logs, value, words):
    r = spdfit("fit", "--method", "ls", "--scale-b", value, logs["A"], logs["B_kN"])
    assert r.returncode == 2, r.stderr
    assert "--scale-b" in r.stderr and words in r.stderr, r.stderr
