"""Constant offsets (--offsets none|estimate|rest) on fit, compare and hexapod identify: estimate fits
A X + 1 c^T ~= B (the fit of the column-centred data, c = mean(B) - X^T mean(A)), rest subtracts
the rest rows' means (taring), none takes the data as given but warns of offsets it would take for
signal.

Reference: NumPy, independently of the library: the data centred (or tared) by NumPy and written to
files of their own, fitted without offsets; numpy.linalg.lstsq on [1 A]; the singular values of the
centred [A B] for the noise estimate; the intercept's and the rest rows' evidence computed by hand
for the warnings."""
import json

import numpy as np
import pytest

from spdfit_testing import save_csv

SAME = 1e-10  # relative: the same fit of data that differ by a subtraction (centring, taring) or a shift

X_TRUE = np.array([[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]])
SD_A, SD_B = np.array([0.05, 0.1, 0.2]), np.array([0.3, 0.2, 0.1])
OFF_A, OFF_B = np.array([3.0, -2.0, 4.0]), np.array([20.0, -5.0, 2.0])
COLS = ["--a-cols", "a1:a3", "--b-cols", "f1:f3"]


def write(path, M, header=None):
    return str(save_csv(path, M, header))


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """m = 300 rows, n = d = 3, with constant offsets in A's and B's columns (A_off, B_off); the
    same centred by NumPy (A_c, B_c); shifted by 1e4 times each column's spread, a different
    multiple per column (A_big, B_big); 600 rest rows with the offsets (rest_A, rest_B); the data
    tared by the rest rows' means (A_t, B_t); and one log of the rest rows then the data rows."""
    d = tmp_path_factory.mktemp("offsets")
    rng = np.random.default_rng(17)
    m = 300
    A0 = rng.uniform(-5, 5, (m, 3))
    A_off = A0 + OFF_A + rng.standard_normal((m, 3)) * SD_A
    B_off = A0 @ X_TRUE + OFF_B + rng.standard_normal((m, 3)) * SD_B
    A_c, B_c = A_off - A_off.mean(axis=0), B_off - B_off.mean(axis=0)
    A_big = A_off + 1e4 * A_off.std(axis=0) * np.array([1.0, -0.7, 0.4])
    B_big = B_off + 1e4 * B_off.std(axis=0) * np.array([-0.5, 1.0, 0.8])
    rest_A = OFF_A + rng.standard_normal((600, 3)) * SD_A
    rest_B = OFF_B + rng.standard_normal((600, 3)) * SD_B
    mean_rest_A, mean_rest_B = rest_A.mean(axis=0), rest_B.mean(axis=0)
    A_t, B_t = A_off - mean_rest_A, B_off - mean_rest_B
    log = np.column_stack([0.01 * np.arange(600 + m), np.vstack([rest_A, A_off]), np.vstack([rest_B, B_off])])
    arrays = {"A_off": A_off, "B_off": B_off, "A_c": A_c, "B_c": B_c, "A_big": A_big, "B_big": B_big,
              "rest_A": rest_A, "rest_B": rest_B, "A_t": A_t, "B_t": B_t}
    out = {name + "_path": write(d / f"{name}.csv", M) for name, M in arrays.items()}
    out.update(arrays)
    out.update(mean_rest_A=mean_rest_A, mean_rest_B=mean_rest_B, dir=d,
               log_path=write(d / "log.csv", log, "t,a1,a2,a3,f1,f2,f3"))
    return out


def paths(files, *names):
    return [files[name + "_path"] for name in names]


def run_json(spdfit, *args):
    r = spdfit(*args, "--json")
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def fit_json(spdfit, *args):
    return run_json(spdfit, "fit", *args)


def assert_same_x(got, want, rtol=SAME):
    got, want = (np.asarray(v["X"] if isinstance(v, dict) else v) for v in (got, want))
    assert np.linalg.norm(got - want) <= rtol * np.linalg.norm(want), (got, want)


def c_of(X, A, B):
    """c = mean(B) - X^T mean(A), computed by NumPy from the X returned."""
    return B.mean(axis=0) - np.asarray(X).T @ A.mean(axis=0)


def assert_c(offsets, X, A, B, rtol=SAME):
    assert offsets["mode"] == "estimate" and set(offsets) == {"mode", "c"}, offsets
    want = c_of(X, A, B)
    scale = np.linalg.norm(B.mean(axis=0)) + np.linalg.norm(X) * np.linalg.norm(A.mean(axis=0))
    np.testing.assert_allclose(offsets["c"], want, rtol=0, atol=rtol * scale)


def intercept_evidence(A, B):
    """Least squares with an intercept by NumPy: (the largest |c_j| in standard errors, the largest
    change of X's entries, from the fit without an intercept, in X's standard errors)."""
    m, n = A.shape
    Z = np.column_stack([np.ones(m), A])
    coef, *_ = np.linalg.lstsq(Z, B, rcond=None)
    sigma = np.sqrt(((B - Z @ coef) ** 2).sum(axis=0) / (m - 1 - n))
    cov = np.linalg.inv(Z.T @ Z)
    se = np.sqrt(np.diag(cov))[:, None] * sigma[None, :]
    plain, *_ = np.linalg.lstsq(A, B, rcond=None)
    return np.max(np.abs(coef[0]) / se[0]), np.max(np.abs(plain - coef[1:]) / se[1:])


# ---- estimate: the fit of the centred data -----------------------------------------------------

@pytest.mark.parametrize("method", ["ls", "procrustes", "spd-tls"])
def test_estimate_is_the_fit_of_the_centred_data(spdfit, files, method):
    est = fit_json(spdfit, "--method", method, "--offsets", "estimate", *paths(files, "A_off", "B_off"))
    ref = fit_json(spdfit, "--method", method, *paths(files, "A_c", "B_c"))
    assert_same_x(est, ref)
    assert "offsets" not in ref  # none: no key
    assert_c(est["offsets"], est["X"], files["A_off"], files["B_off"])
    # The offsets matter here: the fit of the data as given is another X.
    plain = fit_json(spdfit, "--method", method, *paths(files, "A_off", "B_off"))
    assert np.linalg.norm(np.subtract(plain["X"], ref["X"])) > 1e-3 * np.linalg.norm(ref["X"])


def test_estimate_with_ls_is_lstsq_with_an_intercept(spdfit, files):
    A, B = files["A_off"], files["B_off"]
    coef, *_ = np.linalg.lstsq(np.column_stack([np.ones(len(A)), A]), B, rcond=None)
    est = fit_json(spdfit, "--method", "ls", "--offsets", "estimate", *paths(files, "A_off", "B_off"))
    assert_same_x(est["X"], coef[1:])
    np.testing.assert_allclose(est["offsets"]["c"], coef[0], rtol=SAME, atol=0)


def test_report_has_an_offsets_line(spdfit, files):
    r = spdfit("fit", "--method", "ls", "--report", "--offsets", "estimate", *paths(files, "A_off", "B_off"))
    assert r.returncode == 0, r.stderr
    assert any(line.startswith("offsets:") for line in r.stdout.splitlines()), r.stdout
    r = spdfit("fit", "--method", "spd-tls", "--report", "--offsets", "rest",
               "--rest-a", files["rest_A_path"], "--rest-b", files["rest_B_path"], *paths(files, "A_off", "B_off"))
    assert r.returncode == 0, r.stderr
    assert any(line.startswith("offsets:") for line in r.stdout.splitlines()), r.stdout
    r = spdfit("fit", "--method", "ls", "--report", *paths(files, "A_c", "B_c"))
    assert r.returncode == 0, r.stderr
    assert not any(line.startswith("offsets:") for line in r.stdout.splitlines()), r.stdout


# ---- estimate: invariant to constants added to the columns ---------------------------------------

@pytest.mark.parametrize("how", [[], ["--stream", "--block-rows", "7"], ["--stream", "--block-rows", "1000"]],
                         ids=["memory", "stream-7", "stream-1000"])
@pytest.mark.parametrize("method", ["ls", "spd-tls"])
def test_estimate_is_invariant_to_large_constants(spdfit, files, method, how):
    want = fit_json(spdfit, "--method", method, "--offsets", "estimate", *paths(files, "A_off", "B_off"))
    same = fit_json(spdfit, "--method", method, "--offsets", "estimate", *how, *paths(files, "A_off", "B_off"))
    big = fit_json(spdfit, "--method", method, "--offsets", "estimate", *how, *paths(files, "A_big", "B_big"))
    assert_same_x(same, want)
    assert_same_x(big, want)
    assert_c(same["offsets"], same["X"], files["A_off"], files["B_off"])
    assert_c(big["offsets"], big["X"], files["A_big"], files["B_big"])


@pytest.mark.parametrize("how", [[], ["--stream"]], ids=["memory", "stream"])
@pytest.mark.parametrize("method", ["ls", "spd-tls"])
def test_bootstrap_with_estimate_is_invariant_to_large_constants(spdfit, files, method, how):
    args = ["--method", method, "--offsets", "estimate", "--bootstrap", "20", "--seed", "3", *how]
    want = fit_json(spdfit, *args, *paths(files, "A_off", "B_off"))
    big = fit_json(spdfit, *args, *paths(files, "A_big", "B_big"))
    assert_same_x(big, want)
    assert np.all(np.asarray(want["standard_errors"]) > 0)
    np.testing.assert_allclose(big["standard_errors"], want["standard_errors"], rtol=1e-8, atol=0)
    # Shifted by the columns' means instead (NumPy's centred files): the same again.
    centred = fit_json(spdfit, *args, *paths(files, "A_c", "B_c"))
    np.testing.assert_allclose(want["standard_errors"], centred["standard_errors"], rtol=1e-8, atol=0)


# ---- rest: the rest rows' means subtracted -------------------------------------------------------

@pytest.mark.parametrize("how", [[], ["--stream", "--block-rows", "7"]], ids=["memory", "stream-7"])
@pytest.mark.parametrize("method", ["ls", "spd-tls", "auto"])
def test_rest_subtracts_the_rest_means(spdfit, files, method, how):
    rest = ["--rest-a", files["rest_A_path"], "--rest-b", files["rest_B_path"]]
    got = fit_json(spdfit, "--method", method, "--offsets", "rest", *rest, *how, *paths(files, "A_off", "B_off"))
    want = fit_json(spdfit, "--method", method, *rest, *paths(files, "A_t", "B_t"))
    assert got["method"] == want["method"]
    assert_same_x(got, want)
    assert got["offsets"]["mode"] == "rest" and set(got["offsets"]) == {"mode", "a", "b"}, got["offsets"]
    np.testing.assert_allclose(got["offsets"]["a"], files["mean_rest_A"], rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(got["offsets"]["b"], files["mean_rest_B"], rtol=1e-12, atol=1e-14)
    # The noise model is the rest rows', as without offsets.
    np.testing.assert_allclose(got["diagnostics"]["noise_model"]["cov_b"], want["diagnostics"]["noise_model"]["cov_b"],
                               rtol=1e-12)


@pytest.mark.parametrize("method", ["spd-tls", "ls"])
def test_rest_rows_of_one_log(spdfit, files, method):
    want = fit_json(spdfit, "--method", method, "--offsets", "rest", "--rest-a", files["rest_A_path"], "--rest-b",
                    files["rest_B_path"], *paths(files, "A_off", "B_off"))
    got = fit_json(spdfit, "--method", method, "--offsets", "rest", "--rest-rows", "1:600", *COLS, files["log_path"])
    assert got["m"] == 300
    np.testing.assert_allclose(got["X"], want["X"], rtol=1e-12, atol=0)
    np.testing.assert_allclose(got["offsets"]["a"], files["mean_rest_A"], rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(got["offsets"]["b"], files["mean_rest_B"], rtol=1e-12, atol=1e-14)
    tared = fit_json(spdfit, "--method", method, "--rest-a", files["rest_A_path"], "--rest-b", files["rest_B_path"],
                     *paths(files, "A_t", "B_t"))
    assert_same_x(got, tared)


def test_compare_and_identify_take_offsets(spdfit, files):
    rest = ["--rest-a", files["rest_A_path"], "--rest-b", files["rest_B_path"]]
    cases = [(["--offsets", "estimate"], ("A_off", "B_off"), [], ("A_c", "B_c"), "estimate"),
             (["--offsets", "rest", *rest], ("A_off", "B_off"), rest, ("A_t", "B_t"), "rest")]
    for args, data, ref_args, ref_data, mode in cases:
        got = run_json(spdfit, "compare", *args, *paths(files, *data))["results"]
        want = run_json(spdfit, "compare", *ref_args, *paths(files, *ref_data))["results"]
        assert [r["method"] for r in got] == [r["method"] for r in want]
        for g, w in zip(got, want):
            if w["status"] != "success":
                continue
            assert_same_x(g, w, 1e-9)
            assert g["offsets"]["mode"] == mode, g["method"]
            if mode == "estimate":
                assert_c(g["offsets"], g["X"], files["A_off"], files["B_off"], 1e-9)
        got = run_json(spdfit, "hexapod", "identify", *args, *paths(files, *data))["methods"]
        want = run_json(spdfit, "hexapod", "identify", *ref_args, *paths(files, *ref_data))["methods"]
        assert set(got) == set(want)
        for name, w in want.items():
            if "X" in w:
                assert_same_x(got[name], w, 1e-9)
                assert got[name]["offsets"]["mode"] == mode, name


# ---- the noise estimate counts the degree of freedom of the offsets ------------------------------

@pytest.mark.parametrize("how", [[], ["--stream", "--block-rows", "7"]], ids=["memory", "stream-7"])
def test_tls_noise_estimate_counts_the_lost_degree_of_freedom(spdfit, files, how):
    A, B = files["A_off"], files["B_off"]
    m, n = A.shape
    d = B.shape[1]
    Ac, Bc = A - A.mean(axis=0), B - B.mean(axis=0)
    s = np.linalg.svd(np.hstack([Ac, Bc]), compute_uv=False)
    want = np.sqrt(np.sum(s[-d:] ** 2) / (d * (m - 1 - n)))
    got = fit_json(spdfit, "--method", "tls", "--offsets", "estimate", *how, *paths(files, "A_off", "B_off"))
    assert got["diagnostics"]["noise_sigma"] == pytest.approx(want, rel=1e-9)
    # The centred files without offsets divide by m - n: one degree of freedom more.
    centred = fit_json(spdfit, "--method", "tls", *paths(files, "A_c", "B_c"))
    assert centred["diagnostics"]["noise_sigma"] == pytest.approx(want * np.sqrt((m - 1 - n) / (m - n)), rel=1e-9)


# ---- warnings with the default none --------------------------------------------------------------

@pytest.fixture(scope="module")
def untared(tmp_path_factory):
    """B with a constant load in both the rest rows and the data (never tared), A without offsets
    (its driving motion of mean 0); the same tared; and clean rest rows and data."""
    d = tmp_path_factory.mktemp("untared")
    rng = np.random.default_rng(23)
    m = 300
    A0 = rng.uniform(-5, 5, (m, 3))
    A0 -= A0.mean(axis=0)
    A = A0 + rng.standard_normal((m, 3)) * SD_A
    B_clean = A0 @ X_TRUE + rng.standard_normal((m, 3)) * SD_B
    B = B_clean + OFF_B
    rest_A = rng.standard_normal((600, 3)) * SD_A
    noise_B = rng.standard_normal((600, 3)) * SD_B
    rest_B = OFF_B + noise_B
    # The condition the warning names, by hand: the rest rows' mean of B far from 0, the data's the same.
    rest_se = rest_B.std(axis=0, ddof=1) / np.sqrt(600)
    data_se = B.std(axis=0, ddof=1) / np.sqrt(m)
    assert np.all(np.abs(rest_B.mean(axis=0)) > 5 * rest_se)
    assert np.all(np.abs(B.mean(axis=0) - rest_B.mean(axis=0)) <= 5 * np.hypot(rest_se, data_se))
    return {"A": write(d / "A.csv", A), "B": write(d / "B.csv", B),
            "B_tared": write(d / "B_tared.csv", B - rest_B.mean(axis=0)), "B_clean": write(d / "B_clean.csv", B_clean),
            "rest_A": write(d / "rest_A.csv", rest_A), "rest_B": write(d / "rest_B.csv", rest_B),
            "rest_B_clean": write(d / "rest_B_clean.csv", noise_B)}


def test_the_constructed_data_have_offsets_and_the_clean_data_none(files):
    z_c, z_x = intercept_evidence(files["A_off"], files["B_off"])
    assert z_c > 5 and z_x > 2, (z_c, z_x)
    z_c, z_x = intercept_evidence(files["A_c"], files["B_c"])
    assert not (z_c > 5 and z_x > 2), (z_c, z_x)


@pytest.mark.parametrize("method", ["ls", "spd-tls"])
def test_offsets_taken_for_signal_are_a_warning(spdfit, files, method):
    r = spdfit("fit", "--method", method, *paths(files, "A_off", "B_off"))
    assert r.returncode == 0, r.stderr
    assert "--offsets estimate" in r.stderr, r.stderr
    assert "`offsets`" not in r.stderr  # spelled as the command line's option
    clean = spdfit("fit", "--method", method, *paths(files, "A_c", "B_c"))
    assert clean.returncode == 0, clean.stderr
    assert "--offsets" not in clean.stderr, clean.stderr
    # Fitted with the offsets, nothing to warn of.
    est = spdfit("fit", "--method", method, "--offsets", "estimate", *paths(files, "A_off", "B_off"))
    assert est.returncode == 0 and "--offsets" not in est.stderr, est.stderr


@pytest.mark.parametrize("command", [["compare"], ["hexapod", "identify"]], ids=["compare", "identify"])
def test_offsets_warning_is_said_once_for_every_estimator(spdfit, files, command):
    r = spdfit(*command, *paths(files, "A_off", "B_off"))
    assert r.returncode == 0, r.stderr
    assert r.stderr.count("--offsets estimate") == 1, r.stderr
    clean = spdfit(*command, *paths(files, "A_c", "B_c"))
    assert clean.returncode == 0 and "--offsets" not in clean.stderr, clean.stderr
    est = spdfit(*command, "--offsets", "estimate", *paths(files, "A_off", "B_off"))
    assert est.returncode == 0 and "--offsets" not in est.stderr, est.stderr


@pytest.mark.parametrize("method", ["spd-tls", "ls"])
def test_untared_b_is_a_warning(spdfit, untared, method):
    r = spdfit("fit", "--method", method, "--rest-a", untared["rest_A"], "--rest-b", untared["rest_B"], untared["A"],
               untared["B"])
    assert r.returncode == 0, r.stderr
    assert "--offsets rest" in r.stderr, r.stderr
    tared = spdfit("fit", "--method", method, "--rest-a", untared["rest_A"], "--rest-b", untared["rest_B"],
                   untared["A"], untared["B_tared"])
    assert tared.returncode == 0 and "--offsets" not in tared.stderr, tared.stderr
    clean = spdfit("fit", "--method", method, "--rest-a", untared["rest_A"], "--rest-b", untared["rest_B_clean"],
                   untared["A"], untared["B_clean"])
    assert clean.returncode == 0 and "--offsets" not in clean.stderr, clean.stderr
    # With --offsets rest the load is taken out: no warning.
    fixed = spdfit("fit", "--method", method, "--offsets", "rest", "--rest-a", untared["rest_A"], "--rest-b",
                   untared["rest_B"], untared["A"], untared["B"])
    assert fixed.returncode == 0 and "--offsets" not in fixed.stderr, fixed.stderr


# ---- errors ------------------------------------------------------------------------------------

@pytest.mark.parametrize("command", [["fit", "--method", "spd-tls"], ["fit", "--method", "spd-tls", "--stream"],
                                     ["compare"], ["hexapod", "identify"]],
                         ids=["fit", "fit-stream", "compare", "identify"])
def test_rest_without_rest_rows_is_a_usage_error(spdfit, files, command):
    r = spdfit(*command, "--offsets", "rest", *paths(files, "A_off", "B_off"))
    assert r.returncode == 2, r.stderr
    # Naming the option and where rest rows come from (--rest-a/--rest-b, --rest-rows).
    assert "--offsets" in r.stderr, r.stderr
    assert any(words in r.stderr for words in ("rest rows", "--rest-rows", "--rest-a")), r.stderr


@pytest.mark.parametrize("command", [["fit", "--method", "ls"], ["compare"], ["hexapod", "identify"]],
                         ids=["fit", "compare", "identify"])
def test_an_unknown_mode_is_a_usage_error(spdfit, files, command):
    r = spdfit(*command, "--offsets", "bogus", *paths(files, "A_off", "B_off"))
    assert r.returncode == 2, r.stderr
    assert "--offsets" in r.stderr, r.stderr


@pytest.mark.parametrize("how", [[], ["--stream"]], ids=["memory", "stream"])
def test_estimate_with_m_equal_n_is_a_data_error(spdfit, files, how):
    d = files["dir"]
    a, b = write(d / "A3.csv", files["A_off"][:3]), write(d / "B3.csv", files["B_off"][:3])
    assert spdfit("fit", "--method", "ls", *how, a, b).returncode == 0  # without offsets, m = n fits
    r = spdfit("fit", "--method", "ls", "--offsets", "estimate", *how, a, b)
    assert r.returncode == 1, r.stderr
    assert "offsets" in r.stderr, r.stderr


def test_estimate_with_the_physical_fit_reports_its_constants(spdfit, tmp_path):
    # (Its numbers against the fit of the centred data: tests/hexapod/test_logged_hexapod.py.)
    g = tmp_path / "g.json"
    assert spdfit("hexapod", "model", "--write-geometry", g).returncode == 0
    sim = spdfit("hexapod", "simulate", "--geometry", g, "--samples", 60, "--noise-var", 0.5, "--seed", 4, "--out",
                 tmp_path / "run")
    assert sim.returncode == 0, sim.stderr
    data = [tmp_path / "run" / "A.csv", tmp_path / "run" / "B.csv"]
    ok = spdfit("hexapod", "identify", "--physical", "--geometry", g, *data)
    assert ok.returncode == 0, ok.stderr
    r = spdfit("hexapod", "identify", "--physical", "--geometry", g, "--offsets", "estimate", "--json", *data)
    assert r.returncode == 0, r.stderr
    physical = json.loads(r.stdout)["physical"]
    assert physical["offsets"]["mode"] == "estimate" and len(physical["offsets"]["c"]) == 6
    report = spdfit("hexapod", "identify", "--physical", "--geometry", g, "--offsets", "estimate", *data)
    assert "offsets: estimated with the payload" in report.stdout, report.stdout
