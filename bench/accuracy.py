"""Accuracy on hard inputs: spdfit against the thesis' Gram-matrix algorithms (appendix B,
as implemented independently in tests/reference/thesis_reference.py).

For each condition number of A, noise-free data B = A X0 (X0 SPD, cond 10; m = 12, n = 6,
graded and ungraded A) are fitted by every method; the table shows the worst relative error
||X - X0||_F / ||X0||_F over the trials, and how many estimates of `spde`/`procrustes` came
out not symmetric positive definite (complex or indefinite).

    /usr/bin/python3 bench/accuracy.py build/apps/spdfit [--trials 20]
"""
import argparse
import json
import pathlib
import subprocess
import sys
import tempfile
import warnings

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests" / "reference"))
import thesis_reference as ref  # noqa: E402

METHODS = {"ls": ref.least_squares, "procrustes": ref.procrustes, "tls": ref.tls, "spde": ref.spde}


def problem(rng, cond, graded):
    m, n = 12, 6
    s = np.logspace(0, -np.log10(cond), n)
    if graded:
        A = rng.standard_normal((m, n)) * s
    else:
        U, _ = np.linalg.qr(rng.standard_normal((m, n)))
        V, _ = np.linalg.qr(rng.standard_normal((n, n)))
        A = U @ np.diag(s) @ V.T
    W, _ = np.linalg.qr(rng.standard_normal((n, n)))
    X0 = W @ np.diag(np.logspace(0, 1, n)) @ W.T
    X0 = (X0 + X0.T) / 2
    return A, A @ X0, X0


def spdfit_fit(cli, method, A, B, tmp):
    np.savetxt(tmp / "A.csv", A, delimiter=",", fmt="%.17g")
    np.savetxt(tmp / "B.csv", B, delimiter=",", fmt="%.17g")
    out = subprocess.run([cli, "-q", "fit", "--method", method, "--json", tmp / "A.csv", tmp / "B.csv"],
                         capture_output=True, text=True)
    if out.returncode != 0:
        return None
    return np.array(json.loads(out.stdout)["X"])


def is_spd(X, exact_symmetry):
    """Real, finite, symmetric (exactly, or to rounding for the reference) and positive definite."""
    if X is None or np.iscomplexobj(X) or not np.all(np.isfinite(X)):
        return False
    if exact_symmetry and not np.array_equal(X, X.T):
        return False
    if not np.allclose(X, X.T, rtol=1e-12, atol=0):
        return False
    return np.linalg.eigvalsh((X + X.T) / 2)[0] > 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("cli")
    parser.add_argument("--trials", type=int, default=20)
    args = parser.parse_args()
    rng = np.random.default_rng(2026)
    print(f"{'cond(A)':>8} {'method':>11} {'spdfit max err':>15} {'Gram (thesis) max err':>22}"
          f" {'non-SPD spdfit/Gram':>20}")
    with tempfile.TemporaryDirectory() as d:
        tmp = pathlib.Path(d)
        for cond in [1e2, 1e4, 1e6, 1e8]:
            for method, reference in METHODS.items():
                ours, theirs, bad_ours, bad_theirs = [], [], 0, 0
                for trial in range(args.trials):
                    A, B, X0 = problem(rng, cond, graded=trial % 2 == 0)
                    X = spdfit_fit(args.cli, method, A, B, tmp)
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        try:
                            Y = reference(A, B)
                        except Exception:  # the Gram path can fail outright (e.g. eig not converging)
                            Y = np.full_like(X0, np.nan)
                    ours.append(np.inf if X is None else np.linalg.norm(X - X0) / np.linalg.norm(X0))
                    err = np.linalg.norm(Y - X0) / np.linalg.norm(X0)
                    theirs.append(err if np.isfinite(err) else np.inf)
                    if method in ("procrustes", "spde"):
                        bad_ours += not is_spd(X, exact_symmetry=True)
                        bad_theirs += not is_spd(Y, exact_symmetry=False)
                spd = f"{bad_ours}/{bad_theirs}" if method in ("procrustes", "spde") else "-"
                print(f"{cond:8.0e} {method:>11} {max(ours):15.2e} {max(theirs):22.2e} {spd:>20}")


if __name__ == "__main__":
    main()
