"""spdfit.Factor, the mergeable triangular factor (issue 20): the factors of a split of the rows,
merged, give spdfit.fit's estimate on all of them and the independent NumPy reference's
(tests/reference/thesis_reference.py: lstsq, the SVD of [A B], the documents' Gram-matrix
formulas); the merge is associative to rounding and leaves its inputs alone; the bytes follow the
layout documented in spdfit/triangular_factor.hpp, decoded here with struct, and are the pickle;
bad input raises ValueError or TypeError with the library's message; and the Dask route (blocks of
a dask.array, a factor per block, a pairwise tree of dask.delayed merges) runs on the process
scheduler."""
import copyreg
import functools
import os
import pickle
import struct
import warnings

import numpy as np
import pytest

import spdfit
import thesis_reference as ref
from spdfit import _spdfit
from spdfit_testing import save_csv

EPS = np.finfo(float).eps
# Merging re-triangularizes: a few Householder QRs of (n + d) x (n + d) blocks per merge, each
# backward stable to O((n + d) eps). The closed-form estimates of well-conditioned data (cond(A)
# about 3 here) then move by O(k (n + d) eps) for k merges: 1e-12 relative is the bound
# and leaves two orders of magnitude of room over the 1e-15 observed.
MERGE_RTOL = 1e-12
# The reference works from the Gram matrices A^T A and B^T B, as the documents' M-files do, so
# it is accurate to cond(A)^2 eps (about 1e-15 here); 1e-10 allows ill-luck in the draw.
REFERENCE_RTOL = 1e-10
# The iterative methods stop at their convergence tests (spd-tls: ||X^1/2 grad f X^1/2||_F <=
# 1e-10 f; psd-ls: a relative KKT residual <= 1e-12), so two routes whose data differ by rounding
# agree to about the stopping tolerance, not to eps: 1e-8 relative bounds the first.
ITERATIVE_RTOL = 1e-8
# R^T R is the scaled Gram matrix of [A B] to O(m eps) relative in each of the two groupings.
GRAM_RTOL = 1e-12

CLOSED_FORM = ["ls", "procrustes", "tls", "tls-sym", "tls-psd", "spde"]
# psd-ls's floor above the smallest eigenvalues of the truth (1, 2, 3, 4), so that the constraint
# is active and psd-ls iterates instead of returning Procrustes.
PSD_LS_FLOOR = 2.5


def rel(X, Y):
    return np.linalg.norm(X - Y) / np.linalg.norm(Y)


def problem(m=3000, n=4, d=None, sigma=0.3, seed=20):
    """A X ~= B with an SPD truth of eigenvalues 1..n (d = n) or a random n x d X, noise sigma in both."""
    rng = np.random.default_rng(seed)
    d = n if d is None else d
    if d == n:
        Q = np.linalg.qr(rng.standard_normal((n, n)))[0]
        X = Q @ np.diag(np.arange(1.0, n + 1)) @ Q.T
    else:
        X = rng.standard_normal((n, d))
    A0 = rng.standard_normal((m, n))
    return A0 + sigma * rng.standard_normal((m, n)), A0 @ X + sigma * rng.standard_normal((m, d))


def split(A, B, cuts):
    """The factors of the row blocks between consecutive cuts (an empty block where two are equal)."""
    bounds = [0, *cuts, A.shape[0]]
    return [spdfit.Factor.from_data(A[a:b], B[a:b]) for a, b in zip(bounds, bounds[1:])]


def merge_all(factors):
    return functools.reduce(spdfit.Factor.merge, factors)


# Uneven blocks, with an empty one and a one-row one.
CUTS = [1, 1, 500, 1733]


def decode(data):
    """(n, d, rows, exponent_a, exponent_b, R) from a factor's bytes, read by the layout that
    include/spdfit/triangular_factor.hpp documents for TriangularFactor::serialize (independently
    of the library's reader): magic, uint32 layout (1: d = n, 2: d follows n), int64 n, [int64 d],
    uint64 rows, for A then B a flag byte and an int32 exponent, then the upper triangle of R
    column by column, all little-endian."""
    assert data[:8] == b"spdfitR\0"
    (layout,) = struct.unpack_from("<I", data, 8)
    (n,) = struct.unpack_from("<q", data, 12)
    at, d = 20, n
    if layout == 2:
        (d,) = struct.unpack_from("<q", data, at)
        at += 8
    else:
        assert layout == 1
    (rows,) = struct.unpack_from("<Q", data, at)
    at += 8
    exponents = []
    for _ in range(2):
        flag, exponent = struct.unpack_from("<Bi", data, at)
        exponents.append(exponent if flag else 0)
        at += 5
    size = n + d
    R = np.zeros((size, size))
    columns = np.triu_indices(size)
    order = np.lexsort((columns[0], columns[1]))  # column by column, rows ascending within each
    R[columns[0][order], columns[1][order]] = struct.unpack_from(f"<{len(order)}d", data, at)
    assert at + 8 * len(order) == len(data)
    return n, d, rows, exponents[0], exponents[1], R


def scaled_gram(A, B, exponent_a, exponent_b):
    Z = np.hstack([A * 2.0 ** -exponent_a, B * 2.0 ** -exponent_b])
    return Z.T @ Z


# ---- the estimate of merged factors ------------------------------------------------------------

@pytest.mark.parametrize("method", CLOSED_FORM)
def test_merged_factors_give_the_fit_of_all_rows(method):
    A, B = problem()
    r = merge_all(split(A, B, CUTS)).fit(method)
    assert r.method == method and r.diagnostics.m == A.shape[0]
    assert rel(r.X, spdfit.fit(A, B, method).X) < MERGE_RTOL
    assert rel(r.X, ref.METHODS[method](A, B)) < REFERENCE_RTOL
    # The diagnostics are of all the rows: the residual is numpy's for the returned X.
    assert r.diagnostics.residual_norm == pytest.approx(np.linalg.norm(A @ r.X - B), rel=MERGE_RTOL)


def test_least_squares_is_lstsq():
    A, B = problem(seed=5)
    X = merge_all(split(A, B, CUTS)).fit("ls").X
    assert rel(X, np.linalg.lstsq(A, B, rcond=None)[0]) < MERGE_RTOL


def test_spde_minimizes_the_area_criterion():
    # Chen & McInroy, Corollary III.4: the area criterion's minimum is 2 tr(Sigma_Q~ - A^T B).
    A, B = problem(seed=6)
    X = merge_all(split(A, B, CUTS)).fit("spde").X
    assert ref.area_criterion(A, B, X) == pytest.approx(ref.area_minimum(A, B), rel=REFERENCE_RTOL)


@pytest.mark.parametrize("method, options", [("spd-tls", {}), ("psd-ls", {"min_eig": PSD_LS_FLOOR}),
                                             ("auto", {})])
def test_iterative_methods_agree_to_their_tolerance(method, options):
    A, B = problem(seed=7)
    r = merge_all(split(A, B, CUTS)).fit(method, **options)
    r0 = spdfit.fit(A, B, method, **options)
    assert r.method == r0.method  # auto makes the same choice
    assert r.diagnostics.converged and r0.diagnostics.converged
    assert rel(r.X, r0.X) < ITERATIVE_RTOL
    if method == "psd-ls":
        # The floor is active (the truth's eigenvalues are 1..4), and the certificate holds.
        assert np.linalg.eigvalsh(r.X)[0] == pytest.approx(PSD_LS_FLOOR, rel=1e-12)
        c = r.diagnostics.certificate
        assert c.dual_min_eig > -1e-10 and abs(c.duality_gap) < 1e-12


def test_the_options_reach_the_estimator():
    A, B = problem(seed=8)
    f = spdfit.Factor.from_data(A, B)
    assert rel(f.fit("tls", noise_ratio=0.5).X, spdfit.fit(A, B, "tls", noise_ratio=0.5).X) < MERGE_RTOL
    assert rel(f.fit("tls", noise_ratio=0.5).X, f.fit("tls").X) > 1e-6
    with pytest.warns(spdfit.SpdfitWarning, match="did not converge in 1 iterations"):
        limited = f.fit("spd-tls", max_iter=1)
    assert limited.diagnostics.iterations == 1 and not limited.diagnostics.converged


# ---- the merge as a value ------------------------------------------------------------------

def test_merge_is_associative_to_rounding():
    A, B = problem(seed=9)
    f, g, h = split(A, B, [700, 1900])
    left, right = f.merge(g).merge(h), f.merge(g.merge(h))
    n, d, rows, ea, eb, R_left = decode(left.to_bytes())
    assert (n, d, rows) == (4, 4, A.shape[0])
    R_right = decode(right.to_bytes())[5]
    assert decode(right.to_bytes())[:5] == (n, d, rows, ea, eb)
    # R is unique up to the signs of its rows: R^T R is the (scaled) Gram matrix either way.
    gram = scaled_gram(A, B, ea, eb)
    assert rel(R_left.T @ R_left, gram) < GRAM_RTOL
    assert rel(R_right.T @ R_right, gram) < GRAM_RTOL
    for method in CLOSED_FORM:
        assert rel(left.fit(method).X, right.fit(method).X) < MERGE_RTOL, method


def test_merge_leaves_its_inputs_unchanged():
    A, B = problem(seed=10)
    f, g = split(A, B, [1200])
    before = f.to_bytes(), g.to_bytes()
    merged = f.merge(g)
    assert (f.to_bytes(), g.to_bytes()) == before
    assert merged is not f and merged is not g
    assert (f.rows, g.rows, merged.rows) == (1200, A.shape[0] - 1200, A.shape[0])
    f.merge(f)  # a factor merged with itself counts its rows twice, and is still unchanged
    assert f.to_bytes() == before[0]
    assert f.merge(f).rows == 2 * f.rows


def test_the_empty_factor_is_the_neutral_element():
    A, B = problem(seed=11)
    f = spdfit.Factor.from_data(A, B)
    empty = spdfit.Factor(4)
    assert (empty.n, empty.d, empty.rows) == (4, 4, 0)
    assert spdfit.Factor(4, 2).d == 2
    for merged in (empty.merge(f), f.merge(empty)):
        assert merged.rows == f.rows
        assert rel(merged.fit("spde").X, f.fit("spde").X) < MERGE_RTOL


def test_rows_n_d_and_repr():
    A, B = problem(m=50, n=3, d=2, seed=12)
    f = spdfit.Factor.from_data(A, B)
    assert (f.rows, f.n, f.d) == (50, 3, 2)
    assert repr(f) == "Factor(n=3, d=2, rows=50)"
    g = spdfit.Factor.from_data(A[:, 0], B[:, 0])  # 1-D arrays are one column each
    assert (g.n, g.d) == (1, 1)


def test_the_gram_matrix_of_any_dtype_and_layout():
    A, B = problem(m=40, n=3, seed=13)
    for a, b in [(A.astype(np.float32), B.astype(np.float32)), (np.asfortranarray(A), B[:, ::-1]),
                 (np.rint(A * 10).astype(np.int64), np.rint(B * 10).astype(np.int32))]:
        _, _, rows, ea, eb, R = decode(spdfit.Factor.from_data(a, b).to_bytes())
        assert rows == 40
        assert rel(R.T @ R, scaled_gram(np.asarray(a, float), np.asarray(b, float), ea, eb)) < GRAM_RTOL


# ---- non-square X (d != n) -----------------------------------------------------------------------

def test_a_non_square_factor_fits_ls_and_tls_only():
    A, B = problem(m=400, n=3, d=2, sigma=0.05, seed=14)
    f = merge_all(split(A, B, [100, 101, 333]))
    assert (f.n, f.d) == (3, 2)
    assert rel(f.fit("ls").X, np.linalg.lstsq(A, B, rcond=None)[0]) < MERGE_RTOL
    assert rel(f.fit("tls").X, ref.tls(A, B)) < REFERENCE_RTOL
    assert f.fit("tls").X.shape == (3, 2)
    for method in spdfit.METHODS:
        if method not in ("ls", "tls"):
            with pytest.raises(ValueError, match=f"{method} estimates a symmetric X.*use ls or tls"):
                f.fit(method)
    # Layout 2, with d after n, and a round trip bit for bit.
    assert decode(f.to_bytes())[:3] == (3, 2, 400)
    assert struct.unpack_from("<I", f.to_bytes(), 8) == (2,)
    assert spdfit.Factor.from_bytes(f.to_bytes()).to_bytes() == f.to_bytes()


def test_tls_with_a_non_square_x_needs_n_plus_d_rows():
    A, B = problem(m=4, n=3, d=2, seed=15)
    f = spdfit.Factor.from_data(A, B)
    with pytest.warns(spdfit.SpdfitWarning, match="degrees of freedom"):  # m - n = 1 < n
        assert f.fit("ls").ok
    with pytest.raises(ValueError, match="n \\+ d = 5"):
        f.fit("tls")


# ---- bytes and pickling ----------------------------------------------------------------------------

@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
def test_pickle_round_trip_bit_for_bit(protocol):
    A, B = problem(seed=16)
    f = merge_all(split(A, B, CUTS))
    data = pickle.dumps(f, protocol=protocol)
    g = pickle.loads(data)
    assert type(g) is spdfit.Factor
    assert g.to_bytes() == f.to_bytes()
    assert np.array_equal(g.fit("spde").X, f.fit("spde").X)
    if protocol >= 3:  # protocols 0-2 write bytes in a text form
        assert f.to_bytes() in data  # the pickle holds the library's serialization


def test_the_compiled_factor_pickles_as_its_bytes():
    core = _spdfit.TriangularFactor.from_data(*problem(m=20, n=2, seed=17))
    assert pickle.loads(pickle.dumps(core)).serialize() == core.serialize()
    assert core.serialize() in pickle.dumps(core)


def test_from_bytes_takes_any_bytes_like():
    f = spdfit.Factor.from_data(*problem(m=20, n=2, seed=18))
    data = f.to_bytes()
    for view in (bytearray(data), memoryview(data)):
        assert spdfit.Factor.from_bytes(view).to_bytes() == data
    with pytest.raises(TypeError, match="data must be bytes, got str"):
        spdfit.Factor.from_bytes(data.decode("latin-1"))


def corrupted(data):
    """(what is wrong, bytes): one corruption of each kind the library checks."""
    nan = struct.pack("<d", float("nan"))
    return [
        ("wrong magic bytes", b"X" + data[1:]),
        ("layout version 7 is not 1, 2 or 3", data[:8] + struct.pack("<I", 7) + data[12:]),
        ("end inside", data[:10]),
        ("bytes of R", data[:-3]),
        ("bytes of R", data + b"\0"),
        ("is not finite", data[:-8] + nan),
        ("an exponent flag is 2, not 0 or 1", data[:28] + b"\x02" + data[29:]),  # after magic, layout, n, rows
        ("exponent 2000 is out of range", data[:29] + struct.pack("<i", 2000) + data[33:]),
        ("layout 2 with d = n", data[:8] + struct.pack("<I", 2) + data[12:20] + data[12:20] + data[20:]),
    ]


@pytest.mark.parametrize("index", range(9))
def test_corrupted_bytes_raise_the_librarys_message(index):
    data = spdfit.Factor.from_data(*problem(m=20, n=2, seed=19)).to_bytes()
    what, bad = corrupted(data)[index]
    with pytest.raises(ValueError, match=f"TriangularFactor::deserialize: .*{what}"):
        spdfit.Factor.from_bytes(bad)
    # A pickle holding them (as a Factor's pickle holds its bytes) is refused the same way.
    assert Forged(data).__reduce__()[2] == spdfit.Factor.from_bytes(data).__reduce_ex__(2)[2]
    with pytest.raises(ValueError, match=f"TriangularFactor::deserialize: .*{what}"):
        pickle.loads(pickle.dumps(Forged(bad)))


class Forged:
    """Pickles as a Factor whose state is `state` (as pickle's protocols 0 and 1 write one)."""

    def __init__(self, state):
        self.state = state

    def __reduce__(self):
        return copyreg._reconstructor, (spdfit.Factor, object, None), self.state


# ---- bad input ---------------------------------------------------------------------------------

def test_bad_data_is_refused_with_the_librarys_message():
    A, B = problem(m=10, n=2, seed=21)
    with pytest.raises(ValueError, match="A is 10x2 but B is 9x2: they must have the same numbers of rows"):
        spdfit.Factor.from_data(A, B[:9])
    corner = np.eye(10, 2) > 0
    for name, a, b in [("A", np.where(corner, np.nan, A), B), ("B", A, np.where(corner, np.inf, B))]:
        with pytest.raises(ValueError, match=f"{name} contains NaN or Inf"):
            spdfit.Factor.from_data(a, b)
    with pytest.raises(ValueError, match="A must be a real numeric array, got dtype complex128"):
        spdfit.Factor.from_data(A + 1j, B)
    with pytest.raises(ValueError, match="B must be a matrix \\(2-D array\\), got 3 dimensions"):
        spdfit.Factor.from_data(A, B[None])
    with pytest.raises(ValueError, match="at least one column"):
        spdfit.Factor.from_data(A[:, :0], B)


def test_merging_factors_of_other_columns_is_refused():
    A, B = problem(m=10, n=2, seed=22)
    f = spdfit.Factor.from_data(A, B)
    for other in (spdfit.Factor.from_data(A[:, :1], B), spdfit.Factor.from_data(A, B[:, :1])):
        with pytest.raises(ValueError, match="cannot merge factors of A and B with 2 and 2 columns and with"):
            f.merge(other)
        with pytest.raises(ValueError, match="cannot merge"):
            other.merge(f)
    with pytest.raises(TypeError, match="other must be a spdfit.Factor, got FitResult"):
        f.merge(f.fit("ls"))


def test_bad_constructor_arguments():
    for n, d in [(0, None), (2, 0), (-1, None)]:
        with pytest.raises(ValueError, match="at least one column"):
            spdfit.Factor(n, d)
    with pytest.raises(TypeError, match="n must be an int, got float"):
        spdfit.Factor(2.0)
    with pytest.raises(TypeError, match="d must be an int, got str"):
        spdfit.Factor(2, "2")


def test_fit_refuses_what_a_factor_cannot_do():
    A, B = problem(m=10, n=3, seed=23)
    f = spdfit.Factor.from_data(A, B)
    with pytest.raises(ValueError, match="cannot bootstrap.*spdfit.fit\\(A, B, bootstrap=N\\).*fit_files"):
        f.fit("spde", bootstrap=100)
    with pytest.raises(ValueError, match="noise_ratio applies to .*not to ls"):
        f.fit("ls", noise_ratio=2.0)
    with pytest.raises(ValueError, match="unknown method 'nope'"):
        f.fit("nope")
    with pytest.raises(TypeError, match="method must be a str"):
        f.fit(3)
    with pytest.raises(TypeError, match="max_iter must be an int, got float"):
        f.fit("spd-tls", max_iter=2.5)
    with pytest.raises(TypeError, match="bootstrap must be an int"):
        f.fit("spde", bootstrap="many")
    # Fewer rows than columns: the message of spdfit.fit on the same rows.
    few = spdfit.Factor.from_data(A[:2], B[:2])
    with pytest.raises(ValueError) as from_factor:
        few.fit("ls")
    with pytest.raises(ValueError) as in_memory:
        spdfit.fit(A[:2], B[:2], "ls")
    assert str(from_factor.value) == str(in_memory.value)


def test_numerical_failures_and_warnings_are_fits():
    # A of rank 1 < n: spde has no answer (NumericalError with the failed result), and ls warns
    # of the rank deficiency, as spdfit.fit does on the same rows.
    rng = np.random.default_rng(24)
    A = np.outer(rng.standard_normal(30), [1.0, 2.0])
    B = rng.standard_normal((30, 2))
    f = merge_all(split(A, B, [10, 20]))
    with pytest.raises(spdfit.NumericalError) as error:
        f.fit("spde")
    with pytest.raises(spdfit.NumericalError) as in_memory:
        spdfit.fit(A, B, "spde")
    assert str(error.value) == str(in_memory.value)
    assert error.value.result.diagnostics.rank_a == 1
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = f.fit("ls")
    assert [str(w.message) for w in caught] == [f"ls: {m}" for m in r.warnings] and r.warnings
    # Each with its code's class, a subclass of SpdfitWarning (r.warning_codes names them).
    assert [w.category for w in caught] == [spdfit._errors.warning_class(c) for c in r.warning_codes]
    assert all(issubclass(w.category, spdfit.SpdfitWarning) and w.filename == __file__ for w in caught)


# ---- files ---------------------------------------------------------------------------------------

def test_from_files_reads_block_by_block(tmp_path):
    A, B = problem(m=301, n=3, seed=25)
    a, b = save_csv(tmp_path / "A.csv", A), save_csv(tmp_path / "B.csv", B)
    f = spdfit.Factor.from_files(a, str(b), block_rows=37, threads=2)
    assert (f.rows, f.n, f.d) == (301, 3, 3)
    assert rel(f.fit("spde").X, ref.spde(A, B)) < REFERENCE_RTOL
    assert rel(f.fit("spde").X, spdfit.fit(A, B, "spde").X) < MERGE_RTOL
    # Factors of two files merge as factors of data do.
    head = spdfit.Factor.from_files(save_csv(tmp_path / "A2.csv", A[:100]), save_csv(tmp_path / "B2.csv", B[:100]))
    g = head.merge(spdfit.Factor.from_data(A[100:], B[100:]))
    assert rel(g.fit("tls").X, f.fit("tls").X) < MERGE_RTOL


def test_from_files_errors(tmp_path):
    A, B = problem(m=20, n=2, seed=26)
    a, b = save_csv(tmp_path / "A.csv", A), save_csv(tmp_path / "B.csv", B[:19])
    with pytest.raises(spdfit.DataError, match="B.csv"):
        spdfit.Factor.from_files(a, b)
    with pytest.raises(spdfit.DataError, match="missing.csv"):
        spdfit.Factor.from_files(tmp_path / "missing.csv", b)
    with pytest.raises(ValueError, match="block_rows must be at least 1"):
        spdfit.Factor.from_files(a, a, block_rows=0)
    with pytest.raises(TypeError, match="block_rows must be an int, got float"):
        spdfit.Factor.from_files(a, a, block_rows=10.0)
    with pytest.raises(TypeError):
        spdfit.Factor.from_files(1, a)


def test_from_files_warns_of_a_dropped_index_column(tmp_path):
    A, B = problem(m=10, n=2, seed=27)
    (tmp_path / "A.csv").write_text(",x,y\n" + "".join(f"{i},{r[0]!r},{r[1]!r}\n" for i, r in enumerate(A)))
    b = save_csv(tmp_path / "B.csv", B)
    with pytest.warns(spdfit.SpdfitWarning, match="index"):
        f = spdfit.Factor.from_files(tmp_path / "A.csv", b)
    assert f.n == 2 and rel(f.fit("ls").X, np.linalg.lstsq(A, B, rcond=None)[0]) < MERGE_RTOL


# ---- Dask --------------------------------------------------------------------------------------

def dask_tree(A, B, delayed):
    """The docs' recipe: a factor per block of the dask.arrays' rows, merged along a pairwise tree."""
    factors = [delayed(spdfit.Factor.from_data)(a, b)
               for a, b in zip(A.to_delayed().ravel(), B.to_delayed().ravel())]
    while len(factors) > 1:
        factors = [delayed(spdfit.Factor.merge)(*factors[i:i + 2]) if i + 1 < len(factors) else factors[i]
                   for i in range(0, len(factors), 2)]
    return factors[0]


def test_dask_with_the_process_scheduler():
    dask = pytest.importorskip("dask", reason="dask is not installed (Debian: python3-dask)")
    import dask.array as da
    A_np, B_np = problem(m=20_001, n=4, seed=28)
    A = da.from_array(A_np, chunks=(2500, 4))  # 9 blocks, the last of one row: an unbalanced tree
    B = da.from_array(B_np, chunks=(2500, 4))
    tree = dask_tree(A, B, dask.delayed)
    factor, worker = dask.compute(tree, dask.delayed(os.getpid)(), scheduler="processes")
    assert worker != os.getpid()  # the tasks ran in other processes: the factors were pickled
    assert type(factor) is spdfit.Factor and factor.rows == 20_001
    for method in CLOSED_FORM:
        assert rel(factor.fit(method).X, spdfit.fit(A_np, B_np, method).X) < MERGE_RTOL, method
    assert rel(factor.fit("spde").X, ref.spde(A_np, B_np)) < REFERENCE_RTOL
    for method, options in [("spd-tls", {}), ("psd-ls", {"min_eig": PSD_LS_FLOOR}), ("auto", {})]:
        r, r0 = factor.fit(method, **options), spdfit.fit(A_np, B_np, method, **options)
        assert r.method == r0.method and rel(r.X, r0.X) < ITERATIVE_RTOL, method
