"""Run once, on the package's first import: a SpdfitWarning when OpenBLAS runs generic kernels on
a CPU that has faster ones (Debian 12's OpenBLAS 0.3.21 does not know some recent CPUs).

OpenBLAS chooses its kernels when it loads, which NumPy has done before spdfit is imported, so the
module cannot fix the choice as the command line does (it restarts itself with OPENBLAS_CORETYPE
set): the remedy is the user's, before Python starts. The rule is the library's
(src/numerics/blas_core.hpp), shared with the command line. Imported by __init__.py after
SpdfitWarning is defined."""
import warnings as _warnings

from . import _spdfit
from ._errors import SpdfitWarning

_check = _spdfit.blas_core()
if _check["suggested"]:
    # stacklevel 3: past this module and the package's __init__ to the user's import statement.
    _warnings.warn(f"OpenBLAS runs its generic '{_check['reported']}' kernels on this CPU, which has "
                   f"{_check['cpu']}: NumPy's and spdfit's matrix products and factorizations run up to "
                   f"four times slower than they can. Choose the kernels before starting Python: "
                   f"export OPENBLAS_CORETYPE={_check['suggested']}", SpdfitWarning, stacklevel=3)
