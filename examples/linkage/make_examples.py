"""Regenerates the linear-system and four-bar example files in examples/linkage/ (Debian's
/usr/bin/python3). The files are committed; this script documents exactly how they were made,
and tests/linkage/test_docs.py checks that it reproduces them byte for byte.

  notes_ex1..6_A.csv, _b.csv   the six classified systems of the lecture notes (shared/seeds/
                               002, section 3.3.2) as their equations are written (example 4's
                               printed matrix has a 6 where its equations have a 2)
  crank_rocker_pairs.csv       13 exact input-output pairs (degrees) of the crank-rocker with
                               a1 = 1, a2 = 0.4, a3 = 1.1, a4 = 0.9 on branch +1, psi = 0..300
  measured_pairs.csv           the same linkage at 25 inputs, outputs with Gaussian noise of
                               0.3 degrees (seed 4), as a measured function would come
  measured_weights.csv         weight 4 on the middle nine positions, 1 elsewhere
"""
import pathlib

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent

NOTES = {
    1: ([[5, -1, 2], [-2, 6, 9], [-7, 5, -3]], [7, 0, -7]),
    2: ([[5, -1, 2], [-2, 6, 9], [15, -3, 6]], [7, 0, 21]),
    3: ([[5, -1, 2], [10, -2, 4], [-15, 3, -6]], [7, 14, -21]),
    4: ([[5, -1, 2], [-10, 2, -4], [15, -3, 6]], [7, -5, -5]),
    5: ([[5, -1, 2], [-2, 6, 9], [-10, 2, -4]], [7, 0, 18]),
    6: ([[5, -1, 2], [-2, 6, 9], [0, 8, 14]], [-12, 0, 8]),
}


def output_angle(a, psi, branch=1):
    """phi on `branch` from the Freudenstein equation (notes eq. 3.3), radians."""
    a1, a2, a3, a4 = a
    k1 = (a1**2 + a2**2 + a4**2 - a3**2) / (2 * a2 * a4)
    k2, k3 = a1 / a2, a1 / a4
    A, B, C = k2 - np.cos(psi), -np.sin(psi), k1 - k3 * np.cos(psi)
    return np.arctan2(B, A) + branch * np.arccos(-C / np.hypot(A, B))


def write(name, rows, header=None, comment=None):
    lines = []
    if comment:
        lines.append(f"# {comment}")
    if header:
        lines.append(",".join(header))
    for row in np.atleast_2d(rows):
        lines.append(",".join(repr(float(x)) if not float(x).is_integer() else str(int(x)) for x in row))
    (HERE / name).write_text("\n".join(lines) + "\n")


def main():
    for n, (A, b) in NOTES.items():
        write(f"notes_ex{n}_A.csv", A, comment=f"lecture notes 002, section 3.3.2, example {n}: A")
        write(f"notes_ex{n}_b.csv", np.array(b)[:, None], comment=f"example {n}: b")
    bar = (1.0, 0.4, 1.1, 0.9)
    psi_deg = np.arange(0, 301, 25)
    phi = output_angle(bar, np.radians(psi_deg))
    write("crank_rocker_pairs.csv", np.c_[psi_deg, np.degrees(phi)], header=["psi_deg", "phi_deg"],
          comment="exact pairs of the crank-rocker a = 1, 0.4, 1.1, 0.9 (branch +1)")
    rng = np.random.default_rng(4)
    psi_deg = np.linspace(0, 300, 25)
    phi = output_angle(bar, np.radians(psi_deg)) + np.radians(0.3) * rng.standard_normal(psi_deg.size)
    write("measured_pairs.csv", np.c_[psi_deg, np.round(np.degrees(phi), 3)], header=["psi_deg", "phi_deg"],
          comment="the crank-rocker's outputs with 0.3 degree noise, to 0.001 degree")
    w = np.ones(psi_deg.size)
    w[8:17] = 4
    write("measured_weights.csv", w[:, None], header=["weight"], comment="weight 4 on positions 9..17")


if __name__ == "__main__":
    main()
