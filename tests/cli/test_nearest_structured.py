"""spdfit nearest --fixed, --h-weights, --rank, --factors (--factors-only), --min-diag: each option
from its file, the combinations that work and the ones that are usage errors naming both options
(exit 2), bad masks, weights and K as data errors naming the file (exit 1), and --header on
df.cov().to_csv()'s output: no warning, labels with quotes and commas kept."""
import io
import json
import os
import subprocess
import sys

import numpy as np
import pytest
from spdfit_testing import cli_path

G = np.array([[2.0, -1, 0, 0], [-1, 2, -1, 0], [0, -1, 2, -1], [0, 0, -1, 2]])  # Higham's, NAG's example
C5 = np.array([[1.0, 0.9, 0.7, 0.1, 0.2], [0.9, 1.0, 0.95, 0.3, 0.1], [0.7, 0.95, 1.0, -0.2, 0.4],
               [0.1, 0.3, -0.2, 1.0, 0.8], [0.2, 0.1, 0.4, 0.8, 1.0]])


def write(path, M):
    np.savetxt(path, np.atleast_2d(M), delimiter=",", fmt="%.17g")
    return str(path)


def json_of(result):
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


@pytest.fixture
def files(tmp_path):
    mask = np.zeros((5, 5))
    mask[:2, :2] = 1
    mask[3, 4] = mask[4, 3] = 1
    H = np.full((5, 5), 0.5)
    H[0, 1] = H[1, 0] = 2.0
    H[2, 4] = H[4, 2] = 0.0
    return {"C": write(tmp_path / "C.csv", C5), "G": write(tmp_path / "G.csv", G),
            "mask": write(tmp_path / "mask.csv", mask), "pairs": write(tmp_path / "pairs.csv", [[1, 2], [4, 5]]),
            "H": write(tmp_path / "H.csv", H), "tmp": tmp_path, "mask_array": mask, "H_array": H}


def test_fixed_keeps_the_entries_bit_for_bit_from_a_mask_or_pairs(spdfit, files):
    by_mask = json_of(spdfit("nearest", "--corr", "--fixed", files["mask"], "--json", files["C"]))
    by_pairs = json_of(spdfit("nearest", "--corr", "--fixed", files["pairs"], "--json", files["C"]))
    X = np.array(by_mask["X"])
    assert X[0, 1] == C5[0, 1] and X[3, 4] == C5[3, 4] and X[4, 3] == C5[4, 3]
    np.testing.assert_array_equal(X, np.array(by_pairs["X"]))
    assert by_mask["fixed_entries"] == 2 and by_mask["method"] == "Qi-Sun Newton with fixed entries"
    # The dual's bound holds for every admissible matrix; X is admissible to its final residual
    # (about 1e-10), so its distance can sit that much below the bound.
    assert abs(by_mask["distance"] - by_mask["lower_bound"]) <= 1e-6 * by_mask["distance"]
    assert np.all(np.diag(X) == 1.0) and np.linalg.eigvalsh(X)[0] > 0
    # The text output reads back to the same bits.
    text = spdfit("nearest", "--corr", "--fixed", files["mask"], files["C"])
    np.testing.assert_array_equal(np.loadtxt(io.StringIO(text.stdout), delimiter=","), X)


def test_fixed_with_keep_diag_and_with_h_weights(spdfit, files):
    S = C5 * np.sqrt(np.outer([1, 4, 9, 1, 2], [1, 4, 9, 1, 2]))
    path = write(files["tmp"] / "S.csv", S)
    kept = json_of(spdfit("nearest", "--keep-diag", "--fixed", files["mask"], "--json", path))
    X = np.array(kept["X"])
    assert np.array_equal(np.diag(X), np.diag(S)) and X[0, 1] == S[0, 1]
    both = json_of(spdfit("nearest", "--corr", "--fixed", files["mask"], "--h-weights", files["H"], "--json",
                          files["C"]))
    Y = np.array(both["X"])
    assert both["method"] == "augmented Lagrangian (H weights)" and both["converged"]
    assert Y[0, 1] == C5[0, 1] and Y[3, 4] == C5[3, 4]
    assert both["distance"] == pytest.approx(np.linalg.norm(files["H_array"] * (Y - C5)), rel=1e-12)
    assert both["optimality_residual"] <= 1e-10


def test_h_weights_alone_and_nags_alpha(spdfit, files):
    out = json_of(spdfit("nearest", "--corr", "--h-weights", files["H"], "--alpha", "0.04", "--json", files["C"]))
    X = np.array(out["X"])
    assert np.linalg.eigvalsh(X)[0] >= 0.04 * (1 - 1e-9)
    assert out["lower_bound"] <= out["distance"] * (1 + 1e-9)


def test_rank_and_factors(spdfit, files):
    r = json_of(spdfit("nearest", "--corr", "--rank", "2", "--json", files["G"]))
    X = np.array(r["X"])
    assert np.linalg.matrix_rank(X, tol=1e-10) == 2 and [s["start"] for s in r["starts"]][:2] == [
        "modified PCA of C", "modified PCA of the convex solution"]
    assert r["lower_bound"] <= r["distance"] and r["optimality_residual"] <= 1e-6
    f = json_of(spdfit("nearest", "--corr", "--factors", "2", "--json", files["G"]))
    F = np.array(f["F"])
    np.testing.assert_allclose(np.diag(1 - np.sum(F ** 2, 1)) + F @ F.T, np.array(f["X"]), atol=1e-14)
    only = spdfit("nearest", "--corr", "--factors", "2", "--factors-only", files["G"])
    assert only.returncode == 0, only.stderr
    np.testing.assert_array_equal(np.loadtxt(io.StringIO(only.stdout), delimiter=",", ndmin=2), F)
    npy = files["tmp"] / "F.npy"
    assert spdfit("nearest", "--corr", "--factors", "2", "--factors-only", "-o", str(npy), files["G"]).returncode == 0
    np.testing.assert_array_equal(np.load(npy), F)


def test_rank_with_weights(spdfit, files):
    w = write(files["tmp"] / "w.csv", [1, 2, 3, 2, 1])
    out = json_of(spdfit("nearest", "--corr", "--rank", "2", "--weights", w, "--json", files["C"]))
    X = np.array(out["X"])
    root = np.sqrt(np.array([1, 2, 3, 2, 1.0]))
    assert out["distance"] == pytest.approx(np.linalg.norm(np.outer(root, root) * (X - C5)), rel=1e-10)


def test_min_diag_names_the_entries(spdfit, tmp_path):
    S = np.array([[4.0, 1.0, 0.5], [1.0, 0.0, 0.2], [0.5, 0.2, -0.01]])
    path = write(tmp_path / "S.csv", S)
    refused = spdfit("nearest", "--keep-diag", path)
    assert refused.returncode == 1
    assert "diagonal entries 2 (0), 3 (-0.01) are not positive" in refused.stderr and "--min-diag" in refused.stderr
    for mode in (["--keep-diag"], ["--via-corr"], [], ["--corr"]):
        raised = spdfit("nearest", *mode, "--min-diag", "1e-3", path)
        assert raised.returncode == 0, raised.stderr
        assert "diagonal entries 2 (0), 3 (-0.01) were below --min-diag and raised to 0.001" in raised.stderr
    X = np.loadtxt(io.StringIO(spdfit("nearest", "--keep-diag", "--min-diag", "1e-3", path).stdout), delimiter=",")
    np.testing.assert_array_equal(np.diag(X), [4.0, 1e-3, 1e-3])
    # --json says which kind of warning it was, by its code.
    out = json_of(spdfit("nearest", "--keep-diag", "--min-diag", "1e-3", "--json", path))
    assert len(out["warning_codes"]) == len(out["warnings"])
    assert out["warning_codes"][out["warnings"].index(next(w for w in out["warnings"] if "min_diag" in w
                                                          or "--min-diag" in w))] == "diagonal_changed"


@pytest.mark.parametrize("args, both", [
    (["--corr", "--rank", "2", "--fixed", "MASK"], ("--fixed", "--rank")),
    (["--corr", "--rank", "2", "--h-weights", "H"], ("--h-weights", "--rank")),
    (["--corr", "--factors", "2", "--fixed", "MASK"], ("--fixed", "--factors")),
    (["--corr", "--factors", "2", "--h-weights", "H"], ("--h-weights", "--factors")),
    (["--corr", "--factors", "2", "--rank", "2"], ("--rank", "--factors")),
    (["--corr", "--weights", "W", "--h-weights", "H"], ("--weights", "--h-weights")),
    (["--corr", "--rank", "2", "--min-eig", "0"], ("--min-eig", "--rank")),
])
def test_forbidden_pairs_are_usage_errors_naming_both(spdfit, files, args, both):
    w = write(files["tmp"] / "w.csv", np.ones(5))
    args = [{"MASK": files["mask"], "H": files["H"], "W": w}.get(a, a) for a in args]
    result = spdfit("nearest", *args, files["C"])
    assert result.returncode == 2, result.stderr
    assert both[0] in result.stderr and both[1] in result.stderr


@pytest.mark.parametrize("args, message", [
    (["--rank", "2"], "--rank needs --corr"),
    (["--factors", "2"], "--factors is a correlation matrix's structure"),
    (["--corr", "--factors-only"], "--factors-only needs --factors"),
    (["--corr", "--rank", "0"], "--rank"),
    (["--via-corr", "--fixed", "MASK"], "--via-corr"),
])
def test_other_usage_errors(spdfit, files, args, message):
    args = [{"MASK": files["mask"]}.get(a, a) for a in args]
    result = spdfit("nearest", *args, files["C"])
    assert result.returncode == 2 and message in result.stderr, result.stderr


@pytest.mark.parametrize("content, option, message", [
    (np.full((5, 5), 0.5), "--fixed", "has 0.5 at (1, 1): a mask holds 1 (kept) and 0 (free)"),
    (np.triu(np.ones((5, 5))), "--fixed", "is not symmetric"),
    (np.zeros((5, 5)), "--fixed", "all zero"),
    (np.ones((4, 4)), "--fixed", "give an 5x5 mask"),
    ([[1, 6]], "--fixed", "indices are integers from 1 to 5"),
    (-np.ones((5, 5)), "--h-weights", "must be finite and >= 0"),
    (np.triu(np.ones((5, 5))), "--h-weights", "not symmetric"),
    (np.zeros((5, 5)), "--h-weights", "all zero"),
])
def test_bad_masks_and_weights_are_data_errors_naming_the_file(spdfit, files, content, option, message):
    path = write(files["tmp"] / "bad.csv", content)
    result = spdfit("nearest", "--corr", option, path, files["C"])
    assert result.returncode == 1, result.stderr
    assert "bad.csv" in result.stderr and message in result.stderr and option in result.stderr


def test_k_above_n_and_infeasible_blocks_are_data_errors(spdfit, files, tmp_path):
    result = spdfit("nearest", "--corr", "--rank", "6", files["C"])
    assert result.returncode == 1 and "--rank is 6, but the matrix is 5x5" in result.stderr
    bad = C5.copy()
    bad[0, 2] = bad[2, 0] = -0.9  # with 0.9 and 0.95 beside it: the block 1..3 is indefinite
    block = np.zeros((5, 5))
    block[:3, :3] = 1
    result = spdfit("nearest", "--corr", "--fixed", write(tmp_path / "block.csv", block), write(tmp_path / "X.csv", bad))
    assert result.returncode == 1
    assert "X.csv" in result.stderr and "rows and columns 1, 2, 3 is not positive semidefinite" in result.stderr


def test_header_reads_pandas_cov_output_without_a_warning_and_keeps_labels(spdfit, tmp_path):
    pd = pytest.importorskip("pandas")
    labels = ['rate, 10y', 'say "hi"', "it's", "plain"]
    rng = np.random.default_rng(4)
    df = pd.DataFrame(rng.standard_normal((30, 4)), columns=labels)
    df.iloc[::3, 1] = np.nan
    path = tmp_path / "cov.csv"
    df.corr().to_csv(path)
    result = spdfit("nearest", "--corr", "--header", str(path))
    assert result.returncode == 0, result.stderr
    assert "warning" not in result.stderr
    back = pd.read_csv(io.StringIO(result.stdout), index_col=0)
    assert list(back.columns) == labels and list(back.index) == labels
    # --fixed with --header: the labels stay, the kept entry too.
    mask = np.zeros((4, 4))
    mask[0, 1] = mask[1, 0] = 1
    kept = spdfit("nearest", "--corr", "--header", "--fixed", write(tmp_path / "m.csv", mask), str(path))
    back = pd.read_csv(io.StringIO(kept.stdout), index_col=0)
    assert back.loc[labels[0], labels[1]] == pytest.approx(df.corr().loc[labels[0], labels[1]], rel=1e-15)
    # The factor loadings are named by variable and factor.
    loadings = spdfit("nearest", "--corr", "--factors", "2", "--factors-only", "--header", str(path))
    F = pd.read_csv(io.StringIO(loadings.stdout), index_col=0)
    assert list(F.index) == labels and list(F.columns) == ["factor 1", "factor 2"]


def test_labelled_masks_and_weights_are_aligned_to_xs_names(spdfit, tmp_path):
    pd = pytest.importorskip("pandas")
    labels = ["a", "b, c", 'd "e"', "f", "g"]
    C = pd.DataFrame(C5, index=labels, columns=labels)
    C.to_csv(tmp_path / "C.csv")
    H = pd.DataFrame(np.full((5, 5), 0.5), index=labels, columns=labels)
    H.iloc[0, 1] = H.iloc[1, 0] = 2.0
    H.to_csv(tmp_path / "H.csv")
    H.loc[labels[::-1], labels[::-1]].to_csv(tmp_path / "H_reversed.csv")
    a = spdfit("nearest", "--corr", "--h-weights", str(tmp_path / "H.csv"), str(tmp_path / "C.csv"))
    b = spdfit("nearest", "--corr", "--h-weights", str(tmp_path / "H_reversed.csv"), str(tmp_path / "C.csv"))
    assert a.returncode == 0 and b.returncode == 0, a.stderr + b.stderr
    assert a.stdout == b.stdout and "warning" not in a.stderr + b.stderr
    H.rename(columns={"f": "z"}, index={"f": "z"}).to_csv(tmp_path / "H_other.csv")
    c = spdfit("nearest", "--corr", "--h-weights", str(tmp_path / "H_other.csv"), str(tmp_path / "C.csv"))
    assert c.returncode == 1 and "H_other.csv" in c.stderr and "are not the matrix's" in c.stderr


@pytest.mark.skipif(os.environ.get("SPDFIT_SANITIZED") == "1", reason="the sanitizers' own memory")
def test_factors_only_holds_c_once(tmp_path):
    """--factors-only from a .npy keeps no n x n matrix beside C: the file is decoded a block of rows
    at a time (before, its bytes were held whole beside the matrix: twice C). Peak resident set of
    the command less that of the same command on a 3 x 3 matrix, against C's size."""
    n = 3000
    rng = np.random.default_rng(4)
    F = rng.standard_normal((n, 4)) * 0.4
    C = F @ F.T + 0.05 * np.eye(n)
    d = np.sqrt(np.diag(C))
    C = C / d[:, None] / d[None, :]
    big, small = tmp_path / "C.npy", tmp_path / "small.npy"
    np.save(big, C)
    np.save(small, np.eye(3))
    cli = cli_path()

    def peak(path):
        probe = ("import resource, subprocess, sys; subprocess.run(sys.argv[1:], check=True, capture_output=True); "
                 "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024)")
        args = [cli, "nearest", "--corr", "--factors", "2", "--factors-only", "-o", str(tmp_path / "F.npy"), str(path)]
        return int(subprocess.run([sys.executable, "-c", probe, *args], capture_output=True, text=True,
                                  check=True).stdout)

    extra = peak(big) - peak(small)
    assert extra < 1.4 * C.nbytes, f"{extra / C.nbytes:.2f} times C's {C.nbytes} bytes"
