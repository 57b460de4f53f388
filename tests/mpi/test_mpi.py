"""`mpirun -n K spdfit fit --stream` against the single-process `spdfit fit --stream`: the same
estimate for K = 1, 2, 3 (.npy and CSV, rows that do not divide evenly, lines of very different
lengths in A and B, a header and comments), how the rows were divided (--json), and errors that end
every process promptly with one message."""
import json
import os
import pathlib
import shutil
import subprocess
import sys

import numpy as np
import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "support"))

from spdfit_testing import SLOWDOWN, cli_path, mpirun_environment, run_cli  # noqa: E402

MPIRUN = shutil.which("mpirun")
pytestmark = pytest.mark.skipif(MPIRUN is None, reason="no mpirun (Debian: openmpi-bin)")

M, N = 10007, 4  # 10007 is prime: no K divides it


def mpirun(k, *args, env=None, timeout_s=120, program=None):
    """CompletedProcess of `mpirun -n k spdfit args...` (`program` instead of the spdfit under
    test if given); -q keeps mpirun's own notices out of stderr, so that what is left is spdfit's."""
    command = [MPIRUN, "-q", "--oversubscribe", "-n", str(k)]
    if os.geteuid() == 0:
        command.insert(1, "--allow-run-as-root")
    return subprocess.run(command + [program or cli_path(), *map(str, args)], capture_output=True, text=True,
                          timeout=timeout_s * SLOWDOWN, env=mpirun_environment(env))


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """The same noisy data as .npy files and as CSV: A with a header, comments and blank lines and
    short lines, B with long lines (17 digits) and CR LF line ends."""
    d = tmp_path_factory.mktemp("mpi")
    rng = np.random.default_rng(11)
    X = rng.standard_normal((N, N))
    X = X @ X.T + N * np.eye(N)
    A = np.round(rng.uniform(-5, 5, (M, N)), 2)
    B = A @ X + 0.05 * rng.standard_normal((M, N))
    np.save(d / "A.npy", A)
    np.save(d / "B.npy", B)
    lines = ["# accelerations", "", ",".join(f"a{j}" for j in range(N))]
    for i, row in enumerate(A):
        if i % 1000 == 0:
            lines += ["# block %d" % i, ""]
        lines.append(",".join("%g" % v for v in row))
    (d / "A.csv").write_text("\n".join(lines) + "\n")
    (d / "B.csv").write_bytes("".join(",".join("%.17g" % v for v in row) + "\r\n" for row in B).encode())
    return d


def fit_json(result):
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def single(files, kind, method, *extra):
    return fit_json(run_cli(cli_path(), "fit", "--method", method, "--stream", "--json", *extra,
                            files / f"A.{kind}", files / f"B.{kind}"))


def relative(X, Y):
    return np.abs(np.array(X) - np.array(Y)).max() / np.abs(np.array(Y)).max()


@pytest.mark.parametrize("kind", ["npy", "csv"])
@pytest.mark.parametrize("k", [1, 2, 3])
def test_every_process_count_gives_the_single_process_estimate(files, kind, k):
    for method in ["spde", "ls", "procrustes"]:
        reference = single(files, kind, method)
        out = fit_json(mpirun(k, "fit", "--method", method, "--stream", "--json", "--block-rows", "1000",
                              files / f"A.{kind}", files / f"B.{kind}"))
        assert relative(out["X"], reference["X"]) < 1e-12, method
        assert out["m"] == M
        assert out["processes"] == k
        assert len(out["rows_per_process"]) == k and sum(out["rows_per_process"]) == M
        assert max(out["rows_per_process"]) - min(out["rows_per_process"]) <= 1
        if kind == "csv":
            assert out["row_names"] == [f"a{j}" for j in range(N)]


def test_auto_makes_the_same_choice_and_spd_tls_agrees_to_its_tolerance(files):
    for method in ["auto", "spd-tls"]:
        reference = single(files, "csv", method)
        out = fit_json(mpirun(3, "fit", "--method", method, "--stream", "--json", files / "A.csv",
                              files / "B.csv"))
        assert out["method"] == reference["method"]
        assert relative(out["X"], reference["X"]) < 1e-8


def test_units_apply_to_the_merged_factor(files, tmp_path):
    """--scale-a and --scale-b (issue 42 item 2) under mpirun: B written in kN with --scale-b 1000
    gives the newton data's estimate of one process."""
    B = np.load(files / "B.npy")
    np.save(tmp_path / "B_kN.npy", B / 1000)
    reference = single(files, "npy", "spde")
    out = fit_json(mpirun(3, "fit", "--method", "spde", "--stream", "--json", "--scale-b", "1000",
                          files / "A.npy", tmp_path / "B_kN.npy"))
    assert relative(out["X"], reference["X"]) < 1e-12


def test_offsets_apply_to_the_merged_factor_of_one_a_b(files, tmp_path):
    """--offsets (issue 42 item 1) under mpirun: constants 1e4 times the columns' spread added to A
    and B leave X unchanged with --offsets estimate (each process factors [1 A B], the factors merge
    with their means), c the NumPy one; --offsets rest tares the merged factor as NumPy tares the rows."""
    A, B = np.load(files / "A.npy"), np.load(files / "B.npy")
    shift_a, shift_b = 1e4 * A.std(0) * np.arange(1, N + 1), -1e4 * B.std(0)
    np.save(tmp_path / "As.npy", A + shift_a)
    np.save(tmp_path / "Bs.npy", B + shift_b)
    reference = single(files, "npy", "spde", "--offsets", "estimate")
    out = fit_json(mpirun(3, "fit", "--method", "spde", "--stream", "--json", "--offsets", "estimate",
                          tmp_path / "As.npy", tmp_path / "Bs.npy"))
    assert relative(out["X"], reference["X"]) < 1e-10
    X = np.array(out["X"])
    c = (B + shift_b).mean(0) - X.T @ (A + shift_a).mean(0)
    np.testing.assert_allclose(out["offsets"]["c"], c, rtol=1e-9, atol=1e-9 * np.abs(shift_b).max())
    # rest: rows at rest with a load, given as files; the tared rows fitted in one process.
    rng = np.random.default_rng(5)
    rest_a, rest_b = 0.05 * rng.standard_normal((50, N)), 7.0 + 0.05 * rng.standard_normal((50, N))
    for name, M in [("rA", rest_a), ("rB", rest_b), ("Bl", B + 7.0), ("Bt", B + 7.0 - rest_b.mean(0)),
                    ("At", A - rest_a.mean(0))]:
        np.save(tmp_path / f"{name}.npy", M)
    rest = ["--rest-a", tmp_path / "rA.npy", "--rest-b", tmp_path / "rB.npy"]
    tared = fit_json(mpirun(3, "fit", "--method", "spd-tls", "--stream", "--json", "--offsets", "rest", *rest,
                            files / "A.npy", tmp_path / "Bl.npy"))
    by_hand = fit_json(run_cli(cli_path(), "fit", "--method", "spd-tls", "--json", *rest, tmp_path / "At.npy",
                               tmp_path / "Bt.npy"))
    assert relative(tared["X"], by_hand["X"]) < 1e-10
    np.testing.assert_allclose(tared["offsets"]["b"], rest_b.mean(0), rtol=1e-12)


def test_the_output_is_the_same_run_to_run_and_written_once(files, tmp_path):
    first = mpirun(3, "fit", "--method", "spde", "--stream", files / "A.csv", files / "B.csv")
    second = mpirun(3, "fit", "--method", "spde", "--stream", files / "A.csv", files / "B.csv")
    assert first.returncode == 0 and first.stdout == second.stdout
    assert len(first.stdout.splitlines()) == N  # one X, from process 0 only
    out = tmp_path / "X.npy"
    assert mpirun(2, "fit", "--method", "spde", "--stream", "-o", out, files / "A.npy",
                  files / "B.npy").returncode == 0
    assert relative(np.load(out), single(files, "npy", "spde")["X"]) < 1e-12


def test_the_streaming_bootstrap_is_the_single_process_one(tmp_path):
    # The Poisson bootstrap needs about 100 groups of 4096 rows: 409,600 rows and a few more.
    rng = np.random.default_rng(12)
    m = 100 * 4096 + 7
    A = rng.uniform(-5, 5, (m, 2))
    np.save(tmp_path / "A.npy", A)
    np.save(tmp_path / "B.npy", A @ np.array([[2.0, 0.5], [0.5, 1.0]]) + 0.05 * rng.standard_normal((m, 2)))
    reference = single(tmp_path, "npy", "spde", "--bootstrap", "30", "--seed", "4")
    assert reference["bootstrap"]["scheme"] == "poisson_groups"
    out = fit_json(mpirun(2, "fit", "--method", "spde", "--stream", "--json", "--bootstrap", "30", "--seed", "4",
                          tmp_path / "A.npy", tmp_path / "B.npy"))
    assert out["rows_per_process"][0] % 4096 == 0  # parts start at whole groups of rows
    se, se_ref = (np.array(o["standard_errors"]) for o in (out, reference))
    assert np.abs(se - se_ref).max() <= 1e-10 * np.abs(se_ref).max()


def test_the_streaming_bootstrap_on_too_few_rows_is_refused(files):
    # One process resamples such data in memory; spread over processes it cannot.
    result = mpirun(2, "fit", "--method", "spde", "--stream", "--bootstrap", "30", files / "A.npy", files / "B.npy")
    assert result.returncode == 1
    assert "needs about 100 groups (409600 rows)" in result.stderr and "have 10007 rows (3 groups)" in result.stderr
    assert "under MPI" in result.stderr


def errors(result):
    return [line for line in result.stderr.splitlines() if line.startswith("spdfit: error:")]


def test_a_bad_row_on_the_last_process_ends_every_process_with_one_message(files, tmp_path):
    text = (files / "B.csv").read_bytes().decode().split("\r\n")
    text[M - 3] = "1,2,x,4"
    bad = tmp_path / "B.csv"
    bad.write_bytes("\r\n".join(text).encode())
    alone = run_cli(cli_path(), "fit", "--method", "spde", "--stream", files / "A.csv", bad)
    assert alone.returncode == 1 and f"B.csv:{M - 2}:5: 'x' is not a number" in alone.stderr
    for k in [2, 3]:
        result = mpirun(k, "fit", "--method", "spde", "--stream", "--block-rows", "500", files / "A.csv", bad)
        assert result.returncode == 1
        assert errors(result) == errors(alone), result.stderr


def test_the_first_bad_row_in_the_files_order_is_the_one_reported(files, tmp_path):
    text = (files / "A.csv").read_text().splitlines()
    text[200] = "1,2,early,4"
    text[-5] = "1,2,late,4"
    bad = tmp_path / "A.csv"
    bad.write_text("\n".join(text) + "\n")
    result = mpirun(3, "fit", "--method", "spde", "--stream", "--block-rows", "500", bad, files / "B.csv")
    assert result.returncode == 1
    assert len(errors(result)) == 1 and "'early' is not a number" in errors(result)[0], result.stderr


def test_an_unreadable_file_ends_every_process(files, tmp_path):
    for b in [tmp_path / "missing.csv", tmp_path]:  # no such file; a directory
        result = mpirun(3, "fit", "--method", "spde", "--stream", files / "A.csv", b)
        assert result.returncode == 1
        assert len(errors(result)) == 1 and str(b) in errors(result)[0], result.stderr


def test_a_process_that_dies_ends_the_run(files):
    # Process 1 kills itself (SIGKILL) after its first block; mpirun ends the others instead of
    # leaving them waiting for it (the timeout would catch a hang).
    result = mpirun(3, "fit", "--method", "spde", "--stream", "--block-rows", "100", files / "A.csv",
                    files / "B.csv", env={"SPDFIT_TEST_MPI_DIE": "1"}, timeout_s=60)
    assert result.returncode != 0
    assert result.stdout == ""


def test_what_cannot_run_on_several_processes_is_a_usage_error(files, tmp_path):
    result = mpirun(2, "fit", "--method", "spde", files / "A.npy", files / "B.npy")
    assert result.returncode == 2 and len(errors(result)) == 1 and "add --stream" in result.stderr
    result = mpirun(2, "nearest", files / "A.csv")
    assert result.returncode == 2 and len(errors(result)) == 1 and "only 'spdfit fit --stream'" in result.stderr
    # A .mat file is not split among processes; one process reads it as without mpirun.
    subprocess.run([sys.executable, "-c", "import numpy, scipy.io, sys; "
                    "scipy.io.savemat(sys.argv[2], {'B': numpy.load(sys.argv[1])})",
                    files / "B.npy", tmp_path / "B.mat"], check=True)
    result = mpirun(2, "fit", "--method", "spde", "--stream", files / "A.npy", tmp_path / "B.mat")
    assert result.returncode == 1 and "cannot be split among processes" in result.stderr
    assert len(errors(result)) == 1
    result = mpirun(1, "fit", "--method", "spde", "--stream", files / "A.npy", tmp_path / "B.mat")
    assert result.returncode == 0, result.stderr


def test_mpi_is_loaded_only_under_a_launcher(files, tmp_path):
    """The MPI code is a plugin beside the program (spdfit-mpi.so), opened only under mpirun: a
    copy of the program without it runs alone as before, and under mpirun says what is missing."""
    alone = run_cli(cli_path(), "fit", "-m", "spde", "--stream", files / "A.npy", files / "B.npy")
    assert alone.returncode == 0, alone.stderr
    copy = tmp_path / "bin" / "spdfit"
    copy.parent.mkdir()
    shutil.copy(cli_path(), copy)
    copied_alone = run_cli(copy, "fit", "-m", "spde", "--stream", files / "A.npy", files / "B.npy")
    assert copied_alone.returncode == 0, copied_alone.stderr
    assert copied_alone.stdout == alone.stdout
    r = mpirun(2, "fit", "-m", "spde", "--stream", files / "A.npy", files / "B.npy", program=copy)
    assert r.returncode == 2
    assert "MPI's part of spdfit (spdfit-mpi.so) could not be loaded" in r.stderr
    assert str(copy.parent / "spdfit-mpi.so") in r.stderr
    # A shared object of that name that is not this build's plugin is refused, not called.
    linked = subprocess.run(["ldd", cli_path()], capture_output=True, text=True, check=True).stdout
    zlib = next(line.split("=>")[1].split()[0] for line in linked.splitlines() if "libz.so" in line)
    shutil.copy(zlib, copy.parent / "spdfit-mpi.so")
    r = mpirun(2, "fit", "-m", "spde", "--stream", files / "A.npy", files / "B.npy", program=copy)
    assert r.returncode == 2
    assert "is not the MPI plugin of this spdfit" in r.stderr, r.stderr


@pytest.mark.parametrize("kind", ["npy", "csv"])
def test_one_file_with_columns_gives_the_two_files_estimate(files, kind, tmp_path):
    """--a-cols/--b-cols under mpirun: the one file (a timestamp column, B's columns first) is split
    among the processes and gives the two files' estimate."""
    A, B = np.load(files / "A.npy"), np.load(files / "B.npy")
    if kind == "npy":
        np.save(tmp_path / "log.npy", np.hstack([B, A]))
        selection = ["--a-cols", f"{N + 1}:{2 * N}", "--b-cols", f"1:{N}"]
    else:
        header = ",".join(["time"] + [f"f{j}" for j in range(N)] + [f"a{j}" for j in range(N)])
        rows = [f"2026-11-27T10:{i // 6000:02d}:{i % 6000 / 100:05.2f}," + ",".join("%.17g" % v for v in row)
                for i, row in enumerate(np.hstack([B, A]))]
        (tmp_path / "log.csv").write_text(header + "\n" + "\n".join(rows) + "\n")
        selection = ["--a-cols", f"a0:a{N - 1}", "--b-cols", f"f0:f{N - 1}"]
    reference = single(files, "npy", "spde")
    for k in (1, 3):
        out = fit_json(mpirun(k, "fit", "--method", "spde", "--stream", "--json", "--block-rows", "1000",
                              tmp_path / f"log.{kind}", *selection))
        assert relative(out["X"], reference["X"]) < 1e-12
        assert out["m"] == M and sum(out["rows_per_process"]) == M


def test_a_spreadsheet_export_splits_as_it_reads(files, tmp_path):
    """A log as a spreadsheet exports it (issue 42): a units row under the header, empty rows of
    commas between data rows and after them. The processes count those lines as the parser reads
    them (not as rows), so that mpirun's fit is the one-process fit of the same rows, and NumPy's."""
    A, B = np.load(files / "A.npy"), np.load(files / "B.npy")
    names = [f"a{j}" for j in range(N)] + [f"f{j}" for j in range(N)]
    lines = [",".join(names), ",".join(["m/s^2"] * N + ["N"] * N)]
    for i, row in enumerate(np.hstack([A, B])):
        if i in (1, 4000, 7777):
            lines.append("," * (2 * N - 1))
        lines.append(",".join("%.17g" % v for v in row))
    lines += ["," * (2 * N - 1)] * 500
    log = tmp_path / "log.csv"
    log.write_text("\n".join(lines) + "\n")
    cols = ["--a-cols", f"a0:a{N - 1}", "--b-cols", f"f0:f{N - 1}"]
    reference = fit_json(run_cli(cli_path(), "fit", "--method", "ls", "--stream", "--json", *cols, log))
    np.testing.assert_allclose(reference["X"], np.linalg.lstsq(A, B, rcond=None)[0], rtol=1e-10, atol=1e-10)
    for k in (2, 3):
        result = mpirun(k, "fit", "--method", "ls", "--stream", "--json", "--block-rows", "1000", *cols, log)
        out = fit_json(result)
        assert out["m"] == M and sum(out["rows_per_process"]) == M
        assert relative(out["X"], reference["X"]) < 1e-12
