"""Regenerates the example data sets in examples/ (run with Debian's /usr/bin/python3).

The files are committed; this script documents exactly how they were made:
  hexapod/    (A.csv, B.csv, truth.csv; log.mat holds A and B as the MATLAB variables accel and
              force, log.csv as one logger's file with a timestamp column) the thesis' appendix-B generator (000, chapter 6, experiment 2 set-up: m = 12
              samples of n = 6 strut accelerations uniform on [-5, 5], uniform noise with
              nm = 3.2, i.e. variance 0.86, in accelerations A and forces B = A M_p)
  paper_2x2/  the paper's second example (001, section IV): X = [3 1; 1 1], A0 4x2,
              Gaussian noise of std 1.5 in A and 1 in B
  covariance/ C.csv: a correlation matrix estimated from incomplete data (pairwise deletion),
              which is indefinite: repair it with `spdfit nearest --corr`; S.csv: the same
              sensors' covariance in their own units (standard deviations 1e-4 to 2e-3):
              `spdfit nearest` or `spdfit nearest --keep-diag`; S_named.csv: S.csv as pandas'
              df.cov().to_csv() writes it, with the sensors' names (`spdfit nearest --header`)
  load_cell/  a non-square X: m = 20 loads (Fx, Fy, Fz in N) applied to a load cell, measured by
              a reference cell with noise of std 0.5 N, and the cell's 4 strain-gauge readings
              (mV, noise of std 0.05 mV); readings = loads X with X 3 x 4, which `spdfit fit
              --method ls` or `--method tls` estimates
  logged/     log.csv: one hexapod log with a time column, 300 rows at rest then 700 moving, forces
              in kN, untared, one spike (`spdfit fit --time-col t --rest-rows :0.599 --scale-b 1000
              --offsets rest ...`)
"""
import os
import pathlib
import sys

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent

# Thesis eq. (6.1), the UW hexapod's joint-space mass-inertia matrix, from its one home in the
# independent reference (tests/reference/thesis_reference.py).
# (SPDFIT_SOURCE_DIR names the source tree when this script runs from a copy of examples/.)
sys.path.insert(0, str(pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", HERE.parent)) / "tests" / "reference"))
from thesis_reference import MP_THESIS as M_P  # noqa: E402


def save(path, matrix, comment, column_names=None):
    """CSV with a '#' comment line and, optionally, a header row of column names."""
    path.parent.mkdir(parents=True, exist_ok=True)
    header = f"# {comment}" + (f"\n{','.join(column_names)}" if column_names else "")
    np.savetxt(path, matrix, delimiter=",", fmt="%.17g", header=header, comments="")


def hexapod(rng):
    m, n, nm = 12, 6, 3.2
    accelerations = 10.0 * (rng.random((m, n)) - 0.5)
    A = accelerations + nm * (rng.random((m, n)) - 0.5)
    B = accelerations @ M_P + nm * (rng.random((m, n)) - 0.5)
    names = [f"strut{i + 1}" for i in range(n)]
    save(HERE / "hexapod/A.csv", A, "payload accelerations along the struts (m/s^2)", names)
    save(HERE / "hexapod/B.csv", B, "base forces along the struts (N)", names)
    save(HERE / "hexapod/truth.csv", M_P, "true joint-space mass-inertia matrix M_p, thesis eq. 6.1 (kg)")
    # The same log as a data logger writes it: one file with a timestamp, then A's and B's columns
    # (`spdfit fit --a-cols acc1:acc6 --b-cols F1:F6`).
    with open(HERE / "hexapod/log.csv", "w") as out:
        out.write("# hexapod log: time, payload accelerations (m/s^2), base forces (N)\n")
        out.write(",".join(["time"] + [f"acc{i + 1}" for i in range(n)] + [f"F{i + 1}" for i in range(n)]) + "\n")
        for k in range(m):
            stamp = f"2026-11-27T10:00:{k / 100:05.2f}"
            out.write(",".join([stamp] + ["%.17g" % v for v in np.concatenate([A[k], B[k]])]) + "\n")
    # The same log as MATLAB keeps it: one .mat file with named variables (scipy writes level 5).
    import scipy.io
    scipy.io.savemat(HERE / "hexapod/log.mat", {"accel": A, "force": B, "note": "hexapod log, thesis set-up"})


def paper_2x2(rng):
    X = np.array([[3.0, 1.0], [1.0, 1.0]])
    A0 = np.array([[5.0, 2.0], [-3.0, 1.0], [1.0, -2.0], [-1.0, 1.0]])
    A = A0 + 1.5 * rng.standard_normal(A0.shape)
    B = A0 @ X + 1.0 * rng.standard_normal(A0.shape)
    save(HERE / "paper_2x2/A.csv", A, "A0 + noise of std 1.5")
    save(HERE / "paper_2x2/B.csv", B, "A0 X + noise of std 1")
    save(HERE / "paper_2x2/truth.csv", X, "true X")


def covariance(rng):
    n, m = 5, 40
    L = rng.standard_normal((n, n))
    data = rng.standard_normal((m, n)) @ L.T
    data[rng.random((m, n)) < 0.35] = np.nan  # missing readings
    C = np.eye(n)
    for i in range(n):
        for j in range(i):
            both = ~np.isnan(data[:, i]) & ~np.isnan(data[:, j])
            C[i, j] = C[j, i] = np.corrcoef(data[both, i], data[both, j])[0, 1]
    # Pairwise deletion does not guarantee a positive semidefinite matrix; make sure this one
    # shows the problem by pushing one correlation out of the consistent range.
    C[0, 1] = C[1, 0] = np.clip(C[0, 1] + 0.6 * np.sign(C[0, 1] or 1.0), -0.99, 0.99)
    assert np.linalg.eigvalsh(C)[0] < 0, "the example must be indefinite"
    save(HERE / "covariance/C.csv", C, "correlation matrix from pairwise deletion (indefinite)")
    sd = np.array([1e-3, 2e-3, 1e-4, 3e-4, 5e-4])
    S = sd[:, None] * C * sd[None, :]
    save(HERE / "covariance/S.csv", S,
         "covariance of 5 sensors in their units (standard deviations 1e-4 to 2e-3), pairwise deletion (indefinite)")
    save_labelled(HERE / "covariance/S_named.csv", S, SENSORS)


# The sensors of covariance/S_named.csv.
SENSORS = ["accel_x", "accel_y", "gyro_z", "temp", "pressure"]


def save_labelled(path, matrix, names):
    """CSV as pandas' DataFrame(matrix, index=names, columns=names).to_csv() writes it: an empty
    first header cell, the names as the header and as each row's first cell, shortest round-trip
    numbers."""
    lines = ["," + ",".join(names)]
    lines += [name + "," + ",".join(repr(float(v)) for v in row) for name, row in zip(names, matrix)]
    path.write_text("\n".join(lines) + "\n")


def load_cell(rng):
    m = 20
    sensitivity = np.array([[0.80, -0.10, 0.05, 0.30],    # mV per N of Fx on each gauge
                            [0.05, 0.75, -0.20, 0.25],
                            [0.10, 0.10, 0.90, -0.40]])
    loads = rng.uniform(-50.0, 50.0, (m, 3))
    A = loads + 0.5 * rng.standard_normal((m, 3))
    B = loads @ sensitivity + 0.05 * rng.standard_normal((m, 4))
    save(HERE / "load_cell/loads.csv", A, "applied loads measured by a reference cell (N)", ["Fx", "Fy", "Fz"])
    save(HERE / "load_cell/readings.csv", B, "strain-gauge readings (mV)", ["g1", "g2", "g3", "g4"])


def logged(rng):
    """A hexapod log as a logger writes it: a time column (s), 300 rows recorded at rest, then 700
    while the payload moves; accelerations in m/s^2 and forces in kN (a load-cell amplifier's
    unit), untared (a static load of about 21 N on every strut, at rest and moving), with
    per-strut noise, and one spike (data row 650: 60 N on strut 2, about 120 of its standard
    deviations): `spdfit fit --time-col t --rest-rows :0.599 --scale-b 1000 --offsets rest`."""
    n, rest, moving = 6, 300, 700
    sd_a = np.array([0.05, 0.05, 0.1, 0.1, 0.2, 0.2])
    sd_b = np.array([0.5, 0.5, 0.3, 0.3, 0.2, 0.2])  # N
    rest_A = rng.standard_normal((rest, n)) * sd_a
    rest_B = rng.standard_normal((rest, n)) * sd_b
    A0 = rng.uniform(-5, 5, (moving, n))
    A = A0 + rng.standard_normal((moving, n)) * sd_a
    B = A0 @ M_P + rng.standard_normal((moving, n)) * sd_b
    preload = np.array([21.0, 20.0, 22.0, 21.5, 20.5, 21.0])  # N, in every row: the forces untared
    t = 0.002 * np.arange(rest + moving)
    forces = np.vstack([rest_B, B]) + preload
    forces[649, 1] += 60.0  # a spike: one reading of strut 2 off by 60 N
    table = np.column_stack([t, np.vstack([rest_A, A]), forces / 1000.0])
    names = ["t"] + [f"acc{i + 1}" for i in range(n)] + [f"F{i + 1}" for i in range(n)]
    save(HERE / "logged/log.csv", table, "hexapod log: time (s), strut accelerations (m/s^2), base forces (kN, untared); "
         "rows 1-300 at rest (t <= 0.598)", names)


if __name__ == "__main__":
    hexapod(np.random.default_rng(2))
    paper_2x2(np.random.default_rng(7))
    covariance(np.random.default_rng(11))
    load_cell(np.random.default_rng(17))
    logged(np.random.default_rng(23))
