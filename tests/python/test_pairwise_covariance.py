"""The repair of a realistic `df.cov()`: a log of 12 sensors with scales from 1e-3 to 300 whose
stretches of missing values make the pairwise-deleted covariance indefinite (tests/support:
sensor_log, pairwise_covariance). A floor relative to that covariance's largest eigenvalue
(1e-8 x 1e5) is above its smallest variance (1e-6): the diagonal-keeping repair's relative floor
is therefore of the correlation matrix D^-1/2 X D^-1/2, which keeps it below every variance.

References: pandas' own DataFrame.cov() where pandas is installed; R's Matrix::nearPD(S, keepDiag
= TRUE) where Rscript is, else its distance from the run recorded below; the properties users rely
on (the variances kept exactly, Cholesky succeeds, the floor met)."""
import os
import shutil
import subprocess
import tempfile
import warnings

import numpy as np
import pytest

import spdfit
from spdfit_testing import pairwise_covariance, sensor_log

# The generator's matrix, identified by its trace: a changed NumPy random stream would make the
# recorded nearPD distance below refer to another matrix, so the test says so instead.
TRACE = 115595.6930334585
# R 4.2.2 with Matrix 1.5-3 (Debian's r-base-core, r-cran-matrix), 2026-11-26:
# norm(as.matrix(nearPD(S, keepDiag = TRUE)$mat) - S, "F") for this S (8 iterations, converged);
# its answer factors by Cholesky, its smallest eigenvalue is 2.5e-8.
NEARPD_KEEPDIAG_DISTANCE = 12.46506533


@pytest.fixture(scope="module")
def S():
    data = sensor_log()
    S = pairwise_covariance(data)
    assert np.trace(S) == pytest.approx(TRACE, rel=1e-13), "the generator's random stream changed"
    return S


def test_the_matrix_is_what_pandas_computes_and_is_indefinite(S):
    try:
        import pandas
    except ImportError:
        pandas = None
    if pandas is not None:
        theirs = pandas.DataFrame(sensor_log()).cov().to_numpy()
        np.testing.assert_allclose(S, theirs, rtol=0, atol=1e-14 * np.abs(S).max())
    lam = np.linalg.eigvalsh(S)
    assert lam[0] < 0
    # The case of the report: the old default floor, 1e-8 x S's largest eigenvalue, exceeds the
    # smallest variance.
    assert spdfit.REPAIR_FLOOR_DEFAULT * lam[-1] > np.diag(S).min()


@pytest.mark.parametrize("kind", ["keep_diag", "via_corr"])
def test_the_default_floor_is_feasible_and_the_result_factors(S, kind):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no warning either
        r = spdfit.nearest_spd(S, full_output=True, **{kind: True})
    assert r.converged and r.cholesky_ok
    np.linalg.cholesky(r.X)
    assert np.array_equal(np.diag(r.X), np.diag(S))
    d = np.diag(S)
    R = S / np.sqrt(np.outer(d, d))
    assert r.min_eig == pytest.approx(spdfit.REPAIR_FLOOR_DEFAULT * np.linalg.eigvalsh(R)[-1], rel=1e-12)
    # The floor is met by the correlation matrix of the answer (to rounding of its unit scale).
    assert np.linalg.eigvalsh(r.X / np.sqrt(np.outer(d, d)))[0] >= r.min_eig - 1e-14


def test_keep_diag_is_nearer_than_nearpd(S):
    ours = spdfit.nearest_spd(S, keep_diag=True, full_output=True)
    assert ours.distance == pytest.approx(np.linalg.norm(ours.X - S), rel=1e-12)
    assert ours.distance < NEARPD_KEEPDIAG_DISTANCE
    # A tighter Newton tolerance moves the answer by what the default one allows (1e-10 sqrt(n)
    # max(d) on the diagonal before its rescaling), relative to the distance about 3e-5 here.
    tight = spdfit.nearest_spd(S, keep_diag=True, tol=1e-14, full_output=True)
    assert tight.distance <= ours.distance
    assert ours.distance - tight.distance <= 1e-4 * tight.distance


@pytest.mark.skipif(shutil.which("Rscript") is None, reason="R (r-base-core, r-cran-matrix) is not installed")
def test_against_nearpd_run_here(S):
    script = ('suppressPackageStartupMessages(library(Matrix)); a <- commandArgs(TRUE); n <- as.integer(a[2]); '
              'S <- matrix(readBin(a[1], "double", n * n), n, n); r <- nearPD(S, keepDiag = TRUE); '
              'X <- as.matrix(r$mat); cat(sprintf("%.12g", norm(X - S, "F")), max(abs(diag(X) - diag(S))), "\\n")')
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "S.bin")
        np.asfortranarray(S).T.tofile(path)
        out = subprocess.run(["Rscript", "-e", script, path, str(len(S))], capture_output=True, text=True, check=True)
    distance, diagonal_change = map(float, out.stdout.split())
    assert distance == pytest.approx(NEARPD_KEEPDIAG_DISTANCE, rel=1e-8)
    assert diagonal_change == 0.0
    assert spdfit.nearest_spd(S, keep_diag=True, full_output=True).distance < distance
