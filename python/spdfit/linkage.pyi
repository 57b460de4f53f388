"""Type stubs for spdfit.linkage (see linkage.py for the documentation)."""
from typing import List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

Array = npt.NDArray[np.float64]
STEERING_PSI_RANGE: Tuple[float, float]

class FourBar:
    a1: float
    a2: float
    a3: float
    a4: float
    def __init__(self, a1: float, a2: float, a3: float, a4: float) -> None: ...

class AngleRange:
    min: float
    max: float

class DialZeros:
    alpha: float
    beta: float

class MotionCheck:
    grashof: str
    transmission: AngleRange
    dead_points: List[float]
    branch_defect: bool
    branch_defect_reason: str

class LinkageSolution:
    k: Array
    dial_zeros: DialZeros
    lengths: Optional[FourBar]
    no_linkage_reason: str
    design_error_norm: float
    structural_error_rms: float
    structural_error_max: float
    phi_generated: Array
    iterations: int
    final_step_norm: float
    rounding_limited: bool
    check: Optional[MotionCheck]

class SynthesisResult:
    ok: bool
    status: str
    message: str
    positions: int
    precision_point: bool
    dial_zeros_fitted: bool
    branch: int
    rank: int
    condition_number: float
    scaled_condition_number: float
    used_svd: bool
    psi: Array
    phi: Array
    design: LinkageSolution
    structural: LinkageSolution
    warnings: List[str]

class AnalysisSample:
    psi: float
    phi_plus: Optional[float]
    phi_minus: Optional[float]
    transmission_angle: Optional[float]

class Analysis:
    bar: FourBar
    k: Array
    grashof: str
    input_fully_rotates: bool
    dead_points: List[float]
    samples: List[AnalysisSample]
    transmission: Optional[AngleRange]

def function_names() -> List[str]: ...
def freudenstein_parameters(bar: FourBar) -> Array: ...
def link_lengths(k: npt.ArrayLike) -> FourBar: ...
def grashof_type(bar: FourBar) -> str: ...
def synthesize(psi: Optional[npt.ArrayLike] = ..., phi: Optional[npt.ArrayLike] = ..., *,
               weights: Optional[npt.ArrayLike] = ..., steering: Optional[float] = ..., function: Optional[str] = ...,
               x_range: Optional[Tuple[float, float]] = ..., psi_range: Optional[Tuple[float, float]] = ...,
               phi_range: Optional[Tuple[float, float]] = ..., points: int = ..., spacing: str = ...,
               alpha: Optional[float] = ..., beta: Optional[float] = ..., fit_dial_zeros: bool = ...,
               refine: bool = ..., tolerance: float = ..., max_iterations: int = ...,
               radians: bool = ...) -> SynthesisResult: ...
def analyze(lengths: Union[FourBar, Sequence[float]], psi: Optional[npt.ArrayLike] = ..., *,
            psi_range: Tuple[float, float] = ..., points: int = ..., radians: bool = ...) -> Analysis: ...
