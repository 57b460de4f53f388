"""Type stubs for spdfit.io (see io.py for the documentation)."""
import os
from typing import List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

__all__ = ["read_matrix", "read_table", "write_csv"]

_PathLike = Union[str, "os.PathLike[str]"]

def read_matrix(path: _PathLike, *, allow_nonfinite: bool = ..., index_col: Optional[bool] = ..., header: Optional[bool] = ...) -> npt.NDArray[np.float64]: ...
def read_table(path: _PathLike, *, allow_nonfinite: bool = ..., index_col: Optional[bool] = ..., header: Optional[bool] = ...) -> Tuple[npt.NDArray[np.float64], List[str]]: ...
def write_csv(path: _PathLike, X: npt.ArrayLike) -> None: ...
