"""`spdfit nearest` as covariance repair: the relative default floor (the output factors),
--min-eig 0 as the plain projection, --min-eig-rel, --keep-diag and --via-corr, the JSON keys
every repair reports, scaling, and the warnings and errors a user meets."""
import json

import numpy as np
import pytest

from spdfit_testing import indefinite_covariance, pairwise_covariance, sensor_log


def save(tmp_path, name, M):
    path = tmp_path / name
    np.savetxt(path, M, delimiter=",", fmt="%.17g")
    return path


def parse(stdout):
    return np.array([[float(v) for v in line.split(",")] for line in stdout.splitlines()])


def clip(C, floor):
    lam, V = np.linalg.eigh((C + C.T) / 2)
    return (V * np.maximum(lam, floor)) @ V.T


def test_default_floor_is_relative_and_the_output_factors(spdfit, tmp_path):
    C = indefinite_covariance(12, 1)
    path = save(tmp_path, "C.csv", C)
    j = json.loads(spdfit("nearest", "--json", path).stdout)
    floor = 1e-8 * np.linalg.eigvalsh(C)[-1]
    assert j["min_eig_rel"] == 1e-8 and j["min_eig"] == pytest.approx(floor, rel=1e-13)
    assert j["cholesky"] and j["converged"] and j["iterations"] == 0 and j["clipped"] > 0
    X = parse(spdfit("nearest", path).stdout)
    np.testing.assert_allclose(X, clip(C, floor), atol=1e-14 * np.abs(C).max())
    np.linalg.cholesky(X)
    # --min-eig 0: the plain projection, whose Cholesky factorization fails.
    j0 = json.loads(spdfit("nearest", "--min-eig", "0", "--json", path).stdout)
    assert j0["min_eig"] == 0 and j0["min_eig_rel"] is None and not j0["cholesky"]
    np.testing.assert_allclose(np.array(j0["X"]), clip(C, 0.0), atol=1e-14 * np.abs(C).max())
    j3 = json.loads(spdfit("nearest", "--min-eig-rel", "1e-3", "--json", path).stdout)
    assert j3["min_eig"] == pytest.approx(1e-3 * np.linalg.eigvalsh(C)[-1], rel=1e-13)


@pytest.mark.parametrize("flag", ["--keep-diag", "--via-corr", "--corr"])
def test_every_repair_reports_the_same_keys_and_factors(spdfit, tmp_path, flag):
    C = indefinite_covariance(15, 2)
    j = json.loads(spdfit("nearest", flag, "--json", save(tmp_path, "C.csv", C)).stdout)
    for key in ("n", "corr", "keep_diag", "via_corr", "min_eig", "min_eig_rel", "alpha", "X", "distance", "clipped",
                "min_eigenvalue_before", "iterations", "gradient_norm", "converged", "cholesky", "warnings"):
        assert key in j, key
    X = np.array(j["X"])
    assert j["converged"] and j["cholesky"] and j["iterations"] > 0
    # --corr on a covariance warns that the variances were dropped; the others keep them.
    if flag == "--corr":
        assert len(j["warnings"]) == 1 and j["warnings"][0].startswith("the diagonal is not 1")
    else:
        assert j["warnings"] == []
    np.linalg.cholesky(X)
    expected_diagonal = np.ones(15) if flag == "--corr" else np.diag(C)
    assert np.array_equal(np.diag(X), expected_diagonal)
    assert j["min_eigenvalue_before"] == pytest.approx(np.linalg.eigvalsh(C)[0], rel=1e-12)
    assert j["distance"] == pytest.approx(np.linalg.norm(X - C), rel=1e-12)
    assert j[{"--keep-diag": "keep_diag", "--via-corr": "via_corr", "--corr": "corr"}[flag]] is True


def test_keep_diag_is_nearer_than_the_clip_with_the_diagonal_restored(spdfit, tmp_path):
    """Optimality against a feasible competitor: the clip of C rescaled to C's diagonal (what a
    user would do by hand) is admissible, so --keep-diag's answer is at least as near."""
    C = indefinite_covariance(20, 3)
    X = parse(spdfit("nearest", "--keep-diag", "--min-eig", "0", save(tmp_path, "C.csv", C)).stdout)
    P = clip(C, 0.0)
    s = np.sqrt(np.diag(C) / np.diag(P))
    competitor = s[:, None] * P * s[None, :]
    assert np.linalg.norm(X - C) <= np.linalg.norm(competitor - C)
    assert np.linalg.eigvalsh(X)[0] >= -1e-12


def test_via_corr_equals_keep_diag_weighted_by_the_inverse_variances(spdfit, tmp_path):
    C = indefinite_covariance(10, 4)
    path = save(tmp_path, "C.csv", C)
    weights = save(tmp_path, "w.csv", 1 / np.diag(C))
    via = parse(spdfit("nearest", "--via-corr", "--min-eig", "0", path).stdout)
    kept = parse(spdfit("nearest", "--keep-diag", "--min-eig", "0", "--weights", weights, path).stdout)
    np.testing.assert_allclose(via, kept, atol=1e-9)


def test_scaling_the_input_scales_the_answer(spdfit, tmp_path):
    C = indefinite_covariance(9, 5)
    for flag in ([], ["--keep-diag"], ["--via-corr"]):
        X = parse(spdfit("nearest", *flag, save(tmp_path, "C.csv", C)).stdout)
        X4 = parse(spdfit("nearest", *flag, save(tmp_path, "C4.csv", 4 * C)).stdout)
        assert np.array_equal(X4, 4 * X), flag


def test_an_absolute_floor_far_above_the_matrix_warns(spdfit, tmp_path):
    path = save(tmp_path, "C.csv", indefinite_covariance(6, 6, scale=1e-8))
    out = spdfit("nearest", "--min-eig", "1e-6", path)
    assert out.returncode == 0 and "more than the repair itself" in out.stderr
    assert "more than the repair itself" not in spdfit("nearest", path).stderr


def test_asymmetric_input_warns(spdfit, tmp_path):
    C = indefinite_covariance(5, 8)
    C[0, 1] += 0.3
    out = spdfit("nearest", "--json", save(tmp_path, "C.csv", C))
    assert out.returncode == 0 and "not symmetric" in out.stderr
    assert any("not symmetric" in w for w in json.loads(out.stdout)["warnings"])


@pytest.mark.parametrize("matrix, args, message", [
    (-np.eye(3), [], "no positive eigenvalue"),
    (np.diag([1.0, 0.0, 2.0]), ["--via-corr"], "diagonal entry 2"),
    (np.diag([1.0, 0.5, 2.0]), ["--keep-diag", "--min-eig", "0.5"], "not below diagonal entry 2"),
    (np.eye(3), ["--corr", "--min-eig", "1"], "not below diagonal entry 1"),
])
def test_data_errors_name_the_file(spdfit, tmp_path, matrix, args, message):
    path = save(tmp_path, "bad.csv", matrix)
    out = spdfit("nearest", *args, path)
    assert out.returncode == 1 and message in out.stderr and "bad.csv" in out.stderr


def test_quiet_after_the_command_and_the_usage_hint_names_it(spdfit, tmp_path):
    path = save(tmp_path, "C.csv", indefinite_covariance(5, 9, scale=1e-8))
    loud = spdfit("nearest", "--min-eig", "1e-6", path)
    assert "warning" in loud.stderr
    for args in (["-q", "nearest", "--min-eig", "1e-6", path], ["nearest", "--min-eig", "1e-6", "-q", path]):
        out = spdfit(*args)
        assert out.returncode == 0 and out.stderr == "" and out.stdout == loud.stdout
    usage = spdfit("nearest", "--alpha", "0.1", path)
    assert usage.returncode == 2 and "Run 'spdfit nearest --help' for usage." in usage.stderr
    assert "Run 'spdfit nearest --help'" in spdfit("nearest", "--bogus", path).stderr


def test_json_warnings_match_what_is_printed(spdfit, tmp_path):
    out = spdfit("nearest", "--json", save(tmp_path, "C.csv", indefinite_covariance(6, 10)))
    j = json.loads(out.stdout)
    assert j["warnings"] and all(f"spdfit: warning: {w}" in out.stderr for w in j["warnings"])


def test_output_by_extension(spdfit, tmp_path):
    """-o X.npy writes a NumPy file (fit and nearest), the same numbers as the CSV; --json cannot go
    into one (usage error)."""
    path = save(tmp_path, "C.csv", indefinite_covariance(6, 10))
    assert spdfit("nearest", "-o", tmp_path / "X.npy", path).returncode == 0
    assert np.array_equal(np.load(tmp_path / "X.npy"), parse(spdfit("nearest", path).stdout))
    A, B = tmp_path / "A.csv", tmp_path / "B.csv"
    rng = np.random.default_rng(3)
    np.savetxt(A, rng.standard_normal((8, 2)), delimiter=",")
    np.savetxt(B, rng.standard_normal((8, 2)), delimiter=",")
    assert spdfit("fit", "--method", "ls", "-o", tmp_path / "F.npy", A, B).returncode == 0
    assert np.array_equal(np.load(tmp_path / "F.npy"), parse(spdfit("fit", "--method", "ls", A, B).stdout))
    for args in (["nearest", "--json", "-o", tmp_path / "J.npy", path],
                 ["fit", "--method", "ls", "--report", "-o", tmp_path / "R.npy", A, B]):
        out = spdfit(*args)
        assert out.returncode == 2 and "holds a matrix only" in out.stderr


@pytest.mark.parametrize("option", ["--keep-diag", "--via-corr"])
def test_pairwise_deleted_covariance_of_sensors_in_many_units(spdfit, tmp_path, option):
    """`df.cov()` of sensors with scales from 1e-3 to 300 and stretches of missing values: the
    default floor (of the correlation matrix) is below every variance, so the repair succeeds,
    keeps the variances and factors (tests/python/test_pairwise_covariance.py has the rest)."""
    S = pairwise_covariance(sensor_log())
    out = spdfit("nearest", option, "--json", save(tmp_path, "S.csv", S))
    assert out.returncode == 0, out.stderr
    assert out.stderr == ""
    j = json.loads(out.stdout)
    assert j["cholesky"] and j["converged"]
    X = np.array(j["X"])
    assert np.array_equal(np.diag(X), np.diag(S))
    np.linalg.cholesky(X)


def test_nan_in_the_matrix_names_the_pair_by_its_labels(spdfit, tmp_path):
    # df.corr().to_csv() with two variables never observed together (issue 45): the pair is named,
    # where the reader said "NaN is not allowed".
    path = tmp_path / "corr.csv"
    path.write_text(",oil,gas,coal\noil,1,0.5,NaN\ngas,0.5,1,0.2\ncoal,NaN,0.2,1\n")
    result = spdfit("nearest", "--corr", path)
    assert result.returncode == 1
    assert result.stderr.startswith(f"spdfit: error: {path}: NaN at (oil, coal), row 1, column 3: a pair of variables "
                                    "never observed together"), result.stderr
    # pandas' to_csv writes NaN as an empty field: the same message, not "drop such rows first".
    pd = pytest.importorskip("pandas")
    frame = pd.DataFrame({"oil": [1.0, 2.0, np.nan, np.nan], "gas": [2.0, 1.0, 3.0, 4.0],
                          "coal": [np.nan, np.nan, 1.0, 2.0]})
    frame.corr().to_csv(tmp_path / "pairwise.csv")
    result = spdfit("nearest", "--corr", tmp_path / "pairwise.csv")
    assert result.returncode == 1
    assert "pairwise.csv: NaN at (oil, coal), row 1, column 3: a pair of variables never observed" in result.stderr
    assert "drop such rows" not in result.stderr, result.stderr
    (tmp_path / "plain.csv").write_text("1,0.5,0\n0.5,1,inf\n0,inf,1\n")
    result = spdfit("nearest", tmp_path / "plain.csv")
    assert result.returncode == 1 and "Inf at row 2, column 3:" in result.stderr, result.stderr
