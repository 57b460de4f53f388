"""Issue 19, item 1: when OpenBLAS runs kernels without AVX2 on a CPU that has AVX2 or AVX-512 and
the user has not set OPENBLAS_CORETYPE, spdfit restarts itself once with OPENBLAS_CORETYPE naming
the CPU's kernels, and says so under --verbose. SPDFIT_TEST_BLAS_CORE=Prescott makes spdfit take
OpenBLAS for having reported "Prescott", so the restart runs on any CPU with AVX2; the restarted
process reports the core OpenBLAS really chose (openblas_get_corename()), which shows that the
variable reached it. SPDFIT_TEST_BLAS_EXE replaces /proc/self/exe as the program restarted."""
import subprocess

import numpy as np
import pytest

from blas_core_testing import GENERIC_CORES, cpu_flags, environment, expected_choice, openblas_core
from spdfit_testing import SLOWDOWN, cli_path


def run(*args, **env_changes):
    """CompletedProcess of `spdfit args...` in environment(**env_changes)."""
    return subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True,
                          env=environment(**env_changes), timeout=60 * SLOWDOWN)


@pytest.fixture(scope="module")
def fit_args(tmp_path_factory):
    """The arguments of a fit at n = 70 (m = 280), which runs LAPACK's QR (from 128 columns of
    [A B] on) and SVDs (above 64 columns, docs/performance.md) and so the BLAS."""
    directory = tmp_path_factory.mktemp("blas_core")
    rng = np.random.default_rng(19)
    n, m = 70, 280
    A = rng.standard_normal((m, n))
    W = rng.standard_normal((n, n))
    np.save(directory / "A.npy", A)
    np.save(directory / "B.npy", A @ (W @ W.T / n + np.eye(n)) + 0.01 * rng.standard_normal((m, n)))
    return ["fit", "--method", "spde", directory / "A.npy", directory / "B.npy"]


@pytest.fixture(scope="module", autouse=True)
def built_with_openblas():
    """Skips the module when spdfit does not run on OpenBLAS (SPDFIT_LAPACK off)."""
    result = run("-v", "demo", "--help")
    if "not OpenBLAS" in result.stderr:
        pytest.skip("spdfit was built without OpenBLAS: no kernels to choose")


def verbose_lines(result):
    return [line for line in result.stderr.splitlines() if "OpenBLAS" in line]


def test_a_generic_core_restarts_with_the_cpus_core(fit_args):
    extension, core = expected_choice()
    result = run("--verbose", *fit_args, SPDFIT_TEST_BLAS_CORE="Prescott")
    assert result.returncode == 0, result.stderr
    # "core now" is openblas_get_corename() in the restarted process: OpenBLAS saw the variable.
    assert verbose_lines(result) == [f"spdfit: OpenBLAS reported core 'Prescott' on a CPU with {extension}: "
                                     f"restarted with OPENBLAS_CORETYPE={core} (OpenBLAS core now: {core})"]


@pytest.mark.parametrize("generic", GENERIC_CORES[1:] + ("prescott",))
def test_every_generic_core_is_replaced(fit_args, generic):
    _, core = expected_choice()
    result = run("-v", *fit_args, SPDFIT_TEST_BLAS_CORE=generic)
    assert result.returncode == 0, result.stderr
    assert f"restarted with OPENBLAS_CORETYPE={core} (OpenBLAS core now: {core})" in result.stderr


def test_the_restarted_result_is_the_chosen_cores(fit_args):
    _, core = expected_choice()
    restarted = run(*fit_args, SPDFIT_TEST_BLAS_CORE="Prescott")
    chosen_by_user = run(*fit_args, OPENBLAS_CORETYPE=core)
    assert restarted.returncode == 0 and chosen_by_user.returncode == 0, restarted.stderr + chosen_by_user.stderr
    assert restarted.stdout == chosen_by_user.stdout
    assert restarted.stderr == chosen_by_user.stderr == ""  # the restart is silent without --verbose


def test_a_users_coretype_is_kept(fit_args):
    """Even a generic one: OPENBLAS_CORETYPE=Prescott runs Prescott (any x86-64 CPU can)."""
    result = run(*fit_args, "-v", SPDFIT_TEST_BLAS_CORE="Nehalem", OPENBLAS_CORETYPE="Prescott")
    assert result.returncode == 0, result.stderr
    assert verbose_lines(result) == ["spdfit: OpenBLAS core: Prescott (OPENBLAS_CORETYPE=Prescott, set before "
                                     "spdfit ran); SPDFIT_TEST_BLAS_CORE=Nehalem is set"]


def test_an_empty_coretype_is_no_choice(fit_args):
    """OpenBLAS ignores OPENBLAS_CORETYPE="" and so does spdfit."""
    _, core = expected_choice()
    result = run("-v", *fit_args, SPDFIT_TEST_BLAS_CORE="Prescott", OPENBLAS_CORETYPE="")
    assert f"restarted with OPENBLAS_CORETYPE={core}" in result.stderr


def test_verbose_names_openblass_own_choice(fit_args):
    env = environment()
    core = openblas_core(env)
    result = run("-v", *fit_args)
    assert result.returncode == 0, result.stderr
    if core in GENERIC_CORES and {"avx2", "fma"} <= cpu_flags():
        assert "restarted with OPENBLAS_CORETYPE=" in result.stderr  # this machine needs the restart
    else:
        assert verbose_lines(result) == [f"spdfit: OpenBLAS core: {core} (chosen by OpenBLAS)"]


@pytest.mark.parametrize("switch", ["Haswell", "SkylakeX", "Zen", "NoSuchCore", "Prescott2", " ", "\u00e9" * 300])
def test_other_cores_are_left_alone(fit_args, switch):
    result = run("-v", *fit_args, SPDFIT_TEST_BLAS_CORE=switch)
    assert result.returncode == 0, result.stderr
    assert "restarted" not in result.stderr
    assert "(chosen by OpenBLAS)" in result.stderr


@pytest.mark.parametrize("program", ["missing", "not_executable"])
def test_a_failed_restart_runs_on(fit_args, tmp_path, program):
    _, core = expected_choice()
    path = tmp_path / program
    if program == "not_executable":
        path.write_text("#!/bin/sh\nexit 3\n")
    plain = run(*fit_args)
    failed = run(*fit_args, SPDFIT_TEST_BLAS_CORE="Prescott", SPDFIT_TEST_BLAS_EXE=str(path))
    assert failed.returncode == 0, failed.stderr
    assert failed.stdout == plain.stdout  # the kernels OpenBLAS chose, in the environment as it was
    assert failed.stderr.startswith("spdfit: warning: OpenBLAS runs its generic 'Prescott' kernels")
    assert f"restarting with OPENBLAS_CORETYPE={core} failed ({path}: " in failed.stderr
    assert f"Set OPENBLAS_CORETYPE={core} before running spdfit" in failed.stderr
    quiet = run("-q", *fit_args, SPDFIT_TEST_BLAS_CORE="Prescott", SPDFIT_TEST_BLAS_EXE=str(path))
    assert quiet.returncode == 0 and quiet.stderr == ""
    verbose = run("-v", *fit_args, SPDFIT_TEST_BLAS_CORE="Prescott", SPDFIT_TEST_BLAS_EXE=str(path))
    real = openblas_core(environment())
    assert f"spdfit: OpenBLAS core: {real} (it reported 'Prescott'" in verbose.stderr


def test_the_restart_happens_once(fit_args, tmp_path):
    """A program between the two runs takes OPENBLAS_CORETYPE away again: without the marker
    variable the restarted spdfit would restart once more, and so on."""
    expected_choice()
    count = tmp_path / "count"
    wrapper = tmp_path / "wrapper"
    wrapper.write_text(f'#!/bin/sh\necho run >> "{count}"\nunset OPENBLAS_CORETYPE\nexec "{cli_path()}" "$@"\n')
    wrapper.chmod(0o755)
    result = run("-v", *fit_args, SPDFIT_TEST_BLAS_CORE="Prescott", SPDFIT_TEST_BLAS_EXE=str(wrapper))
    assert result.returncode == 0, result.stderr
    assert count.read_text() == "run\n"
    # The restarted process found no OPENBLAS_CORETYPE, so OpenBLAS chose by itself.
    assert verbose_lines(result) == [f"spdfit: OpenBLAS core: {openblas_core(environment())} (chosen by OpenBLAS); "
                                     "SPDFIT_TEST_BLAS_CORE=Prescott is set"]


@pytest.mark.parametrize("marker", ["", ":", "junk", "Prescott:", ":Haswell", "x" * 100000 + ":y"])
def test_a_stray_marker_stops_the_restart(fit_args, marker):
    result = run("-v", *fit_args, SPDFIT_TEST_BLAS_CORE="Prescott", SPDFIT_BLAS_REEXEC=marker)
    assert result.returncode == 0, result.stderr
    assert "restarted" not in result.stderr and "(chosen by OpenBLAS)" in result.stderr


def test_quiet_and_verbose_exclude_each_other(fit_args):
    result = run("-q", *fit_args, "--verbose")
    assert result.returncode == 2
    assert "--quiet excludes --verbose" in result.stderr
    assert result.stdout == ""


def test_without_verbose_nothing_is_said(fit_args):
    result = run(*fit_args)
    assert result.returncode == 0 and result.stderr == ""
