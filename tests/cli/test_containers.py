"""Issue 18: MATLAB .mat files (written here by scipy.io.savemat, an independent writer), NumPy
.npz archives and standard input, in memory and streamed; FILE:NAME, --var-a/--var-b and the
messages that say what to do; --output X.mat read back by scipy.io.loadmat."""
import json
import pathlib
import subprocess
import sys

import numpy as np
import pytest
import scipy.io

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "support"))

from spdfit_testing import cli_path  # noqa: E402

X_TRUE = np.array([[2.0, 0.5, 0.0], [0.5, 1.0, 0.2], [0.0, 0.2, 3.0]])


@pytest.fixture
def data(tmp_path):
    rng = np.random.default_rng(18)
    A = rng.standard_normal((30, 3))
    B = A @ X_TRUE + 1e-3 * rng.standard_normal((30, 3))
    scipy.io.savemat(tmp_path / "log.mat", {"accel": A, "force": B, "note": "test rig 3"})
    scipy.io.savemat(tmp_path / "A.mat", {"A": A.astype(np.float32)})
    scipy.io.savemat(tmp_path / "Bc.mat", {"B": B}, do_compression=True)
    np.savez(tmp_path / "log.npz", accel=A, force=B)
    np.savez_compressed(tmp_path / "B.npz", B)
    np.savetxt(tmp_path / "A.csv", A, delimiter=",")
    np.savetxt(tmp_path / "B.csv", B, delimiter=",")
    return tmp_path, A, B


def estimate(spdfit, *args, stdin=None):
    result = spdfit("fit", "--method", "ls", "--json", *args, input=stdin)
    assert result.returncode == 0, result.stderr
    return np.array(json.loads(result.stdout)["X"]), result.stderr


@pytest.mark.parametrize("stream", [[], ["--stream", "--block-rows", "7"]])
def test_every_container_gives_the_csv_estimate(spdfit, data, stream):
    path, A, B = data
    expected, _ = estimate(spdfit, path / "A.csv", path / "B.csv")
    for a, b in [(f"{path}/log.mat:accel", f"{path}/log.mat:force"),
                 (f"{path}/log.npz:accel", f"{path}/log.npz:force.npy"),
                 (f"{path}/log.mat:accel", path / "Bc.mat"),         # the only 2-D array, compressed
                 (path / "A.csv", path / "B.npz")]:                  # savez_compressed's arr_0
        X, stderr = estimate(spdfit, *stream, a, b)
        np.testing.assert_allclose(X, expected, rtol=1e-12, atol=1e-13, err_msg=f"{a} {b}")
        if stream and str(b).endswith((".mat", ".npz", "force", "force.npy")):
            assert "is read whole, not a block at a time" in stderr
    X, _ = estimate(spdfit, *stream, "--var-a", "accel", "--var-b", "force", path / "log.mat", path / "log.mat")
    np.testing.assert_allclose(X, expected, rtol=1e-12, atol=1e-13)
    # float32 in a .mat file is converted, as scipy gives it back.
    X, _ = estimate(spdfit, *stream, path / "A.mat", path / "B.csv")
    A32 = scipy.io.loadmat(path / "A.mat")["A"].astype(float)
    np.testing.assert_allclose(X, np.linalg.lstsq(A32, B, rcond=None)[0], rtol=1e-10)


@pytest.mark.parametrize("stream", [[], ["--stream"]])
def test_standard_input(spdfit, data, stream):
    path, _, _ = data
    expected, _ = estimate(spdfit, path / "A.csv", path / "B.csv")
    X, stderr = estimate(spdfit, *stream, "-", path / "B.csv", stdin=(path / "A.csv").read_text())
    np.testing.assert_allclose(X, expected, rtol=1e-12, atol=1e-13)
    assert "read whole" not in stderr  # text on standard input streams as from a file
    both = spdfit("fit", "--method", "ls", "-", "-", input="1,2\n")
    assert both.returncode == 2 and "cannot both be standard input" in both.stderr


def test_a_npy_file_on_standard_input_is_read_whole_with_a_warning(spdfit, data, tmp_path):
    path, A, B = data
    np.save(tmp_path / "A.npy", A)
    result = subprocess.run([cli_path(), "fit", "--method", "ls", "--stream", "--json", "-", str(path / "B.csv")],
                            stdin=open(tmp_path / "A.npy", "rb"), capture_output=True)
    assert result.returncode == 0, result.stderr
    np.testing.assert_allclose(json.loads(result.stdout)["X"], np.linalg.lstsq(A, B, rcond=None)[0], rtol=1e-10)
    assert b"standard input is read whole" in result.stderr
    result = subprocess.run([cli_path(), "fit", "--method", "ls", "--stream", "-", str(path / "B.csv")],
                            input=b"1,2\n3,x\n", capture_output=True)
    assert result.returncode == 1 and b"<stdin>:2:3: 'x' is not a number" in result.stderr


def test_a_file_whose_name_has_the_colon_wins(spdfit, data):
    path, A, B = data
    np.savetxt(path / "odd.csv:accel", A[:, :2] * 0, delimiter=",")  # a real file of that name
    result = spdfit("nearest", "--min-eig", "0", f"{path}/odd.csv:accel")
    assert result.returncode == 1 and "square" in result.stderr  # the 30x2 file, not a variable


@pytest.mark.parametrize("spec, fragments", [
    ("log.mat", ["holds 2 2-D numeric arrays (accel, force)", "its variables: accel, force, note",
                 "name one as", "log.mat:NAME"]),
    ("log.mat:nope", ["has no variable 'nope'; its variables: accel, force, note"]),
    ("log.mat:note", ["log.mat:note: is a char array, not a numeric matrix"]),
    ("log.npz", ["holds 2 arrays (accel, force): name one as", "log.npz:accel"]),
    ("log.npz:nope", ["has no array 'nope'; its arrays: accel, force"]),
    ("A.csv:x", ["holds one array, not named ones (only .mat and .npz files do)"]),
])
def test_messages_say_what_to_do(spdfit, data, spec, fragments):
    path, _, _ = data
    result = spdfit("fit", "--method", "ls", path / spec if ":" not in spec else f"{path}/{spec}", path / "B.csv")
    assert result.returncode == 1 and result.stdout == ""
    for fragment in fragments:
        assert fragment in result.stderr, (fragment, result.stderr)


def test_a_damaged_or_empty_npz_is_called_that(spdfit, data, tmp_path):
    """An .npz cut short, or with no arrays, is named as the archive it is meant to be (a ZIP file
    of another name is taken for a misnamed spreadsheet, as before)."""
    path, _, _ = data
    whole = (path / "log.npz").read_bytes()
    (tmp_path / "cut.npz").write_bytes(whole[:200])
    np.savez(tmp_path / "empty.npz")
    cases = [("cut.npz", "is not a ZIP archive (.npz) libzip can read (damaged or truncated?)"),
             ("cut.npz:accel", "is not a ZIP archive (.npz) libzip can read (damaged or truncated?)"),
             ("empty.npz", "holds no .npy arrays")]
    for spec, fragment in cases:
        result = spdfit("fit", "--method", "ls", f"{tmp_path}/{spec}", path / "B.csv")
        assert result.returncode == 1 and fragment in result.stderr, result.stderr
        assert "spreadsheet" not in result.stderr and "xlsx" not in result.stderr
    (tmp_path / "book.zip").write_bytes(whole[:200])
    result = spdfit("fit", "--method", "ls", tmp_path / "book.zip", path / "B.csv")
    assert result.returncode == 1 and "a ZIP archive, such as an Excel .xlsx workbook" in result.stderr


def test_complex_and_3d_arrays_are_refused(spdfit, tmp_path):
    scipy.io.savemat(tmp_path / "c.mat", {"Z": np.ones((4, 2)) * (1 + 1j), "T": np.ones((2, 2, 2))})
    for name, fragment in [("Z", "is complex"), ("T", "has 3 dimensions")]:
        result = spdfit("fit", "--method", "ls", f"{tmp_path}/c.mat:{name}", f"{tmp_path}/c.mat:{name}")
        assert result.returncode == 1 and fragment in result.stderr, result.stderr


def test_output_mat_reads_back_in_scipy(spdfit, data):
    path, _, _ = data
    expected, _ = estimate(spdfit, path / "A.csv", path / "B.csv")
    result = spdfit("fit", "--method", "ls", "-o", path / "X.mat", path / "A.csv", path / "B.csv")
    assert result.returncode == 0, result.stderr
    np.testing.assert_array_equal(scipy.io.loadmat(path / "X.mat")["X"], expected)
    usage = spdfit("fit", "--method", "ls", "--json", "-o", path / "X.mat", path / "A.csv", path / "B.csv")
    assert usage.returncode == 2 and "names a .mat file" in usage.stderr


# ---- Names in the output (issue 18) -------------------------------------------------------------

@pytest.mark.parametrize("stream", [[], ["--stream", "--block-rows", "5"]])
def test_header_and_json_name_x_by_the_files_columns(spdfit, tmp_path, stream):
    rng = np.random.default_rng(4)
    A = rng.standard_normal((20, 3))
    B = A @ rng.standard_normal((3, 2))
    # pandas' df.to_csv(): an index column under an empty header cell, dropped with a warning.
    (tmp_path / "A.csv").write_text("," + "Fx,Fy,Fz\n" + "".join(
        f"{i}," + ",".join(repr(v) for v in row) + "\n" for i, row in enumerate(A)))
    np.savetxt(tmp_path / "B.csv", B, delimiter=",", header='"g,1",g2', comments="")
    result = spdfit("fit", "--method", "ls", "--header", *stream, tmp_path / "A.csv", tmp_path / "B.csv")
    assert result.returncode == 0, result.stderr
    assert "first column holds row labels" in result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == '"","g,1","g2"'
    assert [line.split(",")[0] for line in lines[1:]] == ['"Fx"', '"Fy"', '"Fz"']
    j = json.loads(spdfit("fit", "--method", "ls", "--json", *stream, tmp_path / "A.csv", tmp_path / "B.csv").stdout)
    assert j["row_names"] == ["Fx", "Fy", "Fz"] and j["column_names"] == ["g,1", "g2"]
    # The numbers are the plain output's.
    plain = spdfit("fit", "--method", "ls", *stream, tmp_path / "A.csv", tmp_path / "B.csv").stdout
    X_back = np.array([[float(v) for v in line.split(",")[1:]] for line in lines[1:]])
    np.testing.assert_array_equal(X_back, np.loadtxt(plain.splitlines(), delimiter=","))


def test_header_numbers_names_when_the_files_have_none(spdfit, data):
    path, _, _ = data
    result = spdfit("fit", "--method", "ls", "--header", path / "A.csv", path / "B.csv")
    assert result.stdout.splitlines()[0] == '"","1","2","3"'
    assert spdfit("fit", "--method", "ls", "--header", "--json", path / "A.csv", path / "B.csv").returncode == 2
    assert spdfit("fit", "--method", "ls", "--header", "-o", path / "X.npy", path / "A.csv",
                  path / "B.csv").returncode == 2


def test_streaming_bootstrap_prints_the_readers_warnings(spdfit, tmp_path):
    rng = np.random.default_rng(5)
    A = rng.standard_normal((50, 2))
    (tmp_path / "A.csv").write_text(",x,y\n" + "".join(f"{i},{a},{b}\n" for i, (a, b) in enumerate(A)))
    np.savetxt(tmp_path / "B.csv", A * 2, delimiter=",")
    result = spdfit("fit", "--method", "ls", "--stream", "--bootstrap", "20", "--json", tmp_path / "A.csv",
                    tmp_path / "B.csv")
    assert result.returncode == 0, result.stderr
    assert "first column holds row labels" in result.stderr
    assert json.loads(result.stdout)["row_names"] == ["x", "y"]


def test_matlab_7_3_file(spdfit, tmp_path):
    # fuzz/corpus/mat/v73.mat: MATLAB 7.3 (HDF5), the 3 x 2 double variable A = [1 4; 2 5; 3 7],
    # written by libmatio's MAT_FT_MAT73 writer (test_mat73.py writes others with h5py). scipy
    # cannot read it; spdfit reads it through libmatio's HDF5 path.
    from spdfit_testing import SOURCE_DIR
    path = SOURCE_DIR / "fuzz" / "corpus" / "mat" / "v73.mat"
    assert path.read_bytes()[:19] == b"MATLAB 7.3 MAT-file"
    result = spdfit("fit", "--method", "ls", "--json", f"{path}:A", path)
    assert result.returncode == 0, result.stderr
    j = json.loads(result.stdout)
    assert (j["m"], j["n"]) == (3, 2)
    np.testing.assert_allclose(j["X"], np.eye(2), atol=1e-14)
    # The values: A x = [-7, -8, -11] has the exact solution x = [1, -2] only when A was read as
    # [1 4; 2 5; 3 7].
    (tmp_path / "b.csv").write_text("-7\n-8\n-11\n")
    solved = json.loads(spdfit("solve", "--json", path, tmp_path / "b.csv").stdout)
    np.testing.assert_allclose(np.ravel(solved["solution"]), [1.0, -2.0],
                               rtol=1e-13)


@pytest.mark.parametrize("name, fragment", [
    # 232 bytes declaring a 3 x 83886082 array, which libmatio would allocate and fill.
    ("declares_huge_array.mat", "an array declares 251658246 values in 56 bytes"),
    # 1 kB whose cell array declares 959328513 cells: libmatio asked for 7.8 GB reading its header.
    ("cell_of_959328513_cells.mat", "is a damaged .mat file"),
    # A stray miUINT32 element at the top level, for which libmatio asked for 4 GB.
    ("stray_top_level_element.mat", "an empty top-level array element"),
    # A struct whose field name length is not one int32: libmatio asked for 4 GB.
    ("struct_field_name_length.mat", "a struct without its field name length"),
    # An opaque object whose name libmatio read as a name tag of 1.6 GB (found by a 10-minute run).
    ("opaque_name_of_1_6_gb.mat", "an element declares 1627389755 bytes, more than it holds"),
])
def test_a_mat_file_that_declares_more_than_it_holds_is_refused_at_once(spdfit, name, fragment):
    # Found by the fuzzer (fuzz/regressions/mat): spdfit walks a level-5 file's structure before
    # libmatio reads it.
    from spdfit_testing import SOURCE_DIR
    path = SOURCE_DIR / "fuzz" / "regressions" / "mat" / name
    result = spdfit("fit", "--method", "ls", path, path)
    assert result.returncode == 1 and "is a damaged .mat file" in result.stderr and fragment in result.stderr
