"""Type stubs for spdfit (see __init__.py for the documentation)."""
import os
from typing import Dict, List, Literal, Optional, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from . import experiment as experiment
from . import hexapod as hexapod
from . import linkage as linkage
from . import factor as factor
from .factor import Factor as Factor
from ._spdfit import (AutoReason as AutoReason, PsdCertificate as PsdCertificate, DataError as DataError, Diagnostics as Diagnostics, FitResult as FitResult,
                      LinearSystemResult as LinearSystemResult, NearestResult as NearestResult,
                      Bootstrap as Bootstrap, Interval as Interval, SpectrumUncertainty as SpectrumUncertainty)

NearestSpdResult = NearestResult
NearestCorrelationResult = NearestResult
REPAIR_FLOOR_DEFAULT: float

__version__: str
METHODS: Tuple[str, ...]
_Method = Literal["ls", "procrustes", "tls", "tls-sym", "tls-psd", "spde", "spd-tls", "psd-ls", "auto"]

_PathLike = Union[str, "os.PathLike[str]"]

def read_matrix(path: _PathLike, *, allow_nonfinite: bool = ..., index_col: Optional[bool] = ...) -> npt.NDArray[np.float64]: ...
def read_table(path: _PathLike, *, allow_nonfinite: bool = ..., index_col: Optional[bool] = ...) -> Tuple[npt.NDArray[np.float64], List[str]]: ...
def write_csv(path: _PathLike, X: npt.ArrayLike) -> None: ...

class NumericalError(RuntimeError):
    result: Optional[object]
    def __init__(self, message: str, result: Optional[object] = ...) -> None: ...

class SpdfitWarning(UserWarning): ...

def fit(A: npt.ArrayLike, B: npt.ArrayLike, method: _Method = ..., *,
        rank_tolerance: Optional[float] = ..., noise_ratio: Optional[float] = ...,
        max_iter: Optional[int] = ..., min_eig: Optional[float] = ..., bootstrap: int = ...,
        confidence: Optional[float] = ..., seed: Optional[int] = ..., threads: int = ...,
        reported_diagnostics: bool = ...) -> FitResult: ...
def fit_files(A_path: _PathLike, B_path: _PathLike, method: _Method = ..., *,
              block_rows: int = ..., threads: int = ..., rank_tolerance: Optional[float] = ...,
              noise_ratio: Optional[float] = ..., max_iter: Optional[int] = ...,
              min_eig: Optional[float] = ..., bootstrap: int = ..., confidence: Optional[float] = ...,
              seed: Optional[int] = ..., reported_diagnostics: bool = ...) -> FitResult: ...
def fit_all(A: npt.ArrayLike, B: npt.ArrayLike, *, rank_tolerance: Optional[float] = ...,
            noise_ratio: Optional[float] = ..., max_iter: Optional[int] = ...,
            min_eig: Optional[float] = ..., reported_diagnostics: bool = ...) -> Dict[str, FitResult]: ...
def spd_total_least_squares(A: npt.ArrayLike, B: npt.ArrayLike, *, rank_tolerance: Optional[float] = ...,
                            noise_ratio: Optional[float] = ..., max_iter: Optional[int] = ...) -> FitResult: ...
def psd_least_squares(A: npt.ArrayLike, B: npt.ArrayLike, *, min_eig: Optional[float] = ...,
                      rank_tolerance: Optional[float] = ..., max_iter: Optional[int] = ...) -> FitResult: ...
def auto_fit(A: npt.ArrayLike, B: npt.ArrayLike, *, rank_tolerance: Optional[float] = ...,
             noise_ratio: Optional[float] = ..., max_iter: Optional[int] = ...) -> FitResult: ...
def least_squares(A: npt.ArrayLike, B: npt.ArrayLike, *, rank_tolerance: Optional[float] = ...) -> FitResult: ...
def symmetric_procrustes(A: npt.ArrayLike, B: npt.ArrayLike, *, rank_tolerance: Optional[float] = ...) -> FitResult: ...
def total_least_squares(A: npt.ArrayLike, B: npt.ArrayLike, *, rank_tolerance: Optional[float] = ...,
                        noise_ratio: Optional[float] = ...) -> FitResult: ...
def total_least_squares_symmetric(A: npt.ArrayLike, B: npt.ArrayLike, *,
                                  rank_tolerance: Optional[float] = ...,
                                  noise_ratio: Optional[float] = ...) -> FitResult: ...
def total_least_squares_psd(A: npt.ArrayLike, B: npt.ArrayLike, *, rank_tolerance: Optional[float] = ...,
                            noise_ratio: Optional[float] = ...) -> FitResult: ...
def spde(A: npt.ArrayLike, B: npt.ArrayLike, *, rank_tolerance: Optional[float] = ...) -> FitResult: ...
@overload
def nearest_spd(X: npt.ArrayLike, min_eig: Optional[float] = ..., *, min_eig_rel: Optional[float] = ...,
                keep_diag: bool = ..., via_corr: bool = ..., weights: Optional[npt.ArrayLike] = ...,
                max_iter: Optional[int] = ..., tol: Optional[float] = ...,
                full_output: Literal[False] = ...) -> npt.NDArray[np.float64]: ...
@overload
def nearest_spd(X: npt.ArrayLike, min_eig: Optional[float] = ..., *, min_eig_rel: Optional[float] = ...,
                keep_diag: bool = ..., via_corr: bool = ..., weights: Optional[npt.ArrayLike] = ...,
                max_iter: Optional[int] = ..., tol: Optional[float] = ...,
                full_output: Literal[True]) -> NearestResult: ...
@overload
def nearest_correlation(C: npt.ArrayLike, *, weights: Optional[npt.ArrayLike] = ..., alpha: Optional[float] = ...,
                        min_eig: Optional[float] = ..., min_eig_rel: Optional[float] = ...,
                        max_iter: Optional[int] = ..., tol: Optional[float] = ...,
                        full_output: Literal[False] = ...) -> npt.NDArray[np.float64]: ...
@overload
def nearest_correlation(C: npt.ArrayLike, *, weights: Optional[npt.ArrayLike] = ..., alpha: Optional[float] = ...,
                        min_eig: Optional[float] = ..., min_eig_rel: Optional[float] = ...,
                        max_iter: Optional[int] = ..., tol: Optional[float] = ...,
                        full_output: Literal[True]) -> NearestResult: ...
def area_criterion(A: npt.ArrayLike, B: npt.ArrayLike, X: npt.ArrayLike) -> Optional[float]: ...
def solve(A: npt.ArrayLike, b: npt.ArrayLike, *, threshold: Optional[float] = ...) -> LinearSystemResult: ...
