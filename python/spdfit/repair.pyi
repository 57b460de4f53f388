"""Type stubs for spdfit.repair (see repair.py for the documentation)."""
from typing import Any, Literal, Optional, overload

import numpy.typing as npt

from ._spdfit import NearestResult

__all__ = ["nearest_covariance"]

# Returns NumPy for an array, a pandas DataFrame for a DataFrame (pandas is optional: Any).
@overload
def nearest_covariance(S: Any, *, full_output: Literal[False] = ..., **options: Any) -> Any: ...  # options: nearest_covariance
@overload
def nearest_covariance(S: Any, *, full_output: Literal[True], **options: Any) -> NearestResult: ...  # options: nearest_covariance
