"""A and B from one file or one DataFrame: fit_files(path, a_cols=..., b_cols=...) and
fit(df, a_cols=..., b_cols=...), against the same columns given as two arrays."""
import warnings

import numpy as np
import pandas as pd
import pytest

import spdfit

# The same doubles through the same arithmetic: equal to the last bit; the bound allows only for a
# different summation order.
SAME_DATA_TOL = 1e-13
# fit_files streams (per-block QR factors merged) where fit factors once: equal to rounding.
STREAM_TOL = 1e-12


@pytest.fixture(scope="module")
def log():
    rng = np.random.default_rng(7)
    X = np.array([[2.0, 0.3], [0.3, 1.0]])
    A0 = rng.uniform(-3, 3, (30, 2))
    A = A0 + 0.05 * rng.standard_normal((30, 2))
    B = A0 @ X + 0.05 * rng.standard_normal((30, 2))
    frame = pd.DataFrame({"time": pd.date_range("2026-01-01", periods=30, freq="s"), "a1": A[:, 0], "a2": A[:, 1],
                          "f1": B[:, 0], "f2": B[:, 1]})
    return frame, A, B


def test_fit_files_string_and_list_forms(log, tmp_path):
    frame, A, B = log
    frame.to_csv(tmp_path / "log.csv", index=False)
    reference = spdfit.fit(A, B, "spd-tls").X
    for a_cols, b_cols in [("a1:a2", "f1:f2"), ("2:3", "4,5"), (["a1", "a2"], [3, 4]), ([1, "a2"], ("f1", 4))]:
        r = spdfit.fit_files(tmp_path / "log.csv", method="spd-tls", a_cols=a_cols, b_cols=b_cols)
        np.testing.assert_allclose(r.X, reference, rtol=0, atol=STREAM_TOL)
        assert r.row_names == ["a1", "a2"] and r.column_names == ["f1", "f2"]


def test_fit_files_npz(log, tmp_path):
    _, A, B = log
    np.savez(tmp_path / "log.npz", log=np.hstack([B, A]))
    r = spdfit.fit_files(tmp_path / "log.npz", method="spd-tls", a_cols=[2, 3], b_cols="1:2")
    np.testing.assert_allclose(r.X, spdfit.fit(A, B, "spd-tls").X, rtol=0, atol=STREAM_TOL)
    with pytest.raises(ValueError, match="a_cols 'a1:a2'.*no column names"):
        spdfit.fit_files(tmp_path / "log.npz", a_cols="a1:a2", b_cols="1:2")


def test_fit_files_errors(log, tmp_path):
    frame, _, _ = log
    frame.to_csv(tmp_path / "log.csv", index=False)
    path = tmp_path / "log.csv"
    with pytest.raises(ValueError, match="no column named a9.*its columns: time, a1, a2, f1, f2"):
        spdfit.fit_files(path, a_cols="a1:a9", b_cols="f1:f2")
    with pytest.raises(ValueError, match="both select column 3 \\(a2\\)"):
        spdfit.fit_files(path, a_cols="a1:a2", b_cols="a2:f2")
    with pytest.raises(ValueError, match="come together"):
        spdfit.fit_files(path, a_cols="a1:a2")
    with pytest.raises(ValueError, match="two files were given"):
        spdfit.fit_files(path, path, a_cols="a1:a2", b_cols="f1:f2")
    with pytest.raises(ValueError, match="count from 0"):
        spdfit.fit_files(path, a_cols=[-1], b_cols=[3])
    with pytest.raises(TypeError, match="needs B_path"):
        spdfit.fit_files(path)
    with pytest.raises(spdfit.DataError, match="is not a number"):
        spdfit.fit_files(path, a_cols="time,a1", b_cols="f1:f2")


def test_fit_dataframe(log):
    frame, A, B = log
    reference = spdfit.fit(A, B, "spd-tls").X
    for a_cols, b_cols in [(["a1", "a2"], ["f1", "f2"]), ([1, 2], [3, 4]), (slice("a1", "a2"), slice(3, 5))]:
        X = spdfit.fit(frame, method="spd-tls", a_cols=a_cols, b_cols=b_cols).X
        np.testing.assert_allclose(X, reference, rtol=0, atol=SAME_DATA_TOL)
    with pytest.raises(ValueError, match="both select column 'a2'"):
        spdfit.fit(frame, a_cols=["a1", "a2"], b_cols=["a2", "f1"])
    with pytest.raises(ValueError, match="no column 'a9'"):
        spdfit.fit(frame, a_cols=["a1", "a9"], b_cols=["f1", "f2"])
    with pytest.raises(ValueError, match="come together"):
        spdfit.fit(frame, a_cols=["a1", "a2"])
    with pytest.raises(ValueError, match=r"give the method by name, method='spde'"):
        spdfit.fit(frame, "spde", a_cols=["a1", "a2"], b_cols=["f1", "f2"])
    with pytest.raises(TypeError, match="DataFrame"):
        spdfit.fit(frame.to_numpy()[:, 1:], a_cols=[0, 1], b_cols=[2, 3])
    with pytest.raises(ValueError):  # the timestamps are not numbers
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            spdfit.fit(frame, a_cols=["time", "a1"], b_cols=["f1", "f2"])
