"""The structured repairs (nearest_correlation / nearest_covariance / nearest_spd with fixed,
h_weights, rank, factors, min_diag) against independent references: CVXOPT's semidefinite QP for
the convex problems (tests/support/repair_reference.py), local methods written here (Pietersz and
Groenen's majorization, L-BFGS) for the rank, statsmodels' corr_nearest_factor on its own test
matrices, and NAG's published examples (g02aj, g02ak, g02ae). Small sizes only: the 50-problem
comparison and the timings are bench/structured_repair.py's."""
import warnings

import numpy as np
import pytest

import repair_reference as ref
import spdfit

# CVXOPT's interior-point method at tolerance 1e-10 agrees with the exact optimum to about 1e-8
# relative; the goal is 1e-6 relative, with min_eig 0 (the plain semidefinite constraint).
OBJECTIVE_RTOL = 1e-6


def quiet(function, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        return function(*args, **kwargs)


@pytest.fixture(scope="module")
def convex_cases():
    """Random problems (n = 5..12): kept blocks, elementwise weights with zeros, both, each with the
    unit diagonal; one with the diagonal kept and one with it free; CVXOPT's answers."""
    rng = np.random.default_rng(44)
    cases = []
    for k, n in enumerate((5, 6, 8, 9, 10, 12)):
        C = ref.random_problem(rng, n)
        fixed = np.zeros((n, n), bool)
        block = rng.choice(n, size=3, replace=False)
        fixed[np.ix_(block, block)] = True
        # A kept block must itself be semidefinite: take it from a correlation matrix.
        Z = rng.standard_normal((3, 6))
        B = np.corrcoef(Z)
        C[np.ix_(block, block)] = (B + B.T) / 2  # exactly symmetric: the kept entries are C's
        np.fill_diagonal(C, 1.0)
        H = rng.uniform(0.1, 1.0, (n, n))
        H = (H + H.T) / 2
        H[0, n - 1] = H[n - 1, 0] = 0.0  # a pair never observed together
        diagonal = ("unit", "unit", "unit", "kept", "free", "unit")[k]
        if diagonal == "kept":
            d = rng.uniform(0.5, 4.0, n)
            C = C * np.sqrt(np.outer(d, d))
        kind = ("fixed", "h", "both", "fixed", "both", "h")[k]
        cases.append(dict(C=C, fixed=fixed if kind in ("fixed", "both") else None,
                          H=H if kind in ("h", "both") else None, diagonal=diagonal))
    answers = ref.cvxopt_in_subprocess([dict(C=c["C"], H=c["H"], fixed=c["fixed"], diagonal=c["diagonal"])
                                        for c in cases])
    return [dict(case, reference=answer) for case, answer in zip(cases, answers)]


def spdfit_repair(case, **extra):
    options = dict(min_eig=0, full_output=True, **extra)
    if case["fixed"] is not None:
        options["fixed"] = case["fixed"].astype(float)
    if case["H"] is not None:
        options["h_weights"] = case["H"]
    if case["diagonal"] == "unit":
        return quiet(spdfit.nearest_correlation, case["C"], **options)
    if case["diagonal"] == "kept":
        return quiet(spdfit.nearest_covariance, case["C"], **options)
    return quiet(spdfit.nearest_spd, case["C"], **options)


def test_convex_repairs_reach_cvxopts_objective(convex_cases):
    for case in convex_cases:
        r = spdfit_repair(case)
        H = np.ones_like(case["C"]) if case["H"] is None else case["H"]
        ours = np.linalg.norm(H * (r.X - case["C"]))
        theirs = case["reference"][1]
        assert r.distance == pytest.approx(ours, rel=1e-12)
        assert abs(ours - theirs) <= OBJECTIVE_RTOL * theirs, (case["diagonal"], ours, theirs)
        # Admissible: semidefinite to rounding, the diagonal rule, the kept entries bit for bit.
        assert np.linalg.eigvalsh(r.X)[0] >= -1e-10 * np.abs(r.X).max()
        if case["diagonal"] == "unit":
            assert np.all(np.diag(r.X) == 1.0)
        if case["diagonal"] == "kept":
            assert np.array_equal(np.diag(r.X), np.diag(case["C"]))
        if case["fixed"] is not None:
            assert np.array_equal(r.X[case["fixed"]], case["C"][case["fixed"]])
        # The certificate: the dual's lower bound is below the optimum and close to it.
        assert r.lower_bound <= theirs * (1 + 1e-8)
        assert r.distance - r.lower_bound <= 1e-6 * r.distance


def test_h_weights_of_all_ones_is_the_plain_correlation_repair():
    rng = np.random.default_rng(7)
    C = ref.random_problem(rng, 9)
    plain = quiet(spdfit.nearest_correlation, C)
    weighted = quiet(spdfit.nearest_correlation, C, h_weights=np.ones((9, 9)))
    np.testing.assert_allclose(weighted, plain, atol=1e-9)
    # A rank-one H = h h^T is the diagonal weights' problem with w = h^2.
    h = rng.uniform(0.5, 2.0, 9)
    np.testing.assert_allclose(quiet(spdfit.nearest_correlation, C, h_weights=np.outer(h, h)),
                               quiet(spdfit.nearest_correlation, C, weights=h ** 2), atol=1e-9)


def test_the_augmented_lagrangian_meets_its_kkt_conditions():
    rng = np.random.default_rng(8)
    n = 12
    C = ref.random_problem(rng, n)
    H = rng.uniform(0.2, 1.0, (n, n))
    H = (H + H.T) / 2
    r = quiet(spdfit.nearest_correlation, C, h_weights=H, min_eig=0, full_output=True)
    assert r.method.startswith("augmented Lagrangian") and r.converged
    assert r.optimality_residual <= 1e-10
    # KKT of min ||H o (X - C)||^2 / 2 over diag(X) = 1, X >= 0: the gradient Z = H o H o (X - C)
    # is Diag(y) + S with S >= 0 and S X = 0. S X = 0 gives y_i = (Z X)_ii / X_ii = (Z X)_ii.
    Z = H * H * (r.X - C)
    np.fill_diagonal(Z, 0.0)  # diag(X) = diag(C) = 1
    S = Z - np.diag(np.diag(Z @ r.X))
    scale = np.linalg.norm(Z) * np.linalg.norm(r.X)
    assert np.linalg.norm(S @ r.X) <= 1e-7 * scale
    assert np.linalg.eigvalsh(S).min() >= -1e-7 * np.linalg.norm(Z)


def test_nags_g02aj_example():
    # NAG g02aj's published example: G tridiagonal (2, -1), H with zeros (free entries), alpha 0.04;
    # NAG prints ||H o (G - X)||_F = 0.0572 with H scaled to a largest entry of 1 and G's diagonal 1.
    G = np.array([[2.0, -1, 0, 0], [-1, 2, -1, 0], [0, -1, 2, -1], [0, 0, -1, 2]])
    H = np.array([[0.0, 10, 0, 0], [10, 0, 1.5, 1.5], [0, 1.5, 0, 0], [0, 1.5, 0, 0]])
    r = quiet(spdfit.nearest_correlation, G, h_weights=H, alpha=0.04, full_output=True)
    Gu = G.copy()
    np.fill_diagonal(Gu, 1.0)
    ours = np.linalg.norm(H / 10 * (r.X - Gu))
    assert ours <= 0.0572 + 5e-5  # NAG's printed value, to its 4 digits
    assert np.linalg.eigvalsh(r.X)[0] >= 0.04 * (1 - 1e-9)
    assert np.all(np.diag(r.X) == 1.0)


def test_nags_g02ak_example():
    # NAG g02ak: the same G, rank 2; NAG prints "Squared Frobenius norm of difference: 3.082e-01",
    # which is half the squared distance to G with its diagonal set to 1 (its printed X gives
    # 0.3082058); a local optimum: ours may be another, no worse.
    G = np.array([[2.0, -1, 0, 0], [-1, 2, -1, 0], [0, -1, 2, -1], [0, 0, -1, 2]])
    nag = np.array([[1, -0.9021, 0.2448, 0.1975], [-0.9021, 1, -0.6392, 0.2448], [0.2448, -0.6392, 1, -0.9021],
                    [0.1975, 0.2448, -0.9021, 1]])
    r = quiet(spdfit.nearest_correlation, G, rank=2, full_output=True)
    Gu = G.copy()
    np.fill_diagonal(Gu, 1.0)
    assert 0.5 * np.linalg.norm(r.X - Gu) ** 2 <= 0.5 * np.linalg.norm(nag - Gu) ** 2
    assert 0.5 * np.linalg.norm(r.X - Gu) ** 2 <= 0.3082 + 5e-5
    assert np.linalg.matrix_rank(r.X, tol=1e-10) <= 2 and np.all(np.diag(r.X) == 1.0)
    np.testing.assert_allclose(r.F @ r.F.T, r.X, atol=1e-14)


def test_nags_g02ae_example():
    # NAG g02ae: the same G, two factors; ours is no farther from G than NAG's printed X (4 digits).
    G = np.array([[2.0, -1, 0, 0], [-1, 2, -1, 0], [0, -1, 2, -1], [0, 0, -1, 2]])
    nag = np.array([[1.0, -0.8934, 0.2418, 0.1939], [-0.8934, 1.0, -0.6384, 0.2418],
                    [0.2418, -0.6384, 1.0, -0.8934], [0.1939, 0.2418, -0.8934, 1.0]])
    r = quiet(spdfit.nearest_correlation, G, factors=2, full_output=True)
    F = r.F
    X = np.diag(1 - np.sum(F ** 2, axis=1)) + F @ F.T
    np.testing.assert_allclose(X, r.X, atol=1e-14)
    assert np.all(np.sum(F ** 2, axis=1) <= 1 + 1e-12)
    assert np.linalg.norm(r.X - G) <= np.linalg.norm(nag - G) + 4 * 5e-5 * 4


@pytest.mark.parametrize("n, K", [(10, 2), (15, 3)])
def test_rank_is_as_good_as_the_best_local_method(n, K):
    rng = np.random.default_rng(100 + n)
    C = ref.random_problem(rng, n)
    r = quiet(spdfit.nearest_correlation, C, rank=K, full_output=True)
    best = ref.best_local_rank(C, K, random_starts=2, seed=n)
    assert r.distance <= best * (1 + 1e-3), (r.distance, best)
    assert np.linalg.matrix_rank(r.X, tol=1e-10 * n) <= K and np.all(np.diag(r.X) == 1.0)
    # The convex relaxation's distance is a lower bound; every start is reported.
    convex = quiet(spdfit.nearest_correlation, C, min_eig=0, full_output=True).distance
    assert r.lower_bound == pytest.approx(convex, rel=1e-9) and r.lower_bound <= r.distance
    assert len(r.starts) >= 3 and min(s[1] for s in r.starts) == pytest.approx(r.distance, rel=1e-12)
    assert r.optimality_residual <= 1e-6


def test_rank_with_weights_and_with_the_diagonal_kept():
    rng = np.random.default_rng(21)
    n, K = 10, 3
    C = ref.random_problem(rng, n)
    w = rng.uniform(0.5, 2.0, n)
    r = quiet(spdfit.nearest_correlation, C, rank=K, weights=w, full_output=True)
    assert r.distance == pytest.approx(ref.rank_objective(r.F, C, w), rel=1e-10)
    assert r.distance <= ref.best_local_rank(C, K, w, random_starts=1) * (1 + 1e-3)
    d = rng.uniform(0.5, 4.0, n)
    S = C * np.sqrt(np.outer(d, d))
    kept = quiet(spdfit.nearest_covariance, S, rank=K, full_output=True)
    assert np.array_equal(np.diag(kept.X), np.diag(S))
    assert np.linalg.matrix_rank(kept.X, tol=1e-9) <= K


def statsmodels_factor_matrix(d, dm, noise, seed, threshold=None):
    """statsmodels' test_corr_nearest_factor matrices: sinusoidal loadings, rows projected into
    the unit ball, times 0.7, unit diagonal (thresholded for the sparse test)."""
    from statsmodels.stats.correlation_tools import _project_correlation_factors
    X = np.zeros((d, dm))
    x = np.linspace(0, 2 * np.pi, d)
    rs = np.random.RandomState(seed)
    for j in range(dm):
        X[:, j] = np.sin(x * (j + 1)) + noise * rs.randn(d)
    _project_correlation_factors(X)
    X *= 0.7
    mat = X @ X.T
    np.fill_diagonal(mat, 1.0)
    if threshold is not None:
        mat.flat[np.abs(mat.flat) < threshold] = 0.0
    return mat


@pytest.mark.parametrize("dm", [1, 2])
def test_factors_at_most_statsmodels_objective(dm):
    pytest.importorskip("statsmodels")
    from statsmodels.stats.correlation_tools import corr_nearest_factor
    mat = statsmodels_factor_matrix(100, dm, 1e-10, 10)
    theirs = corr_nearest_factor(mat, dm, maxiter=10000).corr.to_matrix()
    r = quiet(spdfit.nearest_correlation, mat, factors=dm, full_output=True)
    assert np.linalg.norm(r.X - mat) <= np.linalg.norm(theirs - mat) * (1 + 1e-9) + 1e-12
    assert r.distance == pytest.approx(np.linalg.norm(r.X - mat), rel=1e-9, abs=1e-12)


def test_factors_only_returns_f_without_x():
    rng = np.random.default_rng(3)
    C = ref.random_problem(rng, 30)
    full = quiet(spdfit.nearest_correlation, C, factors=3, full_output=True)
    only = quiet(spdfit.nearest_correlation, C, factors=3, factors_only=True, full_output=True)
    assert only.X.size == 0 and only.F.shape == (30, 3)
    np.testing.assert_array_equal(only.F, full.F)
    assert only.distance == pytest.approx(full.distance, rel=1e-12)
    F = quiet(spdfit.nearest_correlation, C, factors=3, factors_only=True)
    assert F.shape == (30, 3)


def test_min_diag_raises_bad_variances_and_names_them():
    S = np.array([[4.0, 1.0, 0.5], [1.0, 0.0, 0.2], [0.5, 0.2, -1e-3]])
    with pytest.raises(spdfit.DataError, match=r"diagonal entries 2 \(0\), 3 \(-0\.001\).*min_diag"):
        spdfit.nearest_covariance(S)
    with pytest.raises(spdfit.DataError, match="min_diag"):
        spdfit.nearest_spd(S, via_corr=True)
    with pytest.warns(spdfit.DiagonalChangedWarning, match=r"diagonal entries 2 \(0\), 3 \(-0\.001\) were below min_diag"):
        X = spdfit.nearest_covariance(S, min_diag=1e-4)
    np.testing.assert_array_equal(np.diag(X), [4.0, 1e-4, 1e-4])
    assert np.linalg.eigvalsh(X)[0] > 0


@pytest.mark.parametrize("kwargs, message", [
    (dict(fixed=-np.eye(4)), "has -1 at"),
    (dict(fixed=np.triu(np.ones((4, 4)))), "not symmetric"),
    (dict(fixed=np.zeros((4, 4))), "all zero"),
    (dict(fixed=np.ones((3, 3))), "give an 4x4 mask"),
    (dict(fixed=np.array([[0, 4]])), "indices are integers from 0 to 3"),
    (dict(h_weights=-np.ones((4, 4))), "must be finite and >= 0"),
    (dict(h_weights=np.triu(np.ones((4, 4)))), "not symmetric"),
    (dict(h_weights=np.zeros((4, 4))), "all zero"),
    (dict(h_weights=np.eye(4)), "zero on every entry the repair may change"),
    (dict(rank=5), "rank is 5, but the matrix is 4x4"),
    (dict(factors=7), "factors is 7, but the matrix is 4x4"),
])
def test_bad_masks_weights_and_ranks_are_clear_errors(kwargs, message):
    C = np.array([[1.0, 0.9, 0.2, 0.1], [0.9, 1.0, 0.9, 0.1], [0.2, 0.9, 1.0, 0.5], [0.1, 0.1, 0.5, 1.0]])
    # Data errors (their code's class), not usage errors: the data's size decides.
    with pytest.raises(spdfit.DataError, match=message):
        spdfit.nearest_correlation(C, **kwargs)


def test_rank_zero_and_bad_combinations_are_usage_errors():
    C = np.eye(3)
    with pytest.raises(ValueError) as info:
        spdfit.nearest_correlation(C, rank=1, fixed=np.eye(3))
    assert not isinstance(info.value, spdfit.DataError)
    with pytest.raises(ValueError, match=r"rank must be an integer in \[1"):
        spdfit.nearest_correlation(C, rank=0)
    with pytest.raises(ValueError, match="give fixed or rank, not both"):
        spdfit.nearest_correlation(C, rank=1, fixed=np.eye(3))
    with pytest.raises(ValueError, match="give h_weights or factors, not both"):
        spdfit.nearest_correlation(C, factors=1, h_weights=np.ones((3, 3)))
    with pytest.raises(ValueError, match="give rank or factors, not both|give factors or rank"):
        spdfit.nearest_correlation(C, factors=1, rank=1)
    with pytest.raises(ValueError, match="factors_only needs factors"):
        spdfit.nearest_correlation(C, factors_only=True)
    with pytest.raises(TypeError, match="unexpected keyword argument 'factors'"):
        spdfit.nearest_covariance(C, factors=1)


def test_infeasible_kept_entries_say_which():
    C = np.array([[1.0, 0.9, 0.9, 0.0], [0.9, 1.0, -0.9, 0.0], [0.9, -0.9, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
    block = np.zeros((4, 4))
    block[:3, :3] = 1
    with pytest.raises(spdfit.DataError, match=r"block of kept entries in rows and columns 1, 2, 3 is not positive "
                                         r"semidefinite"):
        spdfit.nearest_correlation(C, fixed=block)
    C2 = C.copy()
    C2[0, 3] = C2[3, 0] = 1.5
    with pytest.raises(spdfit.DataError, match=r"kept entry \(4, 1\) = 1.5 is larger in magnitude"):
        spdfit.nearest_correlation(C2, fixed=[[0, 3]])
    # Each kept pair is fine and no block is fully kept, but the 4-cycle 1-2-3-4 with correlations
    # 0.9, 0.9, 0.9, -0.9 has no completion (its angles break the cycle condition of Barrett,
    # Johnson & Tarazaga): the dual iteration proves it.
    C3 = np.eye(4)
    for (i, j), c in zip([(0, 1), (1, 2), (2, 3), (3, 0)], [0.9, 0.9, 0.9, -0.9]):
        C3[i, j] = C3[j, i] = c
    with pytest.raises(spdfit.DataError, match="no positive semidefinite matrix with the kept diagonal"):
        spdfit.nearest_correlation(C3, fixed=[[0, 1], [1, 2], [2, 3], [3, 0]])


def test_matrix_options_take_a_files_path(tmp_path):
    # fixed and h_weights as files, read by the command's workflow as the command line reads them:
    # the same answer as the arrays (pairs in a file count from 1, as on the command line).
    C = np.array([[1.0, 0.9, 0.2, 0.1], [0.9, 1.0, 0.9, 0.1], [0.2, 0.9, 1.0, 0.5], [0.1, 0.1, 0.5, 1.0]])
    mask = np.zeros((4, 4))
    mask[0, 1] = mask[1, 0] = 1
    H = np.full((4, 4), 0.5)
    H[2, 3] = H[3, 2] = 3.0
    np.savetxt(tmp_path / "mask.csv", mask, delimiter=",")
    np.savetxt(tmp_path / "H.csv", H, delimiter=",")
    by_file = quiet(spdfit.nearest_correlation, C, fixed=str(tmp_path / "mask.csv"), h_weights=tmp_path / "H.csv")
    by_array = quiet(spdfit.nearest_correlation, C, fixed=mask, h_weights=H)
    np.testing.assert_array_equal(by_file, by_array)
    np.savetxt(tmp_path / "pairs.csv", [[1, 2]], delimiter=",", fmt="%d")
    by_pairs = quiet(spdfit.nearest_correlation, C, fixed=str(tmp_path / "pairs.csv"), h_weights=H)
    np.testing.assert_array_equal(by_pairs, quiet(spdfit.nearest_correlation, C, fixed=[[0, 1]], h_weights=H))
    np.savetxt(tmp_path / "bad.csv", -np.ones((4, 4)), delimiter=",")
    with pytest.raises(spdfit.DataError, match="bad.csv"):
        spdfit.nearest_correlation(C, h_weights=str(tmp_path / "bad.csv"))


def test_fixed_with_h_weights_and_a_zero_floor_reaches_the_cvxopt_optimum():
    """Problem 35 of bench/structured_repair.py's seed, where the augmented Lagrangian used to stall at
    an infeasible X (its iterate drifted off symmetric on the entries of weight 0): the reference
    objective is CVXOPT's cone QP with the same constraints (unit diagonal, entries (1,1), (1,6), (6,6)
    kept, X >= 0)."""
    C = np.array([
        [1.0, 0.45422663917015604, -1.1241310520739984, -0.19428481139400772, -0.22699088221709335, 0.9779762941801782],
        [0.45422663917015604, 1.0, -0.4296781540738028, -0.2528361214765371, -0.19119619959361817, 0.790805770082689],
        [-1.1241310520739984, -0.4296781540738028, 1.0, 0.5810749433086858, 0.6540600265601147, -0.7998968379292806],
        [-0.19428481139400772, -0.2528361214765371, 0.5810749433086858, 1.0, 0.08276368731473949, -0.3730481941327336],
        [-0.22699088221709335, -0.19119619959361817, 0.6540600265601147, 0.08276368731473949, 1.0, -0.8408156283700251],
        [0.9779762941801782, 0.790805770082689, -0.7998968379292806, -0.3730481941327336, -0.8408156283700251, 1.0]])
    H = np.array([
        [0.9369316057526464, 0.0, 0.4460652981894691, 0.31627758646434584, 0.4289095862181322, 0.37341360636532733],
        [0.0, 0.6775818608904968, 0.683537050237154, 0.8280170775347289, 0.3110416112556424, 0.5893972840107415],
        [0.4460652981894691, 0.683537050237154, 0.3834688006656396, 0.6333447628452882, 0.46217712560512514,
         0.7014823023735566],
        [0.31627758646434584, 0.8280170775347289, 0.6333447628452882, 0.9798205493800843, 0.0, 0.47145366036318437],
        [0.4289095862181322, 0.3110416112556424, 0.46217712560512514, 0.0, 0.7553372447998046, 0.9230624882239031],
        [0.37341360636532733, 0.5893972840107415, 0.7014823023735566, 0.47145366036318437, 0.9230624882239031, 0.0]])
    fixed = np.zeros((6, 6))
    fixed[np.ix_([0, 5], [0, 5])] = 1.0
    with warnings.catch_warnings():
        warnings.simplefilter("error", spdfit.NotConvergedWarning)
        X = spdfit.nearest_correlation(C, min_eig=0, fixed=fixed, h_weights=H)
    assert np.linalg.eigvalsh(X)[0] >= -1e-8  # the solver's tolerance, after the kept entries are set exactly
    assert np.linalg.norm(H * (X - C)) <= 0.31763513263019827 * (1 + 1e-6)


def _kept_block_problem(floor):
    """A 60 x 60 indefinite correlation-like matrix whose first 20 rows form a kept block, repaired
    with eigenvalue floor `floor` (0: singular, as nearest_correlation leaves it), and 5 % of the
    other pairs kept too."""
    rng = np.random.default_rng(2)
    n, k = 60, 20
    C = np.corrcoef(rng.standard_normal((n, n // 2)))
    A = rng.standard_normal((n, n))
    C = (C + C.T) / 2 + 0.2 * (A + A.T) / 2
    np.fill_diagonal(C, 1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        C[:k, :k] = spdfit.nearest_correlation(C[:k, :k], min_eig=floor)
    fixed = np.zeros((n, n))
    fixed[:k, :k] = 1.0
    extra = rng.uniform(size=(n, n)) < 0.05
    fixed[extra | extra.T] = 1.0
    return C, fixed, k


def test_a_singular_kept_block_is_named_when_newton_stalls():
    """A kept block with zero eigenvalues makes every completion singular: the dual has no minimizer
    and the multipliers diverge. The warning says so and names rows of the block."""
    C, fixed, k = _kept_block_problem(0.0)
    assert np.linalg.eigvalsh(C[:k, :k])[0] < 1e-12
    with pytest.warns(spdfit.NotConvergedWarning, match="singular") as caught:
        X = spdfit.nearest_correlation(C, fixed=fixed, min_eig=0, max_iter=60)
    message = str(caught[-1].message)
    rows = [int(r) for r in message.split("largest in rows ")[1].split(")")[0].replace(" ", "").split(",")]
    assert rows and all(1 <= r <= k for r in rows), message
    assert np.all(X[fixed > 0] == C[fixed > 0])


def test_a_positive_definite_kept_block_converges_to_a_kkt_point():
    """The same problem with the block repaired with a floor converges, to a KKT point of
    min ||X - C||_F^2 / 2 over X >= 0 with the kept entries: X - C = Z on the free entries for a
    multiplier Z = N S N^T >= 0 (N: X's null space, S >= 0), fitted by least squares. (CVXOPT's
    answer to the same problem is 7e-6 from it, and its residual in this test 7.7e-6.)"""
    C, fixed, k = _kept_block_problem(1e-3)
    with warnings.catch_warnings():
        warnings.simplefilter("error", spdfit.NotConvergedWarning)
        X = spdfit.nearest_correlation(C, fixed=fixed, min_eig=0)
    assert np.all(X[fixed > 0] == C[fixed > 0])
    w, V = np.linalg.eigh(X)
    assert w[0] >= -1e-8
    N = V[:, w < 1e-7 * w[-1]]
    z = N.shape[1]
    assert z > 0  # the input is indefinite: the answer is on the boundary
    free = np.tril(fixed == 0, -1)  # the diagonal is kept too
    pairs = [(a, b) for a in range(z) for b in range(a, z)]
    basis = np.array([((np.outer(N[:, a], N[:, b]) + np.outer(N[:, b], N[:, a])) / (2.0 if a == b else 1.0))[free]
                      for a, b in pairs]).T
    target = (X - C)[free]
    coefficients, *_ = np.linalg.lstsq(basis, target, rcond=None)
    assert np.linalg.norm(basis @ coefficients - target) <= 1e-7 * np.linalg.norm(target)  # measured 1.8e-10
    S = np.zeros((z, z))
    for (a, b), c in zip(pairs, coefficients):
        S[a, b] = S[b, a] = c
    assert np.linalg.eigvalsh(S)[0] >= -1e-6 * np.abs(S).max()
