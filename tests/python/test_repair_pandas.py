"""pandas in, pandas out: nearest_correlation, nearest_covariance and nearest_spd return a DataFrame
with the input's labels and dtype when given one (df.corr(), df.cov()), NumPy when given NumPy;
masks and weights given as DataFrames are aligned by label, and kept entries may be label pairs."""
import warnings

import numpy as np
import pytest

import spdfit

pd = pytest.importorskip("pandas")

# Labels a CSV writer must quote: a comma, double quotes, a single quote, spaces, non-ASCII.
LABELS = ['rate, 10y', 'say "hi"', "it's", "plain", "µ-strain"]


def frame_with_gaps(seed=1, rows=60):
    """Returns with missing values: pairwise deletion (df.corr()) then gives an indefinite matrix."""
    rng = np.random.default_rng(seed)
    base = rng.standard_normal((rows, 2))
    data = np.column_stack([base[:, 0], base[:, 0] + 0.1 * rng.standard_normal(rows), base[:, 1],
                            base[:, 0] - base[:, 1], rng.standard_normal(rows)])
    df = pd.DataFrame(data, columns=LABELS)
    mask = rng.uniform(size=df.shape) < 0.3
    return df.mask(mask)


def quiet(function, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        return function(*args, **kwargs)


def test_a_dataframe_comes_back_as_one_with_its_labels():
    C = frame_with_gaps().corr()
    X = quiet(spdfit.nearest_correlation, C)
    assert isinstance(X, pd.DataFrame)
    assert list(X.index) == LABELS and list(X.columns) == LABELS
    assert X.dtypes.unique().tolist() == [np.float64]
    np.testing.assert_array_equal(X.to_numpy(), quiet(spdfit.nearest_correlation, C.to_numpy()))
    assert isinstance(quiet(spdfit.nearest_correlation, C.to_numpy()), np.ndarray)
    S = frame_with_gaps().cov()
    for function in (spdfit.nearest_covariance, spdfit.nearest_spd):
        Y = quiet(function, S)
        assert isinstance(Y, pd.DataFrame) and list(Y.columns) == LABELS


def test_float32_frames_keep_their_dtype():
    C = frame_with_gaps().corr().astype(np.float32)
    X = quiet(spdfit.nearest_correlation, C)
    assert X.dtypes.unique().tolist() == [np.float32]


def test_masks_and_weights_align_by_label_and_pairs_are_labels():
    df = frame_with_gaps()
    C = df.corr()
    # Weights from the observations each pair shares, as pairwise deletion used them.
    seen = df.notna().astype(float)
    counts = seen.T @ seen
    shuffled = counts.loc[LABELS[::-1], LABELS[::-1]]
    a = quiet(spdfit.nearest_correlation, C, h_weights=counts, full_output=True)
    b = quiet(spdfit.nearest_correlation, C, h_weights=shuffled, full_output=True)
    np.testing.assert_array_equal(a.X, b.X)
    # A trusted pair kept exactly, by label.
    X = quiet(spdfit.nearest_correlation, C, fixed=[(LABELS[0], LABELS[1])])
    assert X.loc[LABELS[0], LABELS[1]] == C.loc[LABELS[0], LABELS[1]]
    assert X.loc[LABELS[1], LABELS[0]] == C.loc[LABELS[1], LABELS[0]]
    mask = pd.DataFrame(0.0, index=LABELS, columns=LABELS)
    mask.loc[LABELS[0], LABELS[1]] = mask.loc[LABELS[1], LABELS[0]] = 1.0
    Y = quiet(spdfit.nearest_correlation, C, fixed=mask.loc[LABELS[::-1], LABELS[::-1]])
    pd.testing.assert_frame_equal(X, Y)
    with pytest.raises(ValueError, match="no variable 'nope'"):
        spdfit.nearest_correlation(C, fixed=[(LABELS[0], "nope")])
    with pytest.raises(spdfit.DataError, match="labels differ"):
        spdfit.nearest_correlation(C, h_weights=counts.rename(columns={LABELS[0]: "other"}))


def test_factors_only_gives_loadings_named_by_variable():
    C = frame_with_gaps(rows=200).corr()
    F = quiet(spdfit.nearest_correlation, C, factors=2, factors_only=True)
    assert isinstance(F, pd.DataFrame) and list(F.index) == LABELS
    assert list(F.columns) == ["factor 1", "factor 2"]


def test_full_output_is_the_result():
    C = frame_with_gaps().corr()
    r = quiet(spdfit.nearest_correlation, C, full_output=True)
    assert isinstance(r, spdfit.NearestResult) and r.X.shape == (5, 5)


def test_a_pair_never_observed_together_is_named_by_its_labels():
    # df.corr() gives NaN for two columns that never overlap; the message names the pair (issue 45),
    # where it said "contains NaN or Inf". An array gets row and column (from 1) and the NumPy index.
    pd = pytest.importorskip("pandas")
    labels = ["oil", "gas", "coal"]
    C = pd.DataFrame([[1.0, 0.5, np.nan], [0.5, 1.0, 0.2], [np.nan, 0.2, 1.0]], index=labels, columns=labels)
    with pytest.raises(spdfit.DataError, match=r"has NaN at \('oil', 'coal'\) \(iloc \[0, 2\]\): a pair of variables "
                                               r"never observed together"):
        spdfit.nearest_correlation(C)
    with pytest.raises(ValueError, match=r"has NaN at row 1, column 3 \(counting from 1; \[0, 2\] in NumPy\)"):
        spdfit.nearest_correlation(C.to_numpy())
    with pytest.raises(ValueError, match=r"has Inf at row 2, column 2"):
        spdfit.nearest_spd(np.diag([1.0, np.inf, 1.0]))


def test_read_matrix_reads_an_empty_field_as_nan_where_nan_is_allowed(tmp_path):
    (tmp_path / "holes.csv").write_text("1,,3\n4,5,\n")
    X = spdfit.read_matrix(tmp_path / "holes.csv", allow_nonfinite=True)
    np.testing.assert_array_equal(np.isnan(X), [[False, True, False], [False, False, True]])
    with pytest.raises(spdfit.DataError, match="empty field"):
        spdfit.read_matrix(tmp_path / "holes.csv")
