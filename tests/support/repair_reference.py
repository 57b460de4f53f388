"""Independent references for the structured repairs (spdfit nearest --fixed, --h-weights,
--rank, --factors), written here from their definitions with NumPy, SciPy and CVXOPT, never with
spdfit's code:

- cvxopt_nearest: the convex problems (kept entries, elementwise weights, a fixed diagonal) as a
  cone quadratic program with a semidefinite cone, solved by CVXOPT's interior-point coneqp;
- the rank problem's local methods: Pietersz and Groenen's majorization (2004) and L-BFGS on
  the normalized-rows parametrization (SciPy), each from modified PCA and from random starts;
- random test problems: indefinite symmetric matrices with a unit diagonal.

CVXOPT (python3-cvxopt) is a test-only dependency.
"""
import numpy as np


def random_problem(rng, n, noise=0.5):
    """A symmetric, indefinite matrix with unit diagonal: a correlation matrix of a few factors plus
    symmetric uniform noise (as pairwise-deleted estimates are)."""
    k = max(1, n // 4)
    F = rng.standard_normal((n, k))
    S = F @ F.T + np.diag(rng.uniform(0.2, 1.0, n))
    d = np.sqrt(np.diag(S))
    C = S / np.outer(d, d)
    E = rng.uniform(-noise, noise, (n, n))
    C = C + (E + E.T) / 2
    C = (C + C.T) / 2  # exactly symmetric (F F^T from the BLAS need not be)
    np.fill_diagonal(C, 1.0)
    return C


def cvxopt_nearest(C, H=None, fixed=None, diagonal="free", floor=0.0, tolerance=1e-10):
    """min sum_ij H_ij^2 (X_ij - C_ij)^2 over symmetric X >= floor I with X_ij = C_ij where `fixed`
    (a symmetric boolean mask) and the diagonal 1 ("unit"), C's ("kept") or free ("free"), by CVXOPT's
    coneqp. Returns (X, ||H o (X - C)||_F)."""
    from cvxopt import matrix, solvers, spmatrix

    n = C.shape[0]
    C = (C + C.T) / 2
    H = np.ones((n, n)) if H is None else np.asarray(H, dtype=float)
    fixed = np.zeros((n, n), dtype=bool) if fixed is None else np.asarray(fixed, dtype=bool).copy()
    target = C.copy()
    if diagonal == "unit":
        np.fill_diagonal(target, 1.0)
    if diagonal in ("unit", "kept"):
        np.fill_diagonal(fixed, True)
    # Variables: the lower triangle of X, column by column.
    pairs = [(i, j) for j in range(n) for i in range(j, n)]
    m = len(pairs)
    index = {p: k for k, p in enumerate(pairs)}
    # Objective 1/2 x^T P x + q^T x: each off-diagonal variable counts twice.
    weight = np.array([(1.0 if i == j else 2.0) * H[i, j] ** 2 for i, j in pairs])
    P = spmatrix(weight.tolist(), range(m), range(m))
    q = matrix((-weight * np.array([C[i, j] for i, j in pairs])).tolist())
    # G x + s = h, s in the cone of semidefinite n x n matrices (column-major): s = X - floor I.
    rows, cols, values = [], [], []
    for (i, j), k in index.items():
        rows.append(i + j * n)
        cols.append(k)
        values.append(-1.0)
        if i != j:
            rows.append(j + i * n)
            cols.append(k)
            values.append(-1.0)
    G = spmatrix(values, rows, cols, (n * n, m))
    h = matrix((-floor * np.eye(n)).reshape(-1, order="F").tolist())
    kept = [index[(i, j)] for (i, j) in pairs if fixed[i, j]]
    options = {"show_progress": False, "abstol": tolerance, "reltol": tolerance, "feastol": tolerance,
               "maxiters": 200}
    if kept:
        A = spmatrix([1.0] * len(kept), range(len(kept)), kept, (len(kept), m))
        b = matrix([target[pairs[k]] for k in kept])
        solution = solvers.coneqp(P, q, G, h, {"l": 0, "q": [], "s": [n]}, A, b, options=options)
    else:
        solution = solvers.coneqp(P, q, G, h, {"l": 0, "q": [], "s": [n]}, options=options)
    x = np.array(solution["x"]).ravel()
    X = np.zeros((n, n))
    for (i, j), k in index.items():
        X[i, j] = X[j, i] = x[k]
    return X, float(np.linalg.norm(H * (X - C)))


def modified_pca(C, K):
    """Flury's modified principal components: the K leading eigenvectors scaled by the roots of
    their eigenvalues, rows normalized."""
    lam, V = np.linalg.eigh((C + C.T) / 2)
    Y = V[:, ::-1][:, :K] * np.sqrt(np.maximum(lam[::-1][:K], 0.0))
    return normalized(Y)


def normalized(Y):
    norms = np.linalg.norm(Y, axis=1, keepdims=True)
    Y = Y / np.where(norms > 0, norms, 1.0)
    Y[norms[:, 0] == 0, 0] = 1.0
    return Y


def rank_objective(Y, C, w=None):
    """||W^1/2 (Y Y^T - C) W^1/2||_F for unit rows of Y."""
    n = C.shape[0]
    w = np.ones(n) if w is None else w
    R = Y @ Y.T - (C + C.T) / 2
    return float(np.linalg.norm(np.sqrt(np.outer(w, w)) * R))


def majorization(C, Y, w=None, sweeps=5000, tol=1e-13):
    """Pietersz & Groenen's (2004) majorization for the weighted rank-K correlation problem, row by
    row: y_i := z / ||z|| with z = (lambda_i I - B_i) y_i + b_i, B_i = sum_j w_ij y_j y_j^T,
    b_i = sum_j w_ij c_ij y_j, lambda_i the largest eigenvalue of B_i."""
    n = C.shape[0]
    w = np.ones(n) if w is None else w
    Wt = np.outer(w, w)
    np.fill_diagonal(Wt, 0.0)
    C = (C + C.T) / 2
    Y = normalized(Y.copy())
    previous = rank_objective(Y, C, w)
    for _ in range(sweeps):
        for i in range(n):
            B = (Y * Wt[i][:, None]).T @ Y
            b = (Wt[i] * C[i]) @ Y
            lam = np.linalg.eigvalsh(B)[-1]
            z = lam * Y[i] - B @ Y[i] + b
            norm = np.linalg.norm(z)
            if norm > 0:
                Y[i] = z / norm
        current = rank_objective(Y, C, w)
        if previous - current <= tol * max(previous, 1.0):
            break
        previous = current
    return Y


def lbfgs_rank(C, Y, w=None):
    """L-BFGS (SciPy) on f(Z) = ||W^1/2 (N(Z) N(Z)^T - C) W^1/2||_F^2 with N normalizing the rows."""
    from scipy.optimize import minimize

    n, K = Y.shape
    w = np.ones(n) if w is None else w
    Wt = np.outer(w, w)
    Cs = (C + C.T) / 2

    def f(z):
        Z = z.reshape(n, K)
        norms = np.linalg.norm(Z, axis=1, keepdims=True)
        Yn = Z / norms
        R = Wt * (Yn @ Yn.T - Cs)
        np.fill_diagonal(R, 0.0)
        gY = 4.0 * R @ Yn
        # Through the normalization: (I - y y^T) g / ||z||.
        gZ = (gY - np.sum(gY * Yn, axis=1, keepdims=True) * Yn) / norms
        return float(np.sum(R * (Yn @ Yn.T - Cs))), gZ.ravel()

    result = minimize(f, Y.ravel(), jac=True, method="L-BFGS-B",
                      options={"maxiter": 20000, "ftol": 1e-15, "gtol": 1e-12})
    return normalized(result.x.reshape(n, K))


def best_local_rank(C, K, w=None, random_starts=3, seed=0):
    """The best objective of the local methods from modified PCA and from random starts."""
    rng = np.random.default_rng(seed)
    starts = [modified_pca(C, K)] + [normalized(rng.standard_normal((C.shape[0], K))) for _ in range(random_starts)]
    best = np.inf
    for Y0 in starts:
        for method in (majorization, lbfgs_rank):
            best = min(best, rank_objective(method(C, Y0, w), C, w))
    return best


def cvxopt_in_subprocess(problems):
    """cvxopt_nearest of each problem (a dict of its keyword arguments with "C"), in a child
    process with single-threaded OpenBLAS: CVXOPT's many small BLAS calls run ten to a hundred
    times slower with OpenBLAS's threads on a machine whose cores are busy. Returns [(X, distance)]."""
    import json
    import os
    import pathlib
    import subprocess
    import sys
    import tempfile

    with tempfile.TemporaryDirectory() as work:
        path = pathlib.Path(work) / "problems.json"
        path.write_text(json.dumps([{k: (np.asarray(v).tolist() if k in ("C", "H", "fixed") and v is not None else v)
                                     for k, v in p.items()} for p in problems]))
        env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
        done = subprocess.run([sys.executable, __file__, str(path)], env=env, capture_output=True, text=True,
                              check=True)
        return [(np.array(X), d) for X, d in json.loads(done.stdout)]


if __name__ == "__main__":
    import json
    import sys

    answers = []
    for problem in json.loads(open(sys.argv[1]).read()):
        C = np.array(problem.pop("C"))
        for key in ("H", "fixed"):
            if problem.get(key) is not None:
                problem[key] = np.array(problem[key])
        X, distance = cvxopt_nearest(C, **problem)
        answers.append([X.tolist(), distance])
    print(json.dumps(answers))
