"""Type stubs for spdfit.hexapod (see hexapod.py for the documentation)."""
import os
from typing import Any, Dict, NamedTuple, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from ._spdfit import FitResult, NoiseModel, SpectrumUncertainty, _Pybind11Type

_Array = npt.NDArray[np.float64]

class Geometry(metaclass=_Pybind11Type):
    @property
    def base_points(self) -> _Array: ...
    @property
    def payload_points(self) -> _Array: ...
    @property
    def payload_origin(self) -> _Array: ...
    @property
    def payload_rotation(self) -> _Array: ...
    @property
    def payload_mass(self) -> float: ...
    @property
    def payload_inertia(self) -> _Array: ...
    @property
    def strut_mass(self) -> _Array: ...
    @property
    def strut_stiffness(self) -> _Array: ...
    @property
    def strut_damping(self) -> _Array: ...
    def to_json(self) -> str: ...

class MethodIdentification(metaclass=_Pybind11Type):
    @property
    def result(self) -> FitResult: ...
    @property
    def eigenvalues(self) -> Optional[_Array]: ...
    @property
    def modes_hz(self) -> Optional[_Array]: ...
    @property
    def error_vs_truth(self) -> Optional[float]: ...
    @property
    def modes_uncertainty(self) -> Optional[SpectrumUncertainty]: ...

class Model(NamedTuple):
    geometry: Geometry
    jacobian: _Array
    mass_matrix: _Array
    payload_mass_matrix: _Array
    modes_hz: _Array
    strut_lengths: _Array
    mass_matrix_eigenvalues: _Array
    jacobian_condition: float
    strut_directions: _Array

class _SimulationFields(NamedTuple):
    A: _Array
    B: _Array
    truth: _Array
    A_true: _Array
    B_true: _Array

class Simulation(_SimulationFields):
    rest_A: Optional[_Array]
    rest_B: Optional[_Array]

_GeometrySource = Union[None, Geometry, str, os.PathLike, Dict[str, Any]]

def cubic_geometry() -> Geometry: ...
def thesis_mass_matrix() -> _Array: ...
def geometry(source: _GeometrySource = ...) -> Geometry: ...
def model(geometry_source: _GeometrySource = ...) -> Model: ...
def simulate(samples: int = ..., noise_var: float = ..., *, truth: Union[str, npt.ArrayLike, _GeometrySource] = ..., **options: Any) -> Simulation: ...  # options: hexapod.simulate
def identify(A: Any, B: Optional[npt.ArrayLike] = ..., *, a_cols: Any = ..., b_cols: Any = ..., truth: Optional[npt.ArrayLike] = ..., stiffness: Union[None, float, npt.ArrayLike] = ..., geometry: _GeometrySource = ..., physical: bool = ..., **options: Any) -> Dict[str, Any]: ...  # options: hexapod.identify
