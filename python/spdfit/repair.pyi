"""Type stubs for spdfit.repair (see repair.py for the documentation)."""
from typing import Any, Literal, Optional, overload

import numpy.typing as npt

from ._spdfit import NearestResult

__all__ = ["REPAIR_FLOOR_DEFAULT", "nearest_covariance", "nearest_correlation", "nearest_spd"]

REPAIR_FLOOR_DEFAULT: float

# The repairs return NumPy for an array, a pandas DataFrame for a DataFrame (pandas is optional: Any).
@overload
def nearest_covariance(S: Any, *, full_output: Literal[False] = ..., **options: Any) -> Any: ...  # options: nearest_covariance
@overload
def nearest_covariance(S: Any, *, full_output: Literal[True], **options: Any) -> NearestResult: ...  # options: nearest_covariance
@overload
def nearest_spd(X: Any, min_eig: Optional[float] = ..., *, full_output: Literal[False] = ..., **options: Any) -> Any: ...  # options: nearest_spd
@overload
def nearest_spd(X: Any, min_eig: Optional[float] = ..., *, full_output: Literal[True], **options: Any) -> NearestResult: ...  # options: nearest_spd
@overload
def nearest_correlation(C: Any, *, full_output: Literal[False] = ..., **options: Any) -> Any: ...  # options: nearest_correlation
@overload
def nearest_correlation(C: Any, *, full_output: Literal[True], **options: Any) -> NearestResult: ...  # options: nearest_correlation
