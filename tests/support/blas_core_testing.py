"""What the CLI's and the module's BLAS-core tests share (issue 19, item 1): what this CPU offers,
read from /proc/cpuinfo (independently of spdfit's CPUID check), the OPENBLAS_CORETYPE spdfit
should then choose, and an environment without the variables that steer the choice."""
import os
import pathlib
import subprocess
import sys

import pytest

# Every variable the choice reads or sets: OpenBLAS's, the restart marker and the test switches.
STEERING = ("OPENBLAS_CORETYPE", "OPENBLAS_VERBOSE", "SPDFIT_BLAS_REEXEC", "SPDFIT_TEST_BLAS_CORE",
            "SPDFIT_TEST_BLAS_EXE")

# OpenBLAS 0.3.21's x86-64 cores without AVX2 kernels; the switch's usual value is the first.
GENERIC_CORES = ("Prescott", "Nehalem", "Core2", "Sandybridge", "Barcelona", "Atom", "Katmai")


def cpu_flags():
    """The flags of the first processor in /proc/cpuinfo (empty when there is none)."""
    try:
        text = pathlib.Path("/proc/cpuinfo").read_text()
    except OSError:
        return set()
    for line in text.splitlines():
        if line.startswith("flags"):
            return set(line.split(":", 1)[1].split())
    return set()


def expected_choice():
    """(vector extension, OPENBLAS_CORETYPE) spdfit should choose on this CPU: ("AVX-512",
    "SkylakeX") with AVX-512 F, BW, VL and DQ, ("AVX2", "Haswell") with AVX2 and FMA; skips the
    calling test on a CPU with neither, where there is nothing to choose."""
    flags = cpu_flags()
    if not {"avx2", "fma"} <= flags:
        pytest.skip("this CPU has no AVX2: spdfit keeps OpenBLAS's choice")
    if {"avx512f", "avx512bw", "avx512vl", "avx512dq"} <= flags:
        return "AVX-512", "SkylakeX"
    return "AVX2", "Haswell"


def environment(**changes):
    """os.environ without STEERING, then `changes` (a value of None removes the variable)."""
    env = {key: value for key, value in os.environ.items() if key not in STEERING}
    for key, value in changes.items():
        if value is None:
            env.pop(key, None)
        else:
            env[key] = value
    return env


def openblas_core(env):
    """OpenBLAS's own name for the kernels it chooses in environment `env`, asked through ctypes in
    a fresh Python (not through spdfit); skips the calling test when OpenBLAS cannot be loaded."""
    code = ("import ctypes, ctypes.util\n"
            "lib = ctypes.CDLL(ctypes.util.find_library('openblas') or 'libopenblas.so.0')\n"
            "lib.openblas_get_corename.restype = ctypes.c_char_p\n"
            "print(lib.openblas_get_corename().decode())\n")
    result = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=60)
    if result.returncode != 0:
        pytest.skip(f"OpenBLAS cannot be loaded here: {result.stderr.strip()}")
    return result.stdout.strip()
