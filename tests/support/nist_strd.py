"""NIST's Statistical Reference Datasets for linear regression (tests/data/nist_strd/): reading a
set, its design matrix, and the LRE by which the StRD assessments (McCullough 1998) score a
program's coefficients. Shared by the accuracy tests and bench/nist_accuracy.py."""
import json
import pathlib

import numpy as np

DATA = pathlib.Path(__file__).resolve().parents[1] / "data" / "nist_strd"

# In NIST's order of difficulty.
DATA_SETS = ("Norris", "Pontius", "NoInt1", "NoInt2", "Filippelli", "Longley",
             "Wampler1", "Wampler2", "Wampler3", "Wampler4", "Wampler5")

# The LRE of an exact match: 15 digits is all the certified values carry.
LRE_CAP = 15.0


def read_set(name):
    """The set's data and certified values: a dict with y, x (observations x predictors), beta
    (the certified coefficients, NumPy floats), the model and NIST's difficulty."""
    certified = json.loads((DATA / "certified.json").read_text())[name]
    table = np.loadtxt(DATA / (name + ".csv"), delimiter=",", skiprows=1, ndmin=2)
    out = dict(certified)
    out["y"] = table[:, 0]
    out["x"] = table[:, 1:]
    out["beta"] = np.array([float(b) for b in certified["beta"]])
    return out


def design(data):
    """The design matrix in double precision: ones for an intercept, then x, x^2, ..., x^degree
    for a polynomial model, or the predictors themselves (Longley)."""
    x = data["x"]
    columns = [np.ones(len(x))] if data["intercept"] else []
    if data["model"] == "polynomial":
        # Repeated multiplication, not x ** k: NumPy's power is not correctly rounded
        # (13.0 ** 4 gives 28560.999999999996), and for integer x (Wampler) products are exact.
        power = np.ones(len(x))
        for _ in range(data["degree"]):
            power = power * x[:, 0]
            columns.append(power)
    else:
        columns += [x[:, j] for j in range(x.shape[1])]
    return np.column_stack(columns)


def lre(estimate, certified):
    """-log10 of the relative error of each coefficient (of the absolute error where the certified
    value is 0), the minimum over the coefficients, capped at LRE_CAP; 0 for a NaN estimate."""
    estimate = np.asarray(estimate, dtype=float)
    if estimate.shape != certified.shape or not np.all(np.isfinite(estimate)):
        return 0.0
    worst = LRE_CAP
    for b, c in zip(estimate, certified):
        error = abs(b - c) / abs(c) if c != 0 else abs(b - c)
        worst = min(worst, LRE_CAP if error == 0 else max(0.0, -np.log10(error)))
    return worst
