"""Issue 19, item 1, in Python: NumPy has loaded OpenBLAS before spdfit is imported, so the module
cannot choose the kernels as the CLI does (tests/cli/test_blas_core.py); when OpenBLAS runs a core
without AVX2 on a CPU with AVX2 or AVX-512 and OPENBLAS_CORETYPE is unset, `import spdfit` warns
once (SpdfitWarning) with the remedy. Each case imports spdfit in a fresh interpreter;
SPDFIT_TEST_BLAS_CORE makes spdfit take OpenBLAS for having reported a generic core."""
import json
import subprocess
import sys

import pytest

import spdfit
from blas_core_testing import GENERIC_CORES, cpu_flags, environment, expected_choice, openblas_core

# Imports spdfit (twice, and reloads it) recording every warning; prints them and blas_core().
IMPORT_SCRIPT = """
import importlib, json, warnings
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    import spdfit
    import spdfit as again
    importlib.reload(spdfit)
print(json.dumps({"warnings": [[w.category.__name__, str(w.message), w.filename] for w in caught],
                  "check": spdfit._spdfit.blas_core()}))
"""


def import_spdfit(**env_changes):
    """(the warnings `import spdfit` gave as [category, message, file], blas_core()) in a fresh
    interpreter with environment(**env_changes)."""
    result = subprocess.run([sys.executable, "-c", IMPORT_SCRIPT], env=environment(**env_changes),
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    output = json.loads(result.stdout)
    return output["warnings"], output["check"]


@pytest.fixture(scope="module", autouse=True)
def built_with_openblas():
    if not spdfit._spdfit.blas_core()["core"]:
        pytest.skip("spdfit was built without OpenBLAS: no kernels to choose")


def test_a_generic_core_warns_once_with_the_remedy():
    extension, core = expected_choice()
    caught, check = import_spdfit(SPDFIT_TEST_BLAS_CORE="Prescott")
    assert caught == [["SpdfitWarning", f"OpenBLAS runs its generic 'Prescott' kernels on this CPU, which has "
                       f"{extension}: NumPy's and spdfit's matrix products and factorizations run up to four "
                       f"times slower than they can. Choose the kernels before starting Python: "
                       f"export OPENBLAS_CORETYPE={core}",
                       "<string>"]]  # the user's import statement, not spdfit's own files
    assert check["reported"] == "Prescott" and check["from_test_switch"]
    assert check["cpu"] == extension and check["suggested"] == core


def test_the_remedy_works():
    """With the variable the warning names, OpenBLAS runs that core and the import is silent."""
    _, core = expected_choice()
    caught, check = import_spdfit(OPENBLAS_CORETYPE=core)
    assert caught == [] and check["core"] == core and check["user_coretype"] == core


def test_a_users_coretype_is_kept_and_silences_the_warning():
    """Even a generic one: the user chose it (any x86-64 CPU runs Prescott's kernels)."""
    caught, check = import_spdfit(SPDFIT_TEST_BLAS_CORE="Nehalem", OPENBLAS_CORETYPE="Prescott")
    assert caught == []
    assert check["core"] == "Prescott" and check["user_coretype"] == "Prescott" and check["suggested"] == ""


def test_the_core_is_openblass_own_choice():
    env = environment()
    caught, check = import_spdfit()
    core = openblas_core(env)
    assert check["core"] == check["reported"] == core and not check["from_test_switch"]
    needed = core in GENERIC_CORES and {"avx2", "fma"} <= cpu_flags()
    assert len(caught) == (1 if needed else 0), caught


@pytest.mark.parametrize("switch", ["Haswell", "SkylakeX", "NoSuchCore", " ", "\u00e9" * 300])
def test_other_cores_are_left_alone(switch):
    caught, check = import_spdfit(SPDFIT_TEST_BLAS_CORE=switch)
    assert caught == [] and check["suggested"] == ""
    assert check["reported"] == switch
