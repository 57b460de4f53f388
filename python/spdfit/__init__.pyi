"""Type stubs for spdfit (see __init__.py for the documentation)."""
from typing import Tuple

from . import experiment as experiment
from . import hexapod as hexapod
from . import linkage as linkage
from . import payload as payload
from . import physical as physical
from . import factor as factor
from . import repair as repair
from .repair import nearest_covariance as nearest_covariance
from .factor import Factor as Factor
from ._errors import DataError as DataError, NumericalError as NumericalError, SpdfitWarning as SpdfitWarning
from ._spdfit import (AutoReason as AutoReason, PsdCertificate as PsdCertificate, BoundaryCertificate as BoundaryCertificate,
                      Diagnostics as Diagnostics, FitResult as FitResult,
                      LinearSystemResult as LinearSystemResult, NearestResult as NearestResult, NoiseModel as NoiseModel,
                      Bootstrap as Bootstrap, Interval as Interval, SpectrumUncertainty as SpectrumUncertainty)

from . import fitting as fitting
from . import io as io
from . import linear_system as linear_system
from .fitting import (area_criterion as area_criterion, auto_fit as auto_fit, fit as fit, fit_all as fit_all,
                      fit_files as fit_files, least_squares as least_squares, psd_least_squares as psd_least_squares,
                      spde as spde, spd_total_least_squares as spd_total_least_squares,
                      symmetric_procrustes as symmetric_procrustes, total_least_squares as total_least_squares,
                      total_least_squares_psd as total_least_squares_psd,
                      total_least_squares_symmetric as total_least_squares_symmetric)
from .io import read_matrix as read_matrix, read_table as read_table, write_csv as write_csv
from .linear_system import solve as solve
from .repair import (REPAIR_FLOOR_DEFAULT as REPAIR_FLOOR_DEFAULT, nearest_correlation as nearest_correlation,
                     nearest_spd as nearest_spd)
from ._errors import outcome_codes as outcome_codes

NearestSpdResult = NearestResult
NearestCorrelationResult = NearestResult

__version__: str
METHODS: Tuple[str, ...]

# warning classes: from ._errors import {} as {}
