"""Type stubs for spdfit.payload (see payload.py for the documentation)."""
import os
from typing import Any, Dict, Optional, Sequence, Union

import numpy.typing as npt

from ._records import PayloadDesign as PayloadDesign, PayloadEstimate as PayloadEstimate

def identify(log: Union[None, str, os.PathLike[str], Any] = ..., *, wrench: Optional[npt.ArrayLike] = ..., quaternion: Optional[npt.ArrayLike] = ..., rotation: Optional[npt.ArrayLike] = ..., gravity_in_sensor: Optional[npt.ArrayLike] = ..., accel: Optional[npt.ArrayLike] = ..., specific_force: Optional[npt.ArrayLike] = ..., omega: Optional[npt.ArrayLike] = ..., alpha: Optional[npt.ArrayLike] = ..., time: Optional[npt.ArrayLike] = ..., **options: Any) -> PayloadEstimate: ...  # options: payload.identify
def urdf_link(estimate: Dict[str, Any], name: str = ..., precision: int = ...) -> str: ...
def design(candidates: Union[None, str, os.PathLike[str], Any] = ..., *, quaternion: Optional[npt.ArrayLike] = ..., rotation: Optional[npt.ArrayLike] = ..., gravity_in_sensor: Optional[npt.ArrayLike] = ..., **options: Any) -> PayloadDesign: ...  # options: payload.design
