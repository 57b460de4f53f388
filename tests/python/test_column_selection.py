"""A and B from one file or one DataFrame: fit_files(path, a_cols=..., b_cols=...) and
fit(df, a_cols=..., b_cols=...), against the same columns given as two arrays."""
import os
import pickle
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import spdfit

SOURCE = Path(os.environ.get("SPDFIT_SOURCE_DIR", Path(__file__).resolve().parents[2]))
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


# One selection type, every function (issue 45): each form picks the same columns from the DataFrame
# (fit) and from the file it writes (fit_files, the command line's reader), and both results carry
# the labels.
FORMS = [("a1:a2", "f1:f2"), ("2:3", "4,5"), (["a1", "a2"], ["f1", "f2"]), ([1, 2], [3, 4]),
         (slice("a1", "a2"), slice(3, 5)), ("a1,a2", slice("f1", "f2"))]


@pytest.mark.parametrize("a_cols, b_cols", FORMS)
def test_every_form_picks_the_same_columns_from_a_dataframe_and_its_file(log, tmp_path, a_cols, b_cols):
    frame, A, B = log
    frame.to_csv(tmp_path / "log.csv", index=False)
    reference = spdfit.fit(A, B, "spd-tls").X
    in_memory = spdfit.fit(frame, method="spd-tls", a_cols=a_cols, b_cols=b_cols)
    from_file = spdfit.fit_files(tmp_path / "log.csv", method="spd-tls", a_cols=a_cols, b_cols=b_cols)
    np.testing.assert_allclose(in_memory.X, reference, rtol=0, atol=SAME_DATA_TOL)
    np.testing.assert_allclose(from_file.X, reference, rtol=0, atol=STREAM_TOL)
    for r in (in_memory, from_file):
        assert r.row_names == ["a1", "a2"] and r.column_names == ["f1", "f2"]
    assert in_memory.a_columns == "DataFrame columns a1..a2 (2-3)"
    assert in_memory.b_columns == "DataFrame columns f1..f2 (4-5)"
    assert from_file.a_columns == f"{tmp_path / 'log.csv'} columns a1..a2 (2-3)"


def test_labels_reach_the_report_and_the_json(log):
    frame, _, _ = log
    r = spdfit.fit(frame, method="spd-tls", a_cols="a1:a2", b_cols="f1:f2")
    text = repr(r)
    assert "a1" in text and "f2" in text
    restored = pickle.loads(pickle.dumps(r))
    assert restored.row_names == ["a1", "a2"] and restored.a_columns == r.a_columns


def test_dataframes_given_apart_label_the_result(log):
    frame, A, B = log
    r = spdfit.fit(frame[["a1", "a2"]], frame[["f1", "f2"]], "spd-tls")
    np.testing.assert_allclose(r.X, spdfit.fit(A, B, "spd-tls").X, rtol=0, atol=SAME_DATA_TOL)
    assert r.row_names == ["a1", "a2"] and r.column_names == ["f1", "f2"] and r.a_columns == ""
    assert spdfit.fit(A, B, "spd-tls").row_names == []  # arrays have no labels
    partial = spdfit.fit(frame[["a1", "a2"]], B, "spd-tls")
    assert partial.row_names == ["a1", "a2"] and partial.column_names == []


def test_fit_all_and_factor_take_the_columns_of_one_dataframe(log):
    frame, A, B = log
    results = spdfit.fit_all(frame, a_cols="a1:a2", b_cols=["f1", "f2"])
    for method, reference in spdfit.fit_all(A, B).items():
        np.testing.assert_allclose(results[method].X, reference.X, rtol=0, atol=SAME_DATA_TOL)
        assert results[method].row_names == ["a1", "a2"] and results[method].b_columns.endswith("(4-5)")
    factor = spdfit.Factor.from_data(frame, a_cols=slice(1, 3), b_cols=slice("f1", "f2"))
    np.testing.assert_allclose(factor.fit("spd-tls").X, spdfit.Factor.from_data(A, B).fit("spd-tls").X,
                               rtol=0, atol=SAME_DATA_TOL)
    with pytest.raises(TypeError, match=r"fit_all\(\) needs B"):
        spdfit.fit_all(frame)


def test_hexapod_and_physical_identify_take_the_columns_of_one_log():
    source = spdfit.hexapod.cubic_geometry()
    A = spdfit.read_matrix(SOURCE / "examples" / "hexapod" / "A.csv")
    B = spdfit.read_matrix(SOURCE / "examples" / "hexapod" / "B.csv")
    names = [f"acc{i}" for i in range(1, 7)] + [f"force{i}" for i in range(1, 7)]
    frame = pd.DataFrame(np.hstack([A, B]), columns=names)
    one = spdfit.hexapod.identify(frame, a_cols="acc1:acc6", b_cols="force1:force6", geometry=source)
    two = spdfit.hexapod.identify(A, B, geometry=source)
    for method in two:
        np.testing.assert_array_equal(one[method].result.X, two[method].result.X)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        p_one = spdfit.physical.identify(frame, geometry=source, a_cols=slice(0, 6), b_cols=slice(6, 12))
        p_two = spdfit.physical.identify(A, B, source)
    np.testing.assert_array_equal(p_one["M_p"], p_two["M_p"])


def test_dataframe_selection_errors_name_the_columns(log):
    frame, _, _ = log
    with pytest.raises(ValueError, match="no column named a9 in the DataFrame; its columns: time, a1, a2, f1, f2"):
        spdfit.fit(frame, a_cols="a1:a9", b_cols="f1:f2")
    with pytest.raises(ValueError, match="beyond the 5 columns of the DataFrame"):
        spdfit.fit(frame, a_cols="2:3", b_cols="4:6")
    with pytest.raises(ValueError, match="both select column 'a2'"):
        spdfit.fit(frame, a_cols="a1:a2", b_cols="a2:f1")


def test_fit_files_takes_slices(log, tmp_path):
    frame, A, B = log
    frame.to_csv(tmp_path / "log.csv", index=False)
    reference = spdfit.fit(A, B, "spd-tls").X
    r = spdfit.fit_files(tmp_path / "log.csv", method="spd-tls", a_cols=slice(1, 3), b_cols=slice("f1", "f2"))
    np.testing.assert_allclose(r.X, reference, rtol=0, atol=STREAM_TOL)
    with pytest.raises(ValueError, match="a slice with a step"):
        spdfit.fit_files(tmp_path / "log.csv", a_cols=slice(1, 3, 2), b_cols=slice(3, 5))
    with pytest.raises(ValueError, match="needs a non-negative start and an end"):
        spdfit.fit_files(tmp_path / "log.csv", a_cols=slice(1, None), b_cols=slice(3, 5))
    with pytest.raises(ValueError, match="chooses no columns"):
        spdfit.fit_files(tmp_path / "log.csv", a_cols=slice(3, 1), b_cols=slice(3, 5))


def test_fit_files_documents_every_form_it_takes():
    # The table's type is the command line's text; Python's fit_files takes lists and slices too.
    doc = spdfit.fit_files.__doc__
    assert "a_cols : str, list or slice, optional" in doc and "b_cols : str, list or slice, optional" in doc
    assert "as fit takes them from a DataFrame" in doc
