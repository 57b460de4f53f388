"""Issue 18: MATLAB 7.3 files (HDF5) are streamed by row ranges (HDF5 hyperslabs through
libmatio), not read whole. The files are written here with h5py, as MATLAB lays them out (a
512-byte user block holding the MAT-file header, each variable a dataset stored transposed with
a MATLAB_class attribute): a writer independent of libmatio. The reference is the same data as
.npy, streamed through the .npy reader."""
import json

import h5py  # python3-h5py, in scripts/packages-test.txt
import numpy as np
import pytest

MATLAB_CLASSES = {np.dtype(np.float64): "double", np.dtype(np.float32): "single",
                  np.dtype(np.int16): "int16", np.dtype(np.int32): "int32", np.dtype(np.uint8): "uint8"}


def write_mat73(path, arrays, compress=True):
    with h5py.File(path, "w", userblock_size=512) as f:
        for name, array in arrays.items():
            array = np.asarray(array)
            # MATLAB is column-major: HDF5 holds the transpose, an m x n matrix as n x m.
            options = {"chunks": True, "compression": "gzip"} if compress else {}
            dataset = f.create_dataset(name, data=array.T, **options)
            matlab_class = MATLAB_CLASSES[array.dtype].encode()
            string = h5py.h5t.C_S1.copy()  # a fixed-length, null-terminated string, as MATLAB writes
            string.set_size(len(matlab_class))
            string.set_strpad(h5py.h5t.STR_NULLTERM)
            attribute = h5py.h5a.create(dataset.id, b"MATLAB_class", string, h5py.h5s.create(h5py.h5s.SCALAR))
            attribute.write(np.array(matlab_class, dtype=f"S{len(matlab_class)}"), mtype=string)
    header = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Wed Nov 25 12:00:00 2026 HDF5 schema 1.00 ."
    with open(path, "r+b") as f:  # text, 8 bytes of subsystem offset, version 0x0200, "IM"
        f.write(header.ljust(116, b" ") + bytes(8) + b"\x00\x02IM")


X_TRUE = np.array([[2.0, 0.5, 0.0], [0.5, 1.0, 0.2], [0.0, 0.2, 3.0]])


@pytest.fixture(scope="module")
def logs(tmp_path_factory):
    path = tmp_path_factory.mktemp("mat73")
    rng = np.random.default_rng(73)
    m = 1003  # not a multiple of any block size used here
    A = rng.standard_normal((m, 3))
    B = A @ X_TRUE + 1e-2 * rng.standard_normal((m, 3))
    write_mat73(path / "log.mat", {"accel": A, "force": B, "counts": np.arange(6, dtype=np.int32).reshape(2, 3)})
    write_mat73(path / "plain.mat", {"B": B}, compress=False)
    np.save(path / "A.npy", A)
    np.save(path / "B.npy", B)
    return path, A, B


def fit(spdfit, *args):
    result = spdfit("fit", "--method", "spde", "--json", *args)
    assert result.returncode == 0, result.stderr
    return np.array(json.loads(result.stdout)["X"]), result.stderr


@pytest.mark.parametrize("block", ["7", "64", "5000"])
def test_streamed_7_3_gives_the_npy_result_without_reading_whole(spdfit, logs, block):
    path, A, B = logs
    stream = ["--stream", "--block-rows", block]
    expected, _ = fit(spdfit, *stream, path / "A.npy", path / "B.npy")
    for b in [f"{path}/log.mat:force", path / "plain.mat"]:   # chunked and compressed; contiguous
        X, stderr = fit(spdfit, *stream, f"{path}/log.mat:accel", b)
        # The same rows in the same blocks: the same arithmetic, so the same bits.
        np.testing.assert_array_equal(X, expected)
        assert "read whole" not in stderr
    whole, _ = fit(spdfit, f"{path}/log.mat:accel", f"{path}/log.mat:force")
    np.testing.assert_allclose(whole, expected, rtol=1e-12, atol=1e-14)


def test_streamed_7_3_converts_other_classes(spdfit, tmp_path):
    rng = np.random.default_rng(7)
    A = rng.integers(-300, 300, (200, 2)).astype(np.int16)
    B = (A.astype(float) @ np.array([[2.0, 0.5], [0.5, 1.0]])).astype(np.float32)
    write_mat73(tmp_path / "A.mat", {"A": A})
    write_mat73(tmp_path / "B.mat", {"B": B})
    result = spdfit("fit", "--method", "ls", "--stream", "--block-rows", "9", "--json", tmp_path / "A.mat",
                    tmp_path / "B.mat")
    assert result.returncode == 0, result.stderr
    expected = np.linalg.lstsq(A.astype(float), B.astype(float), rcond=None)[0]
    np.testing.assert_allclose(json.loads(result.stdout)["X"], expected, rtol=1e-10)


def test_streamed_7_3_names_the_row_of_a_nan(spdfit, logs, tmp_path):
    _, A, B = logs
    A = A.copy()
    A[876, 1] = np.nan
    write_mat73(tmp_path / "A.mat", {"A": A})
    result = spdfit("fit", "--method", "ls", "--stream", "--block-rows", "100", tmp_path / "A.mat",
                    logs[0] / "B.npy")
    assert result.returncode == 1
    assert f"{tmp_path / 'A.mat'}: entry (877, 2) is NaN" in result.stderr


def test_streamed_7_3_says_which_variable(spdfit, logs):
    path, _, _ = logs
    result = spdfit("fit", "--method", "ls", "--stream", path / "log.mat", path / "B.npy")
    assert result.returncode == 1
    assert "holds 3 2-D numeric arrays (accel, counts, force)" in result.stderr
    assert "name one as" in result.stderr
    result = spdfit("fit", "--method", "ls", "--stream", f"{path}/log.mat:nope", path / "B.npy")
    assert result.returncode == 1 and "has no variable 'nope'" in result.stderr
    # A 2 x 3 variable against B's 1003 rows.
    result = spdfit("fit", "--method", "ls", "--stream", f"{path}/log.mat:counts", path / "B.npy")
    assert result.returncode == 1 and "rows" in result.stderr


def test_streamed_7_3_bootstrap_matches_npy(spdfit, tmp_path):
    # The streaming bootstrap resamples groups of 4096 rows and needs about 100 of them.
    rng = np.random.default_rng(11)
    A = rng.standard_normal((100 * 4096 + 3, 3))
    B = A @ X_TRUE + 0.1 * rng.standard_normal(A.shape)
    write_mat73(tmp_path / "log.mat", {"accel": A, "force": B})
    np.save(tmp_path / "A.npy", A)
    np.save(tmp_path / "B.npy", B)
    args = ["--stream", "--bootstrap", "40", "--seed", "4"]
    run_mat = spdfit("fit", "--method", "ls", "--json", *args, f"{tmp_path}/log.mat:accel",
                     f"{tmp_path}/log.mat:force")
    run_npy = spdfit("fit", "--method", "ls", "--json", *args, tmp_path / "A.npy", tmp_path / "B.npy")
    assert run_mat.returncode == 0, run_mat.stderr
    mat, npy = json.loads(run_mat.stdout), json.loads(run_npy.stdout)
    assert mat["bootstrap"]["groups"] == 101
    for key in ["X", "standard_errors", "interval", "bias"]:
        np.testing.assert_array_equal(mat[key], npy[key], err_msg=key)


def test_a_truncated_7_3_file_is_called_damaged(spdfit, logs, tmp_path):
    # Cut in half, HDF5 can no longer list the variables: not "no such variable".
    path, _, _ = logs
    whole = (path / "log.mat").read_bytes()
    (tmp_path / "cut.mat").write_bytes(whole[: len(whole) // 2])
    for spec in [f"{tmp_path}/cut.mat:accel", tmp_path / "cut.mat"]:
        result = spdfit("fit", "--method", "ls", "--stream", spec, path / "B.npy")
        assert result.returncode == 1, result.stderr
        assert "a damaged or truncated .mat file?" in result.stderr, result.stderr


def test_variables_that_cannot_be_read_say_why(spdfit, logs, tmp_path):
    path, A, _ = logs
    # A dataset without MATLAB's class attribute (MATLAB always writes one).
    with h5py.File(tmp_path / "noclass.mat", "w", userblock_size=512) as f:
        f.create_dataset("accel", data=A.T)
    with open(tmp_path / "noclass.mat", "r+b") as f:
        f.write(b"MATLAB 7.3 MAT-file".ljust(116, b" ") + bytes(8) + b"\x00\x02IM")
    result = spdfit("fit", "--method", "ls", f"{tmp_path}/noclass.mat:accel", path / "B.npy")
    assert result.returncode == 1
    assert "has no MATLAB class libmatio knows (no MATLAB_class attribute?)" in result.stderr
    # Only a 3-D array: no "name one", which could not help.
    write_mat73(tmp_path / "cube.mat", {"cube": np.zeros((4, 3, 2))})
    result = spdfit("fit", "--method", "ls", tmp_path / "cube.mat", path / "B.npy")
    assert result.returncode == 1
    assert "holds no real 2-D numeric array; its variables: cube (none is a real numeric matrix" in result.stderr
    assert "name one as" not in result.stderr


def test_var_a_with_a_named_array_or_standard_input_is_a_usage_error(spdfit, logs):
    path, _, _ = logs
    result = spdfit("fit", "--method", "ls", "--var-a", "accel", f"{path}/log.mat:accel", f"{path}/log.mat:force")
    assert result.returncode == 2
    assert f"--var-a accel names the array, but {path}/log.mat:accel names one already" in result.stderr
    result = spdfit("fit", "--method", "ls", "--var-a", "accel", "-", path / "B.npy", input="1,2\n")
    assert result.returncode == 2 and "the file is standard input (-)" in result.stderr
