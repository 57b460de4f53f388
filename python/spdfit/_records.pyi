"""Type stubs for spdfit._records (see _records.py for the documentation)."""
from typing import Any, Dict, List, Optional

import numpy.typing as npt

_Array = npt.NDArray[Any]

class Record(Dict[str, Any]):
    def __init__(self, items: Any = ..., /) -> None: ...
    def __getattr__(self, name: str) -> Any: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def to_json(self, indent: Optional[int] = ...) -> str: ...

class PhysicalEstimate(Record):
    status: str
    mass: float
    center_of_mass: _Array
    inertia: _Array
    principal_moments: _Array
    principal_axes: _Array
    strut_mass: _Array
    M_p: _Array
    M_p_eigenvalues: _Array
    modes_hz: _Array
    pseudo_inertia_min_eig: float
    physically_consistent: bool
    certificate: Record
    criterion: float
    iterations: int
    converged: bool
    warnings: List[str]
    warning_codes: List[str]

class PhysicalDesign(Record):
    parameters: List[str]
    rank: int
    condition: float
    length_scale: float
    null_space: _Array
    confounded: str

class InertiaRepair(Record):
    mass: float
    center_of_mass: _Array
    inertia: _Array
    changed: bool
    distance: float
    certificate: Record
    min_eig: float
    principal_moments: _Array
    warnings: List[str]
    warning_codes: List[str]

class UrdfLinkRepair(Record):
    link: str
    line: int
    changed: bool
    distance: float
    mass: float
    center_of_mass: _Array
    inertia_before: _Array
    inertia: _Array

class RegressFit(Record):
    status: str
    bodies: int
    parameters: _Array
    body: List[Record]
    extra: _Array
    rank: int
    condition: float
    base_parameters: List[Record]
    undetermined: List[Record]
    criterion: float
    residual_rms: float
    certificate: Record
    iterations: int
    converged: bool
    physically_consistent: bool
    warnings: List[str]
    warning_codes: List[str]
    report: str

class PayloadEstimate(Record):
    status: str
    mass: float
    center_of_mass: _Array
    inertia: _Array
    force_bias: _Array
    torque_bias: _Array
    standard_errors: Record
    parameters: _Array
    residual_rms: _Array
    rank: int
    undetermined: List[str]
    physically_consistent: bool
    certificate: Record
    converged: bool
    warnings: List[str]
    warning_codes: List[str]
    residuals: _Array
    report: str

class PayloadDesign(Record):
    criterion: str
    poses: int
    chosen: List[int]
    log_det: float
    condition: float
    se_mass: float
    se_center_of_mass: _Array
    random: Record
    warnings: List[str]
    warning_codes: List[str]
    report: str

class PhysicalExperiment(Record):
    experiment: str
    trials: int
    seed: int
    rows: List[Record]

def record(cls: type, value: Dict[str, Any]) -> Record: ...
