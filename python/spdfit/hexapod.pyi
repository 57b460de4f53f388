"""Type stubs for spdfit.hexapod (see hexapod.py for the documentation)."""
import os
from typing import Any, Dict, NamedTuple, Optional, Union

import numpy as np
import numpy.typing as npt

Array = npt.NDArray[np.float64]

class Geometry:
    base_points: Array
    payload_points: Array
    payload_origin: Array
    payload_rotation: Array
    payload_mass: float
    payload_inertia: Array
    strut_mass: Array
    strut_stiffness: Array
    strut_damping: Array
    def to_json(self) -> str: ...

class MethodIdentification:
    result: Any  # spdfit.FitResult
    eigenvalues: Optional[Array]
    modes_hz: Optional[Array]
    error_vs_truth: Optional[float]
    modes_uncertainty: Any  # Optional[spdfit.SpectrumUncertainty]

class Model(NamedTuple):
    geometry: Geometry
    jacobian: Array
    mass_matrix: Array
    payload_mass_matrix: Array
    modes_hz: Array
    strut_lengths: Array
    mass_matrix_eigenvalues: Array
    jacobian_condition: float
    strut_directions: Array

class Simulation(NamedTuple):
    A: Array
    B: Array
    truth: Array
    A_true: Array
    B_true: Array

GeometrySource = Union[None, Geometry, str, os.PathLike, Dict[str, Any]]

def cubic_geometry() -> Geometry: ...
def thesis_mass_matrix() -> Array: ...
def geometry(source: GeometrySource = ...) -> Geometry: ...
def model(geometry_source: GeometrySource = ...) -> Model: ...
def simulate(samples: int = ..., noise_var: float = ..., *, seed: int = ...,
             truth: Union[str, npt.ArrayLike, GeometrySource] = ..., signal_var: float = ...,
             distribution: str = ..., force_noise_var: Optional[float] = ...) -> Simulation: ...
def identify(A: npt.ArrayLike, B: npt.ArrayLike, *, truth: Optional[npt.ArrayLike] = ...,
             stiffness: Optional[npt.ArrayLike] = ..., bootstrap: int = ..., confidence: Optional[float] = ...,
             seed: Optional[int] = ..., threads: int = ...) -> Dict[str, MethodIdentification]: ...
