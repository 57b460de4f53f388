"""`spdfit fit --stream`: the in-memory estimate to rounding from files read a block at a time,
the same JSON contract, the same bad-input errors, and the options' checks."""
import json

import numpy as np
import pytest

CLOSED_FORM = ["ls", "procrustes", "tls", "tls-sym", "tls-psd", "spde"]
# The iterative methods and auto work from the merged factor as from the in-memory one, so they
# agree to their convergence tolerance (spd-tls: gradient 1e-10 f; psd-ls: KKT residual 1e-12).
ITERATIVE = ["spd-tls", "psd-ls", "auto"]
METHODS = CLOSED_FORM + ITERATIVE


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """A noisy 6x6 problem with m = 20011 rows: A as CSV with a header, B as .npy."""
    d = tmp_path_factory.mktemp("stream")
    rng = np.random.default_rng(8)
    W = rng.standard_normal((6, 6))
    X = W @ W.T + 6 * np.eye(6)
    A0 = rng.uniform(-5, 5, (20011, 6))
    A = A0 + 0.3 * rng.standard_normal(A0.shape)
    B = A0 @ X + 0.3 * rng.standard_normal(A0.shape)
    np.savetxt(d / "A.csv", A, delimiter=",", fmt="%.17g", header="a1,a2,a3,a4,a5,a6", comments="")
    np.save(d / "B.npy", B)
    return d / "A.csv", d / "B.npy"


@pytest.mark.parametrize("method", METHODS)
def test_stream_gives_the_in_memory_estimate(spdfit, files, method):
    whole = spdfit("fit", "--method", method, "--json", *files)
    assert whole.returncode == 0, whole.stderr
    for extra in ([], ["--block-rows", "777", "--threads", "1"], ["--block-rows", "5000", "--threads", "2"]):
        streamed = spdfit("fit", "--method", method, "--json", "--stream", *extra, *files)
        assert streamed.returncode == 0, streamed.stderr
        a, b = json.loads(whole.stdout), json.loads(streamed.stdout)
        assert a.keys() == b.keys()
        X, Y = np.array(a["X"]), np.array(b["X"])
        # Blocked QR rounds differently: about cond * eps, far below 1e-12 on this data.
        tolerance = 1e-12 if method in CLOSED_FORM else 1e-9
        assert np.linalg.norm(X - Y) <= tolerance * np.linalg.norm(X), (method, extra)
        assert b["m"] == 20011


def test_stream_results_do_not_depend_on_threads(spdfit, files):
    outs = {spdfit("fit", "-m", "spde", "--stream", "--block-rows", "999", "--threads", t, *files).stdout
            for t in (1, 2, 5)}
    assert len(outs) == 1


def test_stream_reports_bad_data_with_file_and_line(spdfit, tmp_path):
    rows = "\n".join("1,2" for _ in range(5000))
    (tmp_path / "A.csv").write_text(rows + "\n1,x\n")
    (tmp_path / "B.csv").write_text(rows + "\n1,2\n")
    result = spdfit("fit", "-m", "spde", "--stream", "--block-rows", "100", tmp_path / "A.csv", tmp_path / "B.csv")
    assert result.returncode == 1
    assert f"{tmp_path / 'A.csv'}:5001:3: 'x' is not a number" in result.stderr


def test_stream_reports_unequal_row_counts(spdfit, tmp_path):
    (tmp_path / "A.csv").write_text("1,2\n3,4\n5,6\n")
    (tmp_path / "B.csv").write_text("1,2\n3,4\n")
    result = spdfit("fit", "-m", "ls", "--stream", tmp_path / "A.csv", tmp_path / "B.csv")
    assert result.returncode == 1
    assert "B has 2 rows but A (" in result.stderr and "has more" in result.stderr


@pytest.mark.parametrize("args", [["--block-rows", "0", "--stream"], ["--threads", "-1", "--stream"],
                                  ["--block-rows", "10"], ["--threads", "2"]])
def test_stream_options_are_checked(spdfit, files, args):
    result = spdfit("fit", "-m", "spde", *args, *files)
    assert result.returncode == 2, result.stdout
