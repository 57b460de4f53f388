"""Type stubs for spdfit (see __init__.py for the documentation)."""
import os
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from . import experiment as experiment
from . import hexapod as hexapod
from . import linkage as linkage
from . import payload as payload
from . import physical as physical
from . import factor as factor
from . import repair as repair
from .repair import nearest_covariance as nearest_covariance
from .factor import Factor as Factor
from ._errors import DataError as DataError, NumericalError as NumericalError, SpdfitWarning as SpdfitWarning
from ._spdfit import (AutoReason as AutoReason, PsdCertificate as PsdCertificate, BoundaryCertificate as BoundaryCertificate,
                      Diagnostics as Diagnostics, FitResult as FitResult,
                      LinearSystemResult as LinearSystemResult, NearestResult as NearestResult, NoiseModel as NoiseModel,
                      Bootstrap as Bootstrap, Interval as Interval, SpectrumUncertainty as SpectrumUncertainty)

NearestSpdResult = NearestResult
NearestCorrelationResult = NearestResult
REPAIR_FLOOR_DEFAULT: float

__version__: str
METHODS: Tuple[str, ...]
_Method = Literal["ls", "procrustes", "tls", "tls-sym", "tls-psd", "spde", "spd-tls", "psd-ls", "auto"]

_PathLike = Union[str, "os.PathLike[str]"]
# a_cols and b_cols: a label (a str that is none is a selection as the command line writes it,
# "acc1:acc6"), a slice of labels or of 0-based positions, or a list of labels and positions.
_Columns = Union[None, str, int, slice, Sequence[Any]]

def read_matrix(path: _PathLike, *, allow_nonfinite: bool = ..., index_col: Optional[bool] = ..., header: Optional[bool] = ...) -> npt.NDArray[np.float64]: ...
def read_table(path: _PathLike, *, allow_nonfinite: bool = ..., index_col: Optional[bool] = ..., header: Optional[bool] = ...) -> Tuple[npt.NDArray[np.float64], List[str]]: ...
def write_csv(path: _PathLike, X: npt.ArrayLike) -> None: ...

# warning classes: from ._errors import {} as {}

def outcome_codes() -> List[Tuple[str, str, str, str, str]]: ...

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
# The repairs return NumPy for an array, a pandas DataFrame for a DataFrame (pandas is optional: Any).
@overload
def nearest_spd(X: Any, min_eig: Optional[float] = ..., *, full_output: Literal[False] = ..., **options: Any) -> Any: ...  # options: nearest_spd
@overload
def nearest_spd(X: Any, min_eig: Optional[float] = ..., *, full_output: Literal[True], **options: Any) -> NearestResult: ...  # options: nearest_spd
@overload
def nearest_correlation(C: Any, *, full_output: Literal[False] = ..., **options: Any) -> Any: ...  # options: nearest_correlation
@overload
def nearest_correlation(C: Any, *, full_output: Literal[True], **options: Any) -> NearestResult: ...  # options: nearest_correlation
def area_criterion(A: npt.ArrayLike, B: npt.ArrayLike, X: npt.ArrayLike) -> Optional[float]: ...
def solve(A: npt.ArrayLike, b: npt.ArrayLike, *, threshold: Optional[float] = ...) -> LinearSystemResult: ...
