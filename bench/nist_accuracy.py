"""Accuracy on NIST's Statistical Reference Datasets for linear regression (StRD; data and
certified values in tests/data/nist_strd/): the LRE (log relative error, -log10 of the relative
error of each certified coefficient, the minimum over the coefficients; capped at 15) that
`spdfit solve` reaches with its default settings, side by side with numpy.linalg.lstsq (its
default rcond) and, when Rscript is installed, R's lm() (its default tol = 1e-7) on the same
design matrices.

    /usr/bin/python3 bench/nist_accuracy.py build/apps/spdfit [--markdown]

The design matrix is built in double precision from the data as printed by NIST: a column of
ones when the model has an intercept, then x, x^2, ... (Longley: x1..x6).
"""
import argparse
import datetime
import json
import pathlib
import shutil
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests" / "support"))
from nist_strd import DATA_SETS, design, lre, read_set  # noqa: E402
from machine import cpu_model  # noqa: E402


def spdfit_solve(cli, X, y, workdir):
    a = workdir / "A.csv"
    b = workdir / "b.csv"
    np.savetxt(a, X, delimiter=",", fmt="%.17g")
    np.savetxt(b, y.reshape(-1, 1), delimiter=",", fmt="%.17g")
    out = subprocess.run([cli, "solve", "--json", str(a), str(b)], capture_output=True, text=True, check=True)
    result = json.loads(out.stdout)
    return np.array(result["solution"], dtype=float), result


def r_lm(X, y, workdir):
    """R's lm() on the same design (its QR with tol = 1e-7): coefficients, NaN where lm drops a
    column as collinear. None when Rscript is not installed."""
    if not shutil.which("Rscript"):
        return None
    path = workdir / "xy.csv"
    np.savetxt(path, np.column_stack([y, X]), delimiter=",", fmt="%.17g")
    script = ("d <- as.matrix(read.csv('%s', header = FALSE)); y <- d[, 1]; X <- d[, -1, drop = FALSE]; "
              "b <- coef(lm(y ~ X - 1)); cat(format(b, digits = 17), sep = '\\n')" % path)
    out = subprocess.run(["Rscript", "-e", script], capture_output=True, text=True, check=True)
    return np.array([float(v) if v.strip() != "NA" else np.nan for v in out.stdout.split()])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("cli", help="the spdfit executable")
    parser.add_argument("--markdown", action="store_true", help="print a Markdown table with the run's header")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(tmp)
        for name in DATA_SETS:
            data = read_set(name)
            X, y, certified = design(data), data["y"], data["beta"]
            x_spdfit, result = spdfit_solve(args.cli, X, y, work)
            x_numpy = np.linalg.lstsq(X, y, rcond=None)[0]
            x_r = r_lm(X, y, work)
            rows.append((name, data["difficulty"], lre(x_spdfit, certified), lre(x_numpy, certified),
                         None if x_r is None else lre(x_r, certified), result["rank"], X.shape[1],
                         result["condition_number"], result.get("scaled_condition_number", float("nan"))))
    has_r = any(r[4] is not None for r in rows)
    if args.markdown:
        print("# NIST StRD linear regression: LRE of the certified coefficients\n")
        print("Command: `/usr/bin/python3 bench/nist_accuracy.py %s --markdown`  " % args.cli)
        print("CPU: %s  " % cpu_model())
        print("Date: %s\n" % datetime.date.today().isoformat())
        header = "| data set | difficulty | spdfit `solve` | `numpy.linalg.lstsq` |"
        header += " R `lm` |" if has_r else ""
        header += " spdfit rank | cond(A) | cond(A D), unit-norm columns |"
        print(header)
        print("|" + "---|" * (header.count("|") - 1))
        for name, difficulty, s, n, r, rank, cols, cond, scaled in rows:
            line = "| %s | %s | %.1f | %.1f |" % (name, difficulty, s, n)
            line += (" %.1f |" % r if r is not None else " - |") if has_r else ""
            line += " %d of %d | %.1e | %.1e |" % (rank, cols, cond, scaled)
            print(line)
    else:
        print("%-11s %-8s %7s %7s %7s %5s %10s %10s" % ("data set", "level", "spdfit", "numpy", "R lm", "rank",
                                                        "cond(A)", "cond(AD)"))
        for name, difficulty, s, n, r, rank, cols, cond, scaled in rows:
            print("%-11s %-8s %7.1f %7.1f %7s %2d/%-2d %10.1e %10.1e" % (
                name, difficulty, s, n, "-" if r is None else "%.1f" % r, rank, cols, cond, scaled))


if __name__ == "__main__":
    main()
