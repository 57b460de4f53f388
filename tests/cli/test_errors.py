"""Bad input never crashes: a clear message naming the file (and line), and exit status 1;
usage errors exit with 2."""
import numpy as np
import pytest

from conftest import write_text

GOOD = "1,2\n3,4\n5,6\n"


def fails(result, status, *fragments):
    assert result.returncode == status, (result.returncode, result.stdout, result.stderr)
    assert result.stdout == ""
    assert result.stderr.startswith("spdfit: error: "), result.stderr
    for fragment in fragments:
        assert fragment in result.stderr, (fragment, result.stderr)


@pytest.fixture
def good(tmp_path):
    return write_text(tmp_path / "good.csv", GOOD)


BAD_TEXT = {
    # name: (content, fragments expected in the message besides the file name)
    "ragged": ("1,2\n3,4,5\n6,7\n", [":2", "3 fields", "expected 2"]),
    "not-a-number": ("1,2\n3,abc\n5,6\n", [":2:3", "'abc' is not a number"]),
    "nan": ("1,2\nnan,4\n5,6\n", [":2:1", "NaN"]),
    "inf": ("1,2\n3,4\n5,-inf\n", [":3:3", "Inf"]),
    "overflow": ("1,2\n3,1e999\n5,6\n", [":2:3", "too large"]),
    "empty-field": ("1,,2\n3,4,5\n", [":1", "empty field"]),
    "empty": ("", ["empty"]),
    "only-comments": ("# nothing here\n\n", ["no data"]),
    "binary": ("1,2\n\x00\x01\x02\x03\n", ["binary"]),
    "decimal-comma": ("1,5;2,5\n3,5;4,5\n", ["decimal comma"]),
}


@pytest.mark.parametrize("name", sorted(BAD_TEXT))
def test_bad_text_file(spdfit, tmp_path, good, name):
    content, fragments = BAD_TEXT[name]
    bad = write_text(tmp_path / f"{name}.csv", content)
    fails(spdfit("fit", "--method", "spde", bad, good), 1, str(bad), *fragments)
    fails(spdfit("fit", "--method", "ls", good, bad), 1, str(bad), *fragments)


def test_missing_file(spdfit, tmp_path, good):
    fails(spdfit("fit", "--method", "spde", tmp_path / "nope.csv", good), 1, "nope.csv", "no such file")


def test_directory(spdfit, tmp_path, good):
    fails(spdfit("fit", "--method", "spde", tmp_path, good), 1, str(tmp_path), "directory")


def test_random_binary_garbage(spdfit, tmp_path, good):
    garbage = tmp_path / "garbage.bin"
    garbage.write_bytes(np.random.default_rng(1).integers(0, 256, 4096, dtype=np.uint8).tobytes())
    fails(spdfit("fit", "--method", "spde", garbage, good), 1, "garbage.bin")


def test_different_row_counts(spdfit, tmp_path, good):
    other = write_text(tmp_path / "four.csv", GOOD + "7,8\n")
    fails(spdfit("fit", "--method", "spde", good, other), 1, "four.csv", "4x2", "3x2", "same numbers of rows")


def test_different_column_counts(spdfit, tmp_path, good):
    # B with d != n columns: a non-square X, which only ls and tls fit; the other methods are
    # refused naming B's file and the methods that do fit it, in memory and streamed.
    other = write_text(tmp_path / "wide.csv", "1,2,3\n3,4,5\n5,6,7\n")
    for stream in ([], ["--stream"]):
        fails(spdfit("fit", "--method", "spde", *stream, good, other), 1, "wide.csv", "A has 2 and B 3",
              "use ls or tls")
        # tls needs m >= n + d = 5 rows for a 2x3 X; there are 3.
        fails(spdfit("fit", "--method", "tls", *stream, good, other), 1, str(good), "3 rows", "n + d = 5")


def test_fewer_rows_than_columns(spdfit, tmp_path):
    wide = write_text(tmp_path / "wide.csv", "1,2,3\n4,5,6\n")
    fails(spdfit("fit", "--method", "spde", wide, wide), 1, "wide.csv", "2 rows", "3 columns")


def test_npy_with_wrong_dtype(spdfit, tmp_path, good):
    np.save(tmp_path / "complex.npy", np.ones((3, 2), complex))
    fails(spdfit("fit", "--method", "spde", tmp_path / "complex.npy", good), 1, "complex.npy", "dtype '<c16'")


@pytest.mark.parametrize("dtype", ["float32", "int8", "int16", "int32", "int64", "uint8", "uint16", "uint32",
                                   "uint64", "bool", ">f8", ">i4"])
def test_npy_numeric_dtypes_are_read_as_numpy_converts_them(spdfit, tmp_path, dtype):
    # Issue 18: what numpy's astype(float) gives, in memory and streamed (before: refused).
    rng = np.random.default_rng(3)
    normal = rng.standard_normal((40, 2))
    values = (normal > 0) if dtype == "bool" else (normal * 50).astype(dtype)
    np.save(tmp_path / "A.npy", values)
    X = np.array([[1.0, 2.0], [3.0, 4.0]])
    np.save(tmp_path / "B.npy", values.astype(float) @ X)  # exact: small integers or float32 values
    out = tmp_path / "X.npy"
    for stream in ([], ["--stream", "--block-rows", "7"]):
        result = spdfit("fit", "--method", "ls", *stream, "-o", out, tmp_path / "A.npy", tmp_path / "B.npy")
        assert result.returncode == 0, result.stderr
        np.testing.assert_allclose(np.load(out), X, rtol=1e-12)


def test_truncated_npy(spdfit, tmp_path, good):
    np.save(tmp_path / "cut.npy", np.ones((3, 2)))
    raw = (tmp_path / "cut.npy").read_bytes()
    (tmp_path / "cut.npy").write_bytes(raw[:-10])
    fails(spdfit("fit", "--method", "spde", tmp_path / "cut.npy", good), 1, "cut.npy")


def test_npy_with_nan(spdfit, tmp_path, good):
    values = np.ones((3, 2))
    values[1, 0] = np.nan
    np.save(tmp_path / "nan.npy", values)
    fails(spdfit("fit", "--method", "spde", tmp_path / "nan.npy", good), 1, "nan.npy", "NaN")


def test_rank_deficient_a_fails_spde_with_status_1(spdfit, tmp_path):
    a = write_text(tmp_path / "a.csv", "1,2\n2,4\n3,6\n")
    b = write_text(tmp_path / "b.csv", "1,0\n0,1\n1,1\n")
    fails(spdfit("fit", "--method", "spde", a, b), 1, "rank-deficient")


@pytest.mark.parametrize("args, fragment", [
    (["fit", "--method", "bogus", "a", "b"], "bogus"),
    (["fit", "a.csv", "b.csv"], "--method"),
    (["fit", "--method", "spde", "a.csv"], "B"),
    (["nearest"], "X"),
    (["frobnicate"], "frobnicate"),
    ([], "subcommand"),
    (["nearest", "--min-eig", "-1", "x.csv"], "min-eig"),
])
def test_usage_errors_exit_2(spdfit, args, fragment):
    fails(spdfit(*args), 2, fragment)


def test_negative_min_eig_is_named_in_a_short_message(spdfit):
    """Regression: CLI11's NonNegativeNumber printed the largest double in full (310 digits)."""
    result = spdfit("nearest", "--min-eig", "-1", "x.csv")
    fails(result, 2, "--min-eig: '-1' is not a finite number >= 0")
    assert len(result.stderr) < 200, result.stderr


def test_nearest_rejects_non_square(spdfit, tmp_path, good):
    fails(spdfit("nearest", good), 1, "good.csv", "square")
