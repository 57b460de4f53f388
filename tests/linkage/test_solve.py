"""spdfit solve: the JSON contract of issue 4, the notes' six classified systems, random systems
against NumPy's pinv and matrix_rank, bad input files and usage errors."""
import json

import numpy as np
import pytest

from conftest import ROOT, fails

EPS = np.finfo(float).eps
EXAMPLES = ROOT / "examples" / "linkage"

CONTRACT = {"consistent", "rank", "nullity", "finite_solution_dimension", "at_infinity_dimension",
            "condition_number", "solution", "residual_norm", "null_space"}

# (consistent, rank, finite solution dimension, at-infinity dimension) of notes 002 section 3.3.2
NOTES = {
    1: (True, 3, 0, -1),   # one finite point
    2: (True, 2, 1, 0),    # a line of finite points (and its point at infinity)
    3: (True, 1, 2, 1),    # a plane of finite points (and its line at infinity)
    4: (False, 1, -1, 1),  # three parallel planes: a line at infinity only
    5: (False, 2, -1, 0),  # one point at infinity
    6: (False, 2, -1, 0),  # parallel lines of intersection: one point at infinity
}


@pytest.mark.parametrize("n", sorted(NOTES))
def test_notes_examples(spdfit_json, n):
    out = spdfit_json("solve", EXAMPLES / f"notes_ex{n}_A.csv", EXAMPLES / f"notes_ex{n}_b.csv")
    assert CONTRACT <= out.keys()
    consistent, rank, finite, infinity = NOTES[n]
    assert out["consistent"] is consistent
    assert out["rank"] == rank
    assert out["nullity"] == 3 - rank
    assert out["finite_solution_dimension"] == finite
    assert out["at_infinity_dimension"] == infinity
    assert len(out["null_space"]) == 3 - rank
    if n == 1:
        assert np.allclose(out["solution"], np.array([21, 10, -2]) / 13, rtol=1e-14)
        assert out["condition_number"] > 1
    else:
        assert out["condition_number"] is None or out["condition_number"] > 1e12  # singular: inf -> null


def test_example_text_says_it_in_words(spdfit):
    result = spdfit("solve", EXAMPLES / "notes_ex6_A.csv", EXAMPLES / "notes_ex6_b.csv")
    assert result.returncode == 0, result.stderr
    assert "no finite point in common" in result.stdout
    assert "parallel lines meet at one point at infinity" in result.stdout
    assert "reciprocal condition number" in result.stderr  # the notes' 1e-12 warning


def random_system(rng, m, n, r, p):
    """A rank-r m x n matrix and p right-hand sides, half of them in the range of A."""
    A = rng.standard_normal((m, r)) @ rng.standard_normal((r, n))
    B = rng.standard_normal((m, p))
    B[:, ::2] = A @ rng.standard_normal((n, (p + 1) // 2))
    return A, B


SHAPES = [(5, 3, 3), (3, 5, 3), (6, 6, 6), (8, 5, 2), (4, 7, 2), (6, 6, 4), (10, 1, 1), (1, 4, 1), (7, 7, 1)]


@pytest.mark.parametrize("m,n,r", SHAPES)
def test_random_systems_against_numpy(spdfit_json, write_csv, m, n, r):
    rng = np.random.default_rng(100 * m + 10 * n + r)
    for trial in range(3):
        p = 1 + trial
        A, B = random_system(rng, m, n, r, p)
        out = spdfit_json("solve", write_csv("A.csv", A), write_csv("B.csv", B))
        tol = max(m, n) * EPS  # the notes' cut-off, which is also NumPy's default for matrix_rank
        assert out["rank"] == np.linalg.matrix_rank(A, tol=tol * np.linalg.norm(A, 2)) == r
        X = np.array(out["solution"]).reshape(n, p)
        X_numpy = np.linalg.pinv(A, rcond=tol) @ B
        assert np.linalg.norm(X - X_numpy) <= 1e-10 * max(1.0, np.linalg.norm(X_numpy))
        N = np.array(out["null_space"]).reshape(n - r, n).T
        assert N.shape == (n, n - r)
        assert np.linalg.norm(A @ N) <= 1e-12 * np.linalg.norm(A)
        assert np.allclose(N.T @ N, np.eye(n - r), atol=1e-13)
        assert out["at_infinity_dimension"] == n - r - 1
        for j, column in enumerate(out["columns"]):
            # b_j is in the range of A exactly when appending it keeps the rank.
            augmented = np.c_[A, B[:, j] * np.linalg.norm(A, 2) / np.linalg.norm(B[:, j])]
            consistent = np.linalg.matrix_rank(augmented) == r
            assert column["consistent"] is bool(consistent), (m, n, r, j)
            assert column["finite_solution_dimension"] == (n - r if consistent else -1)
        assert out["residual_norm"] == pytest.approx(np.linalg.norm(A @ X - B), rel=1e-8, abs=1e-12)


def test_threshold_option_edits_singular_values(spdfit_json, write_csv):
    # Nearly dependent columns of equal size: the small singular value is not a matter of units
    # (U diag(1, 1e-9) alone would be, and column scaling would give it rank 2 at any threshold).
    U, _ = np.linalg.qr(np.random.default_rng(3).standard_normal((5, 2)))
    A = U @ np.diag([1.0, 1e-9]) @ np.array([[0.6, 0.8], [-0.8, 0.6]])
    b = write_csv("b.csv", np.ones((5, 1)))
    a = write_csv("A.csv", A)
    assert spdfit_json("solve", a, b)["rank"] == 2
    edited = spdfit_json("solve", "--threshold", "1e-6", a, b)
    assert edited["rank"] == 1 and edited["nullity"] == 1
    assert edited["threshold"] == 1e-6


def test_threshold_applies_to_the_column_scaled_a_as_the_help_says(spdfit, spdfit_json, write_csv):
    # Columns of very different units: A's raw singular values are 1 and 1e-6, so a NumPy user's
    # cut-off 1e-3 * sigma_max would drop one; with its columns scaled to unit norm A is orthogonal
    # (both singular values 1), and that is the matrix the threshold applies to.
    U, _ = np.linalg.qr(np.random.default_rng(4).standard_normal((5, 2)))
    A = U @ np.diag([1.0, 1e-6])
    raw = np.linalg.svd(A, compute_uv=False)
    scaled = np.linalg.svd(A / np.linalg.norm(A, axis=0), compute_uv=False)
    assert raw[1] <= 1e-3 * raw[0] and np.allclose(scaled, 1.0)
    out = spdfit_json("solve", "--threshold", "1e-3", write_csv("A.csv", A), write_csv("b.csv", np.ones((5, 1))))
    assert out["rank"] == 2
    helped = spdfit("solve", "--help")
    assert "columns scaled to unit norm" in " ".join(helped.stdout.split())


def test_b_as_a_row_is_read_as_a_column(spdfit_json, tmp_path):
    (tmp_path / "b.csv").write_text("7,0,-7\n")
    out = spdfit_json("solve", EXAMPLES / "notes_ex1_A.csv", tmp_path / "b.csv")
    assert np.allclose(out["solution"], np.array([21, 10, -2]) / 13, rtol=1e-14)


BAD = {
    "nan": ("1,2\n3,nan\n", [":2:3", "NaN"]),
    "not-a-number": ("1,2\nx,4\n", [":2:1", "'x' is not a number"]),
    "ragged": ("1,2\n3\n", [":2"]),
    "empty": ("", ["empty"]),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_files_exit_1_with_file_and_line(spdfit, tmp_path, name):
    content, fragments = BAD[name]
    bad = tmp_path / f"{name}.csv"
    bad.write_text(content)
    good = tmp_path / "good.csv"
    good.write_text("1\n2\n")
    fails(spdfit("solve", bad, good), 1, bad, *fragments)
    (tmp_path / "A.csv").write_text("1,2\n3,4\n")
    fails(spdfit("solve", tmp_path / "A.csv", bad), 1, bad, *fragments)


def test_mismatched_b_exits_1(spdfit, tmp_path):
    (tmp_path / "A.csv").write_text("1,2\n3,4\n")
    (tmp_path / "b.csv").write_text("1\n2\n3\n")
    fails(spdfit("solve", tmp_path / "A.csv", tmp_path / "b.csv"), 1, "b.csv", "3 rows", "one entry of b per equation")
    fails(spdfit("solve", tmp_path / "missing.csv", tmp_path / "b.csv"), 1, "missing.csv")


@pytest.mark.parametrize("args", [
    ["solve"],
    ["solve", "only-one.csv"],
    ["solve", "--threshold", "2", "A.csv", "b.csv"],
    ["solve", "--threshold", "abc", "A.csv", "b.csv"],
    ["solve", "--no-such-option", "A.csv", "b.csv"],
])
def test_usage_errors_exit_2(spdfit, args):
    result = spdfit(*args)
    assert result.returncode == 2, (result.returncode, result.stderr)
    assert result.stderr.startswith("spdfit: error: ")


def test_a_chosen_threshold_is_not_called_roundoff(spdfit):
    # Issue 18: values cut by the user's --threshold were called "roundoff"; only the default
    # cut-off max(m, n) eps says so.
    chosen = spdfit("solve", "--threshold", "0.7", "examples/linkage/notes_ex1_A.csv", "examples/linkage/notes_ex1_b.csv")
    assert chosen.returncode == 0
    assert "of the column-scaled A below the chosen threshold 0.7 * sigma_max were edited to zero" in chosen.stdout
    assert "roundoff" not in chosen.stdout.replace("not roundoff", "")
    default = spdfit("solve", "examples/linkage/notes_ex5_A.csv", "examples/linkage/notes_ex5_b.csv")
    assert "is roundoff and was edited to zero" in default.stdout
