"""Type stubs for spdfit.physical (see physical.py for the documentation)."""
import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy.typing as npt

from ._records import InertiaRepair as InertiaRepair, PhysicalDesign as PhysicalDesign, PhysicalEstimate as PhysicalEstimate, RegressFit as RegressFit, UrdfLinkRepair as UrdfLinkRepair
from .hexapod import Geometry

_GeometrySource = Union[None, Geometry, str, os.PathLike[str], Dict[str, Any]]

def identify(A: Any, B: Optional[npt.ArrayLike] = ..., geometry: _GeometrySource = ..., *, a_cols: Any = ..., b_cols: Any = ..., strut_masses: Optional[str] = ..., **options: Any) -> PhysicalEstimate: ...  # options: physical.identify
def design(geometry: _GeometrySource = ..., strut_masses: str = ...) -> PhysicalDesign: ...
def mass_matrix(geometry: _GeometrySource = ..., *, mass: float, center_of_mass: npt.ArrayLike,
                inertia: npt.ArrayLike) -> npt.NDArray[Any]: ...
def inertia_repair(mass: float, center_of_mass: npt.ArrayLike, inertia: npt.ArrayLike, **options: Any) -> InertiaRepair: ...  # options: physical.inertia_repair
def inertia_repair_urdf(text: str, *, source: str = ..., **options: Any) -> Tuple[str, str, List[UrdfLinkRepair]]: ...  # options: physical.inertia_repair_urdf
def regress(Y: npt.ArrayLike, tau: npt.ArrayLike, *, noise_cov: Optional[npt.ArrayLike] = ..., prior: Union[None, str, os.PathLike[str], List[Dict[str, Any]]] = ..., **options: Any) -> RegressFit: ...  # options: physical.regress
