"""The noise model on the command line: fit's three sources (--rest-a/--rest-b, --noise-std-a/-b,
--noise-cov-a/-b), their exclusions (usage errors, exit 2), bad files and values (exit 1 or 2 with a
message naming the option and the file), the JSON's noise_model and --report's line, and the same
options on compare, hexapod identify, --stream and --bootstrap.

References: the rest files' model equals the covariance files holding NumPy's sample covariances
of the same rows (np.cov, divisor N - 1), and the standard deviations equal the diagonal
covariances they stand for, to rounding."""
import json

import numpy as np
import pytest

# X from different sources of one model: the same arithmetic after the covariances, which agree to
# a few ulps (NumPy's np.cov against spdfit's streamed moments); the likelihood fit's Newton
# iterations converge to the same minimizer to ~1e-10 relative.
SAME_MODEL_RTOL = 1e-8

STD_A = [0.2, 0.4, 0.8]
STD_B = [3.0, 1.0, 0.3]
TRUE_X = np.array([[3.0, 1.0, 0.5], [1.0, 2.0, 0.2], [0.5, 0.2, 1.5]])


def write(path, M):
    np.savetxt(path, np.atleast_2d(M), delimiter=",", fmt="%.17g")
    return path


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """A, B (m = 200, per-column noise) and 400 rest rows of each, with a constant load in B."""
    d = tmp_path_factory.mktemp("noise")
    rng = np.random.default_rng(11)
    A0 = rng.uniform(-5, 5, (200, 3))
    A = A0 + rng.standard_normal(A0.shape) * STD_A
    B = A0 @ TRUE_X + rng.standard_normal(A0.shape) * STD_B
    rest_A = rng.standard_normal((400, 3)) * STD_A
    rest_B = np.array([5.0, -2.0, 1.0]) + rng.standard_normal((400, 3)) * STD_B
    out = {"A": write(d / "A.csv", A), "B": write(d / "B.csv", B), "rest_A": write(d / "rest_A.csv", rest_A),
           "rest_B": write(d / "rest_B.csv", rest_B),
           "cov_A": write(d / "cov_A.csv", np.cov(rest_A, rowvar=False)),
           "cov_B": write(d / "cov_B.csv", np.cov(rest_B, rowvar=False)),
           "diag_A": write(d / "diag_A.csv", np.diag(np.square(STD_A))),
           "diag_B": write(d / "diag_B.csv", np.diag(np.square(STD_B))), "dir": d}
    return out


def fit_json(spdfit, files, *options, method="spd-tls"):
    r = spdfit("fit", "--method", method, "--json", *options, files["A"], files["B"])
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def rest(files):
    return ["--rest-a", files["rest_A"], "--rest-b", files["rest_B"]]


def test_rest_files_give_the_sample_covariances(spdfit, files):
    out = fit_json(spdfit, files, *rest(files))
    model = out["diagnostics"]["noise_model"]
    assert model["source"] == "rest" and model["rest_rows"] == 400
    rest_A = np.loadtxt(files["rest_A"], delimiter=",")
    assert np.allclose(model["cov_a"], np.cov(rest_A, rowvar=False), rtol=1e-12, atol=0)
    by_cov = fit_json(spdfit, files, "--noise-cov-a", files["cov_A"], "--noise-cov-b", files["cov_B"])
    assert by_cov["diagnostics"]["noise_model"]["source"] == "cov"
    assert np.allclose(out["X"], by_cov["X"], rtol=SAME_MODEL_RTOL, atol=0)


def test_standard_deviations_are_the_diagonal_covariances(spdfit, files):
    by_std = fit_json(spdfit, files, "--noise-std-a", ",".join(map(str, STD_A)), "--noise-std-b",
                      ",".join(map(str, STD_B)))
    model = by_std["diagnostics"]["noise_model"]
    assert model["source"] == "std"
    assert np.allclose(model["cov_b"], np.diag(np.square(STD_B)), rtol=1e-15, atol=0)
    by_cov = fit_json(spdfit, files, "--noise-cov-a", files["diag_A"], "--noise-cov-b", files["diag_B"])
    assert np.allclose(by_std["X"], by_cov["X"], rtol=SAME_MODEL_RTOL, atol=0)
    # One value per side stands for every column.
    one = fit_json(spdfit, files, "--noise-std-a", "0.5", "--noise-std-b", "2")
    assert np.allclose(one["diagnostics"]["noise_model"]["cov_a"], 0.25 * np.eye(3), rtol=1e-15, atol=0)


def test_without_a_model_json_and_report_say_assumed_equal(spdfit, files):
    out = fit_json(spdfit, files, method="auto")
    assert out["diagnostics"]["noise_model"] == {"source": "assumed-equal"}
    assert "assumed equal noise in every column of A and B" in out["diagnostics"]["reason"]["text"]
    r = spdfit("fit", "--method", "auto", "--report", files["A"], files["B"])
    lines = [line for line in r.stdout.splitlines() if line.startswith("noise model:")]
    assert len(lines) == 1 and "assumed-equal" in lines[0]


def test_report_prints_the_model_in_one_line(spdfit, files):
    r = spdfit("fit", "--method", "spd-tls", "--report", *rest(files), files["A"], files["B"])
    assert r.returncode == 0, r.stderr
    lines = [line for line in r.stdout.splitlines() if line.startswith("noise model:")]
    assert len(lines) == 1
    assert "rest (400 rows of" in lines[0] and "rest_A.csv" in lines[0] and "noise std in A" in lines[0]


def test_auto_names_the_noise_source(spdfit, files):
    out = fit_json(spdfit, files, *rest(files), method="auto")
    assert out["diagnostics"]["noise_model"]["source"] == "rest"
    assert "rest" in out["diagnostics"]["reason"]["text"]


@pytest.mark.parametrize("options", [
    ["--rest-a", "R", "--rest-b", "R", "--noise-std-a", "1", "--noise-std-b", "1"],
    ["--noise-std-a", "1", "--noise-std-b", "1", "--noise-cov-a", "R", "--noise-cov-b", "R"],
    ["--noise-std-a", "1", "--noise-std-b", "1", "--noise-ratio", "1"],
    ["--rest-a", "R", "--rest-b", "R", "--noise-ratio", "1"],
    ["--noise-cov-a", "R", "--noise-cov-b", "R", "--noise-ratio", "2"],
])
def test_sources_exclude_each_other_and_the_noise_ratio(spdfit, files, options):
    options = [str(files["rest_A"]) if o == "R" else o for o in options]
    r = spdfit("fit", "--method", "spd-tls", *options, files["A"], files["B"])
    assert r.returncode == 2, r.stderr
    assert "excludes" in r.stderr or "not both" in r.stderr


@pytest.mark.parametrize("given,missing", [(["--rest-a", "R"], "--rest-b"), (["--noise-std-b", "1"], "--noise-std-a"),
                                           (["--noise-cov-a", "R"], "--noise-cov-b")])
def test_a_source_needs_both_sides(spdfit, files, given, missing):
    given = [str(files["rest_A"]) if o == "R" else o for o in given]
    r = spdfit("fit", "--method", "spd-tls", *given, files["A"], files["B"])
    assert r.returncode == 2 and missing in r.stderr


def test_spde_with_a_noise_model_is_a_usage_error_naming_auto_and_spd_tls(spdfit, files):
    r = spdfit("fit", "--method", "spde", *rest(files), files["A"], files["B"])
    assert r.returncode == 2
    assert "--rest-a" in r.stderr and "auto" in r.stderr and "spd-tls" in r.stderr and "not to spde" in r.stderr


@pytest.mark.parametrize("value,words", [("0.2,-1,0.3", "each a finite number >= 0"), ("0.2,,1", "comma-separated"),
                                         ("x", "comma-separated")])
def test_bad_standard_deviations_are_usage_errors(spdfit, files, value, words):
    r = spdfit("fit", "--method", "spd-tls", "--noise-std-a", value, "--noise-std-b", "1", files["A"], files["B"])
    assert r.returncode == 2 and "--noise-std-a" in r.stderr and words in r.stderr


def test_standard_deviations_of_the_wrong_length(spdfit, files):
    r = spdfit("fit", "--method", "spd-tls", "--noise-std-a", "1,2", "--noise-std-b", "1", files["A"], files["B"])
    assert r.returncode in (1, 2) and "--noise-std-a" in r.stderr and "2 values" in r.stderr


def test_a_rest_file_with_another_column_count(spdfit, files, tmp_path):
    wide = write(tmp_path / "wide.csv", np.random.default_rng(1).standard_normal((50, 4)))
    narrow = write(tmp_path / "narrow.csv", np.random.default_rng(2).standard_normal((50, 3)))
    r = spdfit("fit", "--method", "spd-tls", "--rest-a", wide, "--rest-b", narrow, files["A"], files["B"])
    assert r.returncode == 1 and str(wide) in r.stderr and "--rest-a" in r.stderr and "4 columns" in r.stderr


def test_rest_files_of_different_lengths(spdfit, files, tmp_path):
    short = write(tmp_path / "short.csv", np.random.default_rng(2).standard_normal((30, 3)))
    r = spdfit("fit", "--method", "spd-tls", "--rest-a", files["rest_A"], "--rest-b", short, files["A"], files["B"])
    assert r.returncode == 1 and str(short) in r.stderr and "--rest-b" in r.stderr


def test_few_rest_rows_warn(spdfit, files, tmp_path):
    rng = np.random.default_rng(3)
    a = write(tmp_path / "ra.csv", rng.standard_normal((12, 3)) * STD_A)
    b = write(tmp_path / "rb.csv", rng.standard_normal((12, 3)) * STD_B)
    r = spdfit("fit", "--method", "spd-tls", "--rest-a", a, "--rest-b", b, files["A"], files["B"])
    assert r.returncode == 0 and "fewer than" in r.stderr


@pytest.mark.parametrize("rows", [2, 3])
def test_too_few_rest_rows_for_the_columns_say_so(spdfit, files, tmp_path, rows):
    # It was "both are singular (exact columns or directions in A and in B)" (issue 45).
    rng = np.random.default_rng(4)
    a = write(tmp_path / "ra.csv", rng.standard_normal((rows, 3)) * STD_A)
    b = write(tmp_path / "rb.csv", rng.standard_normal((rows, 3)) * STD_B)
    r = spdfit("fit", "--method", "spd-tls", "--rest-a", a, "--rest-b", b, files["A"], files["B"])
    # a data error, as one rest row is (it was 2, a usage error, before 2026-12-02)
    assert r.returncode == 1, r.stderr
    assert f"{rows} rest rows for 3 columns (--rest-a, --rest-b): their sample covariances are singular" in r.stderr
    assert "record more rest rows: at least 4" in r.stderr and "exact columns" not in r.stderr
    # the rest segment of the log itself: named by the option given
    log = write(tmp_path / "log.csv", np.vstack([
        np.hstack([rng.standard_normal((rows, 3)) * STD_A, rng.standard_normal((rows, 3)) * STD_B]),
        np.hstack([np.loadtxt(files["A"], delimiter=",", ndmin=2), np.loadtxt(files["B"], delimiter=",", ndmin=2)])]))
    r = spdfit("fit", "--method", "spd-tls", "--rest-rows", f"1:{rows}", "--a-cols", "1:3", "--b-cols", "4:6", log)
    assert r.returncode == 1, r.stderr
    assert f"{rows} rest rows for 3 columns (--rest-rows): their sample covariances" in r.stderr, r.stderr
    assert "--rest-a" not in r.stderr and "give more rest rows in --rest-rows: at least 4" in r.stderr
    # tls needs B's covariance definite: the same diagnosis (it said "B has exact columns ... use spd-tls")
    r = spdfit("fit", "--method", "tls", "--rest-rows", f"1:{rows}", "--a-cols", "1:3", "--b-cols", "4:6", log)
    assert r.returncode == 1, r.stderr
    assert f"{rows} rest rows for 3 columns (--rest-rows)" in r.stderr and "needs B's positive definite" in r.stderr
    assert "exact columns" not in r.stderr, r.stderr


def test_one_rest_row_of_a_log_names_the_segment(spdfit, files, tmp_path):
    rng = np.random.default_rng(5)
    A = np.loadtxt(files["A"], delimiter=",", ndmin=2)
    B = np.loadtxt(files["B"], delimiter=",", ndmin=2)
    log = write(tmp_path / "log.csv", np.vstack([np.hstack([0.01 * rng.standard_normal((1, 3)), B[:1]]),
                                                 np.hstack([A, B])]))
    r = spdfit("fit", "--method", "spd-tls", "--rest-rows", "1", "--a-cols", "1:3", "--b-cols", "4:6", log)
    assert r.returncode == 1, r.stderr
    assert ("--rest-rows '1': A's rest segment has 1 row(s): a covariance needs at least 2" in r.stderr), r.stderr


@pytest.mark.parametrize("bad,words", [
    (np.array([[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]), "not symmetric"),
    (np.array([[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]]), "not positive semidefinite"),
    (np.eye(2), "is 2x2 but A has 3 columns"),
])
def test_bad_covariance_files_name_the_option_and_the_file(spdfit, files, tmp_path, bad, words):
    path = write(tmp_path / "bad_cov.csv", bad)
    r = spdfit("fit", "--method", "spd-tls", "--noise-cov-a", path, "--noise-cov-b", files["diag_B"], files["A"],
               files["B"])
    assert r.returncode == 1, r.stderr
    assert str(path) in r.stderr and "--noise-cov-a" in r.stderr and words in r.stderr


def test_stream_and_bootstrap_take_the_model(spdfit, files):
    whole = fit_json(spdfit, files, *rest(files))
    streamed = fit_json(spdfit, files, *rest(files), "--stream", "--block-rows", "64")
    assert streamed["diagnostics"]["noise_model"]["source"] == "rest"
    assert np.allclose(whole["X"], streamed["X"], rtol=SAME_MODEL_RTOL, atol=0)
    boot = fit_json(spdfit, files, *rest(files), "--bootstrap", "20", "--threads", "1")
    assert boot["diagnostics"]["noise_model"]["source"] == "rest"
    assert np.array_equal(boot["X"], whole["X"]) and np.all(np.array(boot["standard_errors"]) > 0)


def test_compare_takes_the_model_and_runs_spde_without_it(spdfit, files):
    r = spdfit("compare", "--json", *rest(files), files["A"], files["B"])
    assert r.returncode == 0, r.stderr
    results = {x["method"]: x for x in json.loads(r.stdout)["results"]}
    assert results["spd-tls"]["diagnostics"]["noise_model"]["source"] == "rest"
    assert results["spde"]["diagnostics"]["noise_model"]["source"] == "assumed-equal"
    alone = fit_json(spdfit, files, *rest(files))
    assert np.allclose(results["spd-tls"]["X"], alone["X"], rtol=SAME_MODEL_RTOL, atol=0)
    r = spdfit("compare", "--noise-ratio", "1", *rest(files), files["A"], files["B"])
    assert r.returncode == 2


def test_hexapod_simulate_writes_rest_rows_and_identify_uses_them(spdfit, tmp_path):
    out = tmp_path / "sim"
    r = spdfit("hexapod", "simulate", "--samples", "300", "--noise-std-a", "0.2,0.4,0.8,0.2,0.4,0.8",
               "--noise-std-b", "3,1,0.3,3,1,0.3", "--distribution", "gaussian", "--rest-samples", "500",
               "--scale-b", "0.001", "--seed", "3", "--out", out)
    assert r.returncode == 0, r.stderr
    rest_A = np.loadtxt(out / "rest_A.csv", delimiter=",")
    rest_B = np.loadtxt(out / "rest_B.csv", delimiter=",")
    assert rest_A.shape == (500, 6) and rest_B.shape == (500, 6)
    # The rest rows' spread is the noise asked for (B's in kN): a loose check of the writing, the
    # generator's statistics are the library's tests'.
    assert np.allclose(rest_A.std(axis=0, ddof=1), [0.2, 0.4, 0.8, 0.2, 0.4, 0.8], rtol=0.2)
    assert np.allclose(rest_B.std(axis=0, ddof=1), 1e-3 * np.array([3, 1, 0.3, 3, 1, 0.3]), rtol=0.2)
    settings = json.loads((out / "simulation.json").read_text())
    assert settings["rest_samples"] == 500 and settings["files"]["rest_A"] == "rest_A.csv"
    assert "--rest-a" in r.stdout
    r = spdfit("hexapod", "identify", "--json", out / "A.csv", out / "B.csv", "--truth", out / "truth.csv",
               "--rest-a", out / "rest_A.csv", "--rest-b", out / "rest_B.csv")
    assert r.returncode == 0, r.stderr
    assert "rest" in r.stdout


def test_hexapod_simulate_needs_a_noise(spdfit, tmp_path):
    r = spdfit("hexapod", "simulate", "--out", tmp_path / "x")
    assert r.returncode == 2 and "--noise-var" in r.stderr
    r = spdfit("hexapod", "simulate", "--noise-var", "1", "--noise-std-a", "1", "--noise-std-b", "1",
               "--out", tmp_path / "x")
    assert r.returncode == 2


def test_experiment_thesis_fits_with_each_noise_model(spdfit):
    r = spdfit("experiment", "thesis", "--samples", "100", "--noise-std-a", "0.2,0.4,0.8,0.2,0.4,0.8",
               "--noise-std-b", "3,1,0.3,3,1,0.3", "--distribution", "gaussian", "--rest-samples", "200",
               "--fit-noise", "none,true,rest", "--methods", "psd-ls,spd-tls", "--trials", "4", "--threads", "1",
               "--json")
    assert r.returncode == 0, r.stderr
    methods = json.loads(r.stdout)["methods"]
    assert set(methods) == {"psd-ls", "spd-tls", "psd-ls/true", "spd-tls/true", "psd-ls/rest", "spd-tls/rest"}
    r = spdfit("experiment", "thesis", "--noise-var", "1", "--fit-noise", "rest", "--trials", "2")
    assert r.returncode == 2 and "--rest-samples" in r.stderr


# ---- warnings that agree with the method chosen and the noise model (issue 45 item 1) ------------

@pytest.fixture(scope="module")
def quiet_a(tmp_path_factory):
    """docs/matlab.md's noise-model example: A's noise (0.01) negligible against its signal, B's
    per column (3, 1, 0.3), 2000 rest rows with a constant load in B."""
    d = tmp_path_factory.mktemp("quiet_a")
    t = np.arange(1, 301)[:, None]
    A0 = np.hstack([np.sin(0.7 * t), np.cos(1.3 * t), np.sin(2.9 * t + 1)])
    A = A0 + 0.01 * np.cos(t * [4.3, 9.1, 6.7])
    B = A0 @ np.array([[4, 1, 0.5], [1, 3, 0.2], [0.5, 0.2, 2]]) + np.array([3, 1, 0.3]) * np.sin(t * [5.1, 3.7, 8.3])
    r = np.arange(1, 2001)[:, None]
    rest_A = 0.01 * np.cos(r * [4.3, 9.1, 6.7])
    rest_B = np.array([10, -5, 2]) + np.array([3, 1, 0.3]) * np.sin(r * [5.1, 3.7, 8.3])
    return {"A": write(d / "A.csv", A), "B": write(d / "B.csv", B), "rest_A": write(d / "rest_A.csv", rest_A),
            "rest_B": write(d / "rest_B.csv", rest_B)}


def least_squares_bias(files):
    """The bias that the rest rows' Sigma_A gives least squares, in its standard errors (root mean
    square over X's entries), by the Kronecker form: vec(b)^T (W (x) (A^T A)^-1)^-1 vec(b) =
    tr(b^T A^T A b W^-1), b = m (A^T A)^-1 Sigma_A X, W = X Sigma_A X + Sigma_B."""
    A, B = (np.loadtxt(files[k], delimiter=",") for k in ("A", "B"))
    Sa, Sb = (np.cov(np.loadtxt(files[k], delimiter=","), rowvar=False) for k in ("rest_A", "rest_B"))
    X = np.linalg.lstsq(A, B, rcond=None)[0]
    X = (X + X.T) / 2
    G = A.T @ A
    b = A.shape[0] * np.linalg.solve(G, Sa @ X)
    chi = np.trace(b.T @ G @ b @ np.linalg.inv(X @ Sa @ X + Sb))
    return np.sqrt(chi / X.size)


def warning_lines(stderr):
    return [line for line in stderr.splitlines() if line.startswith("spdfit: warning:")]


def test_auto_choosing_psd_ls_warns_nothing_against_it(spdfit, quiet_a):
    assert least_squares_bias(quiet_a) < 0.1  # negligible: a small fraction of a standard error
    out = fit_json(spdfit, quiet_a, *rest(quiet_a), method="auto")
    assert out["diagnostics"]["reason"]["code"] == "noise_in_b"
    assert out["warnings"] == []
    report = spdfit("fit", "--method", "auto", "--report", *rest(quiet_a), quiet_a["A"], quiet_a["B"])
    assert report.returncode == 0, report.stderr
    assert warning_lines(report.stderr) == []
    # The equal-noise model's sigma is not printed beside the noise model it would contradict.
    assert "in every entry of A" not in report.stdout and "noise model: rest" in report.stdout
    # psd-ls chosen by hand: the same rule as auto's, so no notice either.
    psd = spdfit("fit", "--method", "psd-ls", *rest(quiet_a), quiet_a["A"], quiet_a["B"])
    assert psd.returncode == 0 and warning_lines(psd.stderr) == [], psd.stderr


@pytest.mark.parametrize("method", ["ls", "procrustes", "psd-ls"])
def test_methods_that_ignore_noise_in_a_say_by_how_much(spdfit, files, method):
    expected = least_squares_bias(files)
    assert expected > 1.0  # STD_A biases least squares by more than a standard error here
    r = spdfit("fit", "--method", method, *rest(files), files["A"], files["B"])
    assert r.returncode == 0, r.stderr
    [notice] = [line for line in warning_lines(r.stderr) if "models noise in B only" in line]
    printed = float(notice.split("by about ")[1].split(" standard errors")[0])
    assert printed == pytest.approx(expected, rel=5e-3), notice
    # auto's rule agrees: it does not choose a method that models noise in B only here.
    assert fit_json(spdfit, files, *rest(files), method="auto")["diagnostics"]["reason"]["code"] != "noise_in_b"


def test_identify_states_each_fact_once_and_uses_the_model(spdfit, files, quiet_a):
    r = spdfit("hexapod", "identify", "--bootstrap", "30", *rest(files), files["A"], files["B"])
    assert r.returncode == 0, r.stderr
    lines = warning_lines(r.stderr)
    [notice] = [line for line in lines if "models noise in B only" in line]
    assert notice.startswith("spdfit: warning: ls, procrustes, psd-ls: each models noise in B only"), notice
    assert len(lines) == len(set(lines)) and not any("cannot tell A's from B's" in line for line in lines), lines
    quiet = spdfit("hexapod", "identify", "--bootstrap", "30", *rest(quiet_a), quiet_a["A"], quiet_a["B"])
    assert quiet.returncode == 0, quiet.stderr
    # Only spde's: it runs without the model.
    assert [line.split(":")[2].strip() for line in warning_lines(quiet.stderr)] == ["spde"], quiet.stderr
