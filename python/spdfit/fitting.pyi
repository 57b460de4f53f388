"""Type stubs for spdfit.fitting (see fitting.py for the documentation)."""
import os
from typing import Any, Dict, Literal, Optional, Sequence, Union

import numpy.typing as npt

from ._spdfit import FitResult, NoiseModel

__all__ = ["fit", "fit_all", "fit_files", "least_squares", "symmetric_procrustes", "total_least_squares",
           "total_least_squares_symmetric", "total_least_squares_psd", "spde", "spd_total_least_squares",
           "psd_least_squares", "auto_fit", "area_criterion"]

_Method = Literal["ls", "procrustes", "tls", "tls-sym", "tls-psd", "spde", "spd-tls", "psd-ls", "auto"]

_PathLike = Union[str, "os.PathLike[str]"]
# a_cols and b_cols: a label (a str that is none is a selection as the command line writes it,
# "acc1:acc6"), a slice of labels or of 0-based positions, or a list of labels and positions.
_Columns = Union[None, str, int, slice, Sequence[Any]]

def fit(A: Any, B: Optional[npt.ArrayLike] = ..., method: _Method = ..., *, a_cols: _Columns = ..., b_cols: _Columns = ..., **options: Any) -> FitResult: ...  # options: fit
def fit_files(A_path: _PathLike, B_path: Optional[_PathLike] = ..., method: _Method = ..., **options: Any) -> FitResult: ...  # options: fit_files
def fit_all(A: Any, B: Optional[npt.ArrayLike] = ..., *, a_cols: _Columns = ..., b_cols: _Columns = ..., **options: Any) -> Dict[str, FitResult]: ...  # options: fit_all
def spd_total_least_squares(A: npt.ArrayLike, B: npt.ArrayLike, **options: Any) -> FitResult: ...  # options: fit:spd-tls
def psd_least_squares(A: npt.ArrayLike, B: npt.ArrayLike, **options: Any) -> FitResult: ...  # options: fit:psd-ls
def auto_fit(A: npt.ArrayLike, B: npt.ArrayLike, **options: Any) -> FitResult: ...  # options: fit:auto
def least_squares(A: npt.ArrayLike, B: npt.ArrayLike, **options: Any) -> FitResult: ...  # options: fit:ls
def symmetric_procrustes(A: npt.ArrayLike, B: npt.ArrayLike, **options: Any) -> FitResult: ...  # options: fit:procrustes
def total_least_squares(A: npt.ArrayLike, B: npt.ArrayLike, **options: Any) -> FitResult: ...  # options: fit:tls
def total_least_squares_symmetric(A: npt.ArrayLike, B: npt.ArrayLike, **options: Any) -> FitResult: ...  # options: fit:tls-sym
def total_least_squares_psd(A: npt.ArrayLike, B: npt.ArrayLike, **options: Any) -> FitResult: ...  # options: fit:tls-psd
def spde(A: npt.ArrayLike, B: npt.ArrayLike, **options: Any) -> FitResult: ...  # options: fit:spde
def area_criterion(A: npt.ArrayLike, B: npt.ArrayLike, X: npt.ArrayLike) -> Optional[float]: ...
