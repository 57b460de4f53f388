"""Type stubs for spdfit.linear_system (see linear_system.py for the documentation)."""
from typing import Optional

import numpy.typing as npt

from ._spdfit import LinearSystemResult

__all__ = ["solve"]

def solve(A: npt.ArrayLike, b: npt.ArrayLike, *, threshold: Optional[float] = ...) -> LinearSystemResult: ...
