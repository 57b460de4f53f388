"""Type stubs for spdfit.physical (see physical.py for the documentation)."""
import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy.typing as npt

from .hexapod import Geometry

_GeometrySource = Union[None, Geometry, str, os.PathLike[str], Dict[str, Any]]

def identify(A: Any, B: Optional[npt.ArrayLike] = ..., geometry: _GeometrySource = ..., *, a_cols: Any = ..., b_cols: Any = ..., strut_masses: Optional[str] = ..., **options: Any) -> Dict[str, Any]: ...  # options: physical.identify
def design(geometry: _GeometrySource = ..., strut_masses: str = ...) -> Dict[str, Any]: ...
def mass_matrix(geometry: _GeometrySource = ..., *, mass: float, center_of_mass: npt.ArrayLike,
                inertia: npt.ArrayLike) -> npt.NDArray[Any]: ...
def inertia_repair(mass: float, center_of_mass: npt.ArrayLike, inertia: npt.ArrayLike, **options: Any) -> Dict[str, Any]: ...  # options: physical.inertia_repair
def inertia_repair_urdf(text: str, *, source: str = ..., **options: Any) -> Tuple[str, str, List[Dict[str, Any]]]: ...  # options: physical.inertia_repair_urdf
def regress(Y: npt.ArrayLike, tau: npt.ArrayLike, *, noise_cov: Optional[npt.ArrayLike] = ..., prior: Union[None, str, os.PathLike[str], List[Dict[str, Any]]] = ..., **options: Any) -> Dict[str, Any]: ...  # options: physical.regress
