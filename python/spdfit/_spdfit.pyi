"""Type stubs for the compiled core of spdfit (use the `spdfit` package, not this module)."""
from typing import List, Optional, Tuple

import numpy as np
import numpy.typing as npt

__version__: str

class DataError(ValueError): ...

METHODS: Tuple[str, ...]

class PsdCertificate:
    primal_min_eig: float
    dual_min_eig: float
    complementarity: float
    duality_gap: float

class AutoReason:
    code: str
    text: str

class Diagnostics:
    m: int
    n: int
    d: int
    rank_a: int
    rank_b: int
    cond_a: float
    cond_b: float
    cond_a_scaled: float
    cond_b_scaled: float
    singular_values_a: npt.NDArray[np.float64]
    singular_values_b: npt.NDArray[np.float64]
    residual_norm: float
    symmetric: bool
    positive_definite: bool
    positive_semidefinite: bool
    min_eigenvalue: Optional[float]
    max_eigenvalue: Optional[float]
    area_criterion: Optional[float]
    area_criterion_minimum: Optional[float]
    cross_term_positive_definite: Optional[bool]
    tls_sigma_n: Optional[float]
    tls_sigma_n1: Optional[float]
    tls_correction_norm: Optional[float]
    tls_v22_min_singular_value: Optional[float]
    noise_sigma: Optional[float]
    iterations: Optional[int]
    gradient_norm: Optional[float]
    converged: Optional[bool]
    certificate: Optional[PsdCertificate]
    chosen_method: Optional[str]
    reason: Optional[AutoReason]

class Interval:
    level: float
    lower: npt.NDArray[np.float64]
    upper: npt.NDArray[np.float64]

class SpectrumUncertainty:
    estimate: npt.NDArray[np.float64]
    standard_errors: npt.NDArray[np.float64]
    lower: npt.NDArray[np.float64]
    upper: npt.NDArray[np.float64]
    clusters: List[List[int]]
    failed: int

class Bootstrap:
    replicates: int
    failed: int
    seed: int
    method: str
    scheme: str
    group_rows: int
    groups: int
    standard_errors: npt.NDArray[np.float64]
    bias: npt.NDArray[np.float64]
    interval: Interval
    eigenvalues: Optional[SpectrumUncertainty]

class FitResult:
    method: str
    ok: bool
    status: str
    message: str
    X: npt.NDArray[np.float64]
    diagnostics: Diagnostics
    warnings: List[str]
    standard_errors: Optional[npt.NDArray[np.float64]]
    interval: Optional[Interval]
    bias: Optional[npt.NDArray[np.float64]]
    bootstrap: Optional[Bootstrap]
    row_names: List[str]
    column_names: List[str]

class NearestResult:
    X: npt.NDArray[np.float64]
    distance: float
    clipped: int
    min_eigenvalue_before: float
    min_eig: float
    iterations: int
    gradient_norm: float
    converged: bool
    cholesky_ok: bool
    warnings: List[str]

class ColumnClassification:
    consistent: bool
    finite_solution_dimension: int
    at_infinity_dimension: int
    augmented_rank: int
    residual_norm: float
    backward_error: float

class LinearSystemResult:
    ok: bool
    message: str
    m: int
    n: int
    p: int
    shape: str
    singular_values: npt.NDArray[np.float64]
    threshold: float
    rank: int
    nullity: int
    condition_number: float
    reciprocal_condition_number: float
    effective_condition_number: float
    scaled_singular_values: npt.NDArray[np.float64]
    scaled_condition_number: float
    refinement_steps: int
    consistent: bool
    finite_solution_dimension: int
    at_infinity_dimension: int
    columns: List[ColumnClassification]
    solution: npt.NDArray[np.float64]  # shape (n,) for a 1-D b, (n, p) for an m x p b
    residual_norm: float
    null_space: npt.NDArray[np.float64]
    range: npt.NDArray[np.float64]
    explanation: str
    warnings: List[str]

REPAIR_FLOOR_DEFAULT: float

def fit(A: npt.ArrayLike, B: npt.ArrayLike, method: str, rank_tolerance: Optional[float] = ...,
        noise_ratio: Optional[float] = ..., max_iter: Optional[int] = ...,
        min_eig: Optional[float] = ..., bootstrap: int = ..., confidence: Optional[float] = ...,
        seed: Optional[int] = ..., threads: int = ...) -> FitResult: ...
class StreamOptions:
    block_rows: int
    threads: int
    def __init__(self) -> None: ...

def fit_files(A_path: str, B_path: str, method: str, block_rows: int = ..., threads: int = ...,
              rank_tolerance: Optional[float] = ..., noise_ratio: Optional[float] = ...,
              max_iter: Optional[int] = ..., min_eig: Optional[float] = ..., bootstrap: int = ...,
              confidence: Optional[float] = ..., seed: Optional[int] = ...) -> FitResult: ...
def fit_all(A: npt.ArrayLike, B: npt.ArrayLike, rank_tolerance: Optional[float] = ...,
            noise_ratio: Optional[float] = ..., max_iter: Optional[int] = ...,
            min_eig: Optional[float] = ...) -> List[FitResult]: ...
def nearest(C: npt.ArrayLike, kind: str, min_eig: Optional[float] = ..., min_eig_rel: Optional[float] = ...,
            alpha: Optional[float] = ..., weights: Optional[npt.ArrayLike] = ..., max_iter: Optional[int] = ...,
            tol: Optional[float] = ...) -> NearestResult: ...
def area_criterion(A: npt.ArrayLike, B: npt.ArrayLike, X: npt.ArrayLike) -> Optional[float]: ...
def read_matrix(path: str, *, allow_nonfinite: bool = ...) -> npt.NDArray[np.float64]: ...
def read_table(path: str) -> Tuple[npt.NDArray[np.float64], List[str]]: ...
def write_csv(path: str, X: npt.ArrayLike) -> None: ...
