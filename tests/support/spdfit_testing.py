"""What every Python test suite shares: the source tree, the CLI under test (SPDFIT_CLI, set by
ctest to the built spdfit), how much slower the sanitizer build runs it, a runner, a CSV writer,
and the `$ command` blocks of a documentation page. Each suite's conftest.py imports this module
(ctest runs every suite as its own pytest, so a conftest.py above them would not be loaded) and
keeps its own fixture names on top of it."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))

# The sanitizer build (scripts/sanitize.sh sets SPDFIT_SANITIZED=1) runs the CLI about twenty
# times slower.
SANITIZED = os.environ.get("SPDFIT_SANITIZED") == "1"
SLOWDOWN = 20 if SANITIZED else 1


def cli_path():
    """The spdfit executable named by SPDFIT_CLI; skips the calling test when it is unset and fails
    it when it is not an executable file."""
    path = os.environ.get("SPDFIT_CLI")
    if not path:
        pytest.skip("SPDFIT_CLI is not set (ctest sets it to the built spdfit)")
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        pytest.fail(f"SPDFIT_CLI={path!r} is not an executable file")
    return path


def run_cli(path, *args, timeout_s=60, cwd=None, input=None):
    """CompletedProcess of `spdfit args...` (text, both streams captured); timeout_s is scaled by
    SLOWDOWN."""
    return subprocess.run([path, *map(str, args)], capture_output=True, text=True, input=input,
                          timeout=timeout_s * SLOWDOWN, cwd=cwd)


def save_csv(path, M, header=None):
    """M written to `path` as CSV with round-trip precision (an optional header row); returns path."""
    np.savetxt(path, np.atleast_2d(M), delimiter=",", fmt="%.17g", header=header or "", comments="")
    return path


def doc_commands(page):
    """[(command, [expected output lines])] from the code blocks of the page at `page`: each
    `$ command` line starts an entry, the lines after it are its expected output, "..." elides."""
    commands, in_block = [], False
    for line in pathlib.Path(page).read_text().splitlines():
        if line.startswith("```"):
            in_block = not in_block
            continue
        if not in_block:
            continue
        if line.startswith("$ "):
            commands.append((line[2:], []))
        elif commands and line.strip() != "...":
            commands[-1][1].append(line.rstrip())
    return commands


def indefinite_covariance(n, seed, scale=1.0):
    """A covariance gone wrong, as pairwise-complete estimates are: variances (0.5 to 2)^2 times
    scale, correlations uniform in [-1, 1] (seeded), so that it is indefinite."""
    rng = np.random.default_rng(seed)
    sd = np.linspace(0.5, 2.0, n)
    R = rng.uniform(-1, 1, (n, n))
    R = (R + R.T) / 2
    np.fill_diagonal(R, 1.0)
    C = scale * sd[:, None] * R * sd[None, :]
    assert np.linalg.eigvalsh(C)[0] < 0, "the test matrix must be indefinite"
    return C


def sensor_log(seed=2024, rows=120, n=12):
    """A log of n sensors whose scales run from 1e-3 to 300 (geometric), driven by three common
    factors plus noise, where each sensor misses one stretch of 20-45% of the rows (NaN), as
    sensors that drop out do: the data behind a `df.cov()` gone indefinite. Seeded."""
    rng = np.random.default_rng(seed)
    scales = np.geomspace(1e-3, 300.0, n)
    latent = rng.standard_normal((rows, 3))
    loadings = rng.uniform(-1, 1, (3, n))
    Z = latent @ loadings + 0.5 * rng.standard_normal((rows, n))
    data = Z / Z.std(axis=0) * scales
    for j in range(n):
        length = int(rng.uniform(0.2, 0.45) * rows)
        start = rng.integers(0, rows - length)
        data[start:start + length, j] = np.nan
    return data


def pairwise_covariance(data):
    """The covariance by pairwise deletion, as pandas' DataFrame.cov() computes it: for each pair
    of columns the rows where both are present, their own means, and the divisor count - 1."""
    n = data.shape[1]
    present = ~np.isnan(data)
    C = np.empty((n, n))
    for i in range(n):
        for j in range(i + 1):
            both = present[:, i] & present[:, j]
            x, y = data[both, i], data[both, j]
            C[i, j] = C[j, i] = np.sum((x - x.mean()) * (y - y.mean())) / (both.sum() - 1)
    return C


def mpirun_environment(extra=None):
    """The environment for spdfit under mpirun in the tests: in the sanitizer build, Open MPI keeps
    its components loaded (no dlclose) and allocations get full stacks, so that LeakSanitizer can
    attribute Open MPI's allocations left at exit to its libraries, which
    scripts/lsan-suppressions.txt names (spdfit's own leaks are still reported)."""
    env = dict(os.environ, **(extra or {}))
    if SANITIZED:
        env["OMPI_MCA_mca_base_component_disable_dlclose"] = "1"
        env["ASAN_OPTIONS"] = ":".join(filter(None, [env.get("ASAN_OPTIONS", ""), "fast_unwind_on_malloc=0"]))
    return env


# ---- warnings that contradict the run (issue 45 item 1) ----------------------------------------

# What, in a warning or a report line, contradicts a method that auto chose: a bias warning about
# it, a notice that it ignores noise the model gives, or advice to use auto (which chose it).
_AGAINST_AUTO = ("is biased", "models noise in B only", "(or auto)", "use auto")
# What contradicts a noise model that the run was given: statements of the equal-noise model.
_AGAINST_MODEL = ("cannot tell A's from B's", "in every entry of A")
# Command-line options and keywords that give a noise model.
NOISE_MODEL_OPTIONS = ("--rest-a", "--noise-std-a", "--noise-cov-a", "--noise-std-b", "--noise-cov-b", "--rest-b")


def contradicting_warnings(lines, chosen_by_auto, noise_model):
    """The lines (warnings, or a report's lines) that contradict the run: with `chosen_by_auto`,
    any that calls the chosen estimator biased, says it ignores the model's noise in A or
    recommends auto; with `noise_model`, any that states the equal-noise model's view (the noise
    estimate "in every entry of A", "cannot tell A's from B's"). Rules, not a parser: a new
    warning that contradicts the run in other words needs its words here."""
    bad = []
    for line in lines:
        if chosen_by_auto and any(words in line for words in _AGAINST_AUTO):
            bad.append(line)
        elif noise_model and any(words in line for words in _AGAINST_MODEL):
            bad.append(line)
    return bad


def command_context(words):
    """(chosen_by_auto, noise_model) of a `spdfit ...` command's words."""
    method = None
    for i, word in enumerate(words):
        if word in ("--method", "-m") and i + 1 < len(words):
            method = words[i + 1]
        elif word.startswith("--method="):
            method = word.split("=", 1)[1]
    chosen_by_auto = len(words) > 1 and words[1] == "fit" and method == "auto"
    noise_model = any(word.split("=", 1)[0] in NOISE_MODEL_OPTIONS for word in words)
    return chosen_by_auto, noise_model
