"""Issue 19, item 1: spdfit's own kernels (the block QR every fit of fewer than 128 columns of
[A B] runs, in memory and streamed) are built for baseline x86-64, AVX2 and AVX-512 and chosen at
run time from the CPU; SPDFIT_KERNELS=baseline|avx2|avx512 narrows the choice. Every variant must
give the same bits (sums in fixed lanes, no fused multiply-adds), so a result does not depend on
the CPU it was computed on, and each must agree with NumPy's least squares."""
import json
import subprocess

import numpy as np
import pytest

from blas_core_testing import cpu_flags, environment
from spdfit_testing import SLOWDOWN, cli_path

KERNELS = "SPDFIT_KERNELS"


def variants_of_this_cpu():
    flags = cpu_flags()
    out = ["baseline"]
    if {"avx2", "fma"} <= flags:
        out.append("avx2")
        if {"avx512f", "avx512bw", "avx512vl", "avx512dq"} <= flags:
            out.append("avx512")
    return out


def run(*args, **env_changes):
    return subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True,
                          env=environment(**env_changes), timeout=120 * SLOWDOWN)


def kernel_line(result):
    lines = [line for line in result.stderr.splitlines() if "own kernels" in line]
    assert len(lines) == 1, result.stderr
    return lines[0]


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    """A and B, 70000 x 6 (three streaming blocks of 32768 rows, the last short), as .npy."""
    directory = tmp_path_factory.mktemp("kernels")
    rng = np.random.default_rng(191)
    m, n = 70000, 6
    W = rng.standard_normal((n, n))
    A = rng.standard_normal((m, n)) * np.logspace(0, -3, n)  # columns over three orders of magnitude
    B = A @ (W @ W.T + np.eye(n)) + 0.01 * rng.standard_normal((m, n))
    np.save(directory / "A.npy", A)
    np.save(directory / "B.npy", B)
    return directory / "A.npy", directory / "B.npy", A, B


@pytest.mark.parametrize("stream", [False, True], ids=["in_memory", "streamed"])
def test_every_variant_gives_the_same_bits(data, stream):
    a_path, b_path, A, B = data
    options = ["--stream"] if stream else []
    outputs = {}
    for variant in variants_of_this_cpu():
        result = run("fit", "--method", "ls", "--json", *options, a_path, b_path, **{KERNELS: variant})
        assert result.returncode == 0, result.stderr
        outputs[variant] = result.stdout
        X = np.array(json.loads(result.stdout)["X"])
        reference = np.linalg.lstsq(A, B, rcond=None)[0]
        # The data's condition number is about 1e3: least squares to about cond * eps, with room.
        assert np.linalg.norm(X - reference) <= 1e-11 * np.linalg.norm(reference), variant
    assert len(set(outputs.values())) == 1, {k: v[:200] for k, v in outputs.items()}


def test_verbose_names_the_kernels(data):
    fit = ["fit", "--method", "ls", data[0], data[1]]
    widest = variants_of_this_cpu()[-1]
    result = run("--verbose", *fit, **{KERNELS: None})
    assert kernel_line(result) == f"spdfit: own kernels (the block QR): {widest} (the CPU's widest)"
    chosen = run("-v", *fit, **{KERNELS: "baseline"})
    assert kernel_line(chosen) == "spdfit: own kernels (the block QR): baseline (SPDFIT_KERNELS=baseline)"


def test_an_unknown_or_too_wide_choice_is_not_taken(data):
    fit = ["fit", "--method", "ls", data[0], data[1]]
    widest = variants_of_this_cpu()[-1]
    result = run("-v", *fit, **{KERNELS: "sse9"})
    assert result.returncode == 0, result.stderr
    assert kernel_line(result) == (f"spdfit: own kernels (the block QR): {widest} (the CPU's widest; "
                                   "SPDFIT_KERNELS=sse9 is not one of baseline, avx2, avx512, and is ignored)")
    if widest != "avx512":
        result = run("-v", *fit, **{KERNELS: "avx512"})
        assert kernel_line(result) == (f"spdfit: own kernels (the block QR): {widest} (the CPU's widest; "
                                       "SPDFIT_KERNELS=avx512 asks for more than the CPU has)")


def test_a_choice_not_taken_is_warned_about_without_verbose(data):
    fit = ["fit", "--method", "ls", data[0], data[1]]
    widest = variants_of_this_cpu()[-1]
    result = run(*fit, **{KERNELS: "fast"})
    assert result.returncode == 0, result.stderr
    assert result.stderr == (f"spdfit: warning: SPDFIT_KERNELS=fast is not one of baseline, avx2, avx512: "
                             f"ignored, spdfit's kernels run on {widest}, the CPU's widest\n")
    assert run(*fit, **{KERNELS: "baseline"}).stderr == ""


def test_case_and_blanks_are_ignored(data):
    fit = ["fit", "--method", "ls", data[0], data[1]]
    result = run("-v", *fit, **{KERNELS: " Baseline "})
    assert result.returncode == 0, result.stderr
    assert kernel_line(result) == "spdfit: own kernels (the block QR): baseline (SPDFIT_KERNELS= Baseline )"
    assert "warning" not in result.stderr
