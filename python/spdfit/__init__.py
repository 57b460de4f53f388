"""spdfit: estimate symmetric positive definite matrices from imperfect measurements.

Given measurements A X ~= B with noise in both A and B (A, B m x n, one sample per row),
estimate X (n x n):

    >>> import numpy as np, spdfit
    >>> A = np.array([[5., 2.], [-3., 1.], [1., -2.], [-1., 1.]])
    >>> X = np.array([[3., 1.], [1., 1.]])
    >>> r = spdfit.fit(A, A @ X, method="spde")
    >>> bool(np.allclose(r.X, X))
    True

Methods (the names of the command line): "ls" (least squares), "procrustes" (symmetric least
squares), "tls", "tls-sym", "tls-psd" (total least squares and its repairs), "spde" (the
area-criterion estimate, always symmetric positive definite), "spd-tls" (total least squares over
the positive definite matrices), "psd-ls" (least squares over X >= min_eig I, with an optimality
certificate) and "auto" (spde, spd-tls or psd-ls, chosen from the data; fit's default). "ls" and
"tls" also take B with d != n columns and return an n x d X. Every method works from the
Householder QR of [A B], not from Gram matrices; spdfit.Factor holds that factor as a value that
merges, for fits spread over processes or machines. Numerical failures raise NumericalError; bad
input raises ValueError (DataError for files); warnings are SpdfitWarning.
"""
# The package's modules; this file only gathers their public names (spdfit.fit is
# spdfit.fitting.fit, spdfit.read_matrix spdfit.io.read_matrix, ...). Shared private helpers live
# in _common and _errors, which every module imports directly: no module imports from here.
from . import _spdfit
from ._errors import DataError, NumericalError, SpdfitWarning, WARNING_CLASSES as _WARNING_CLASSES, outcome_codes
from ._spdfit import (AutoReason, Diagnostics, FitResult, LinearSystemResult, NearestResult,
                      NoiseModel, PsdCertificate, BoundaryCertificate, Bootstrap, Interval, SpectrumUncertainty)
from . import _blas_core  # noqa: F401  (warns once if OpenBLAS runs generic kernels here)
from . import experiment, factor, fitting, hexapod, io, linear_system, linkage, payload, physical, repair
from .factor import Factor
from .fitting import (area_criterion, auto_fit, fit, fit_all, fit_files, least_squares, psd_least_squares, spde,
                      spd_total_least_squares, symmetric_procrustes, total_least_squares, total_least_squares_psd,
                      total_least_squares_symmetric)
from .io import read_matrix, read_table, write_csv
from .linear_system import solve
from .repair import REPAIR_FLOOR_DEFAULT, nearest_correlation, nearest_covariance, nearest_spd

# The repairs' one result class, under the names each function's documentation uses.
NearestSpdResult = NearestCorrelationResult = NearestResult

__version__ = _spdfit.__version__

# Every method name fit accepts, from the library: the estimators, then "auto".
METHODS = _spdfit.METHODS

__all__ = [
    "METHODS", "DataError", "Diagnostics", "Factor", "FitResult", "NearestSpdResult", "NoiseModel", "NumericalError",
    "LinearSystemResult", "SpdfitWarning", "area_criterion", "solve", "fit", "fit_all", "fit_files",
    "least_squares", "nearest_spd", "nearest_correlation", "nearest_covariance", "read_matrix",
    "read_table", "spde", "symmetric_procrustes", "total_least_squares", "total_least_squares_psd",
    "spd_total_least_squares", "psd_least_squares", "auto_fit", "PsdCertificate", "BoundaryCertificate", "AutoReason", "Bootstrap", "Interval", "SpectrumUncertainty",
    "NearestCorrelationResult", "NearestResult", "REPAIR_FLOOR_DEFAULT",
    "total_least_squares_symmetric", "write_csv", "outcome_codes",
    *sorted(cls.__name__ for cls in _WARNING_CLASSES.values()),
]

globals().update({cls.__name__: cls for cls in _WARNING_CLASSES.values()})
