"""Type stubs for spdfit.experiment (see experiment.py for the documentation)."""
from typing import Dict, Iterable, List, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

Array = npt.NDArray[np.float64]

THESIS_NOISE_VARIANCES: Tuple[float, float, float]
THESIS_REPORTED: Dict[int, Tuple[float, float, float, float]]

class Summary:
    count: int
    failures: int
    mean: float
    std: float
    median: float
    min: float
    max: float
    standard_error: float

class MethodErrors:
    method: str
    errors: Array
    summary: Summary

class ThesisExperimentResult:
    trials: int
    seed: int
    methods: List[MethodErrors]
    truth: Array

class EntryStatistics:
    method: str
    count: int
    failures: int
    mae: Array
    std: Array
    bias: Array
    errors: Array

class EntryExperimentResult:
    trials: int
    seed: int
    truth: Array
    entries: List[Tuple[int, int]]
    methods: List[EntryStatistics]

def thesis(noise_var: float, *, samples: int = ..., trials: int = ..., seed: int = ..., threads: int = ...,
           force_noise_var: Optional[float] = ..., signal_var: float = ..., distribution: str = ...,
           truth: Optional[npt.ArrayLike] = ..., methods: Optional[Sequence[str]] = ...) -> ThesisExperimentResult: ...
def paper_hexapod(*, noise_var: float = ..., samples: int = ..., trials: int = ..., seed: int = ...,
                  threads: int = ..., methods: Optional[Sequence[str]] = ...) -> EntryExperimentResult: ...
def paper_2x2(std_a: float, *, std_b: float = ..., trials: int = ..., seed: int = ...,
              threads: int = ..., methods: Optional[Sequence[str]] = ...) -> EntryExperimentResult: ...
def paper_2x2_sweep(levels: Optional[Iterable[float]] = ..., *, std_b: float = ..., trials: int = ...,
                    seed: int = ..., threads: int = ...,
                    methods: Optional[Sequence[str]] = ...) -> List[Tuple[float, EntryExperimentResult]]: ...
