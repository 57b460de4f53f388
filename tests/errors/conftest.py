"""Fixtures for the hostile-file tests: the spdfit CLI (SPDFIT_CLI) run with limits on time and
memory, and the evidence of how it ended (exit status, messages, seconds, peak memory)."""
import dataclasses
import os
import pathlib
import resource
import signal
import subprocess
import sys
import tempfile
import time

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "support"))
# The sanitizer build (SPDFIT_SANITIZED=1) runs an unoptimized, instrumented CLI (the reader of a
# 32 MB line took 8.6 s of CPU there, well under 1 s in the plain build), and AddressSanitizer
# reserves terabytes of address space and keeps freed memory in quarantine: there the time budget
# is left to the plain build (only a hang fails) and memory is measured against a larger bound
# instead of capped with RLIMIT_AS.
from spdfit_testing import SANITIZED, cli_path  # noqa: E402

# Issue 7: each hostile file gets a clear error within a second and bounded memory. The second is
# CPU time (user + system) of the CLI, which other jobs on a busy CI machine do not inflate.
TIME_LIMIT_S = None if SANITIZED else 1.0
# Bounded memory: the reader holds the file's bytes plus at most a few times as much again, and
# the biggest file here is 32 MB; the CLI itself needs about 10 MB.
MEMORY_LIMIT_MB = 1024 if SANITIZED else 256
# A run that has not ended by then is killed and fails the test: a hang.
HANG_S = 60


@dataclasses.dataclass
class Run:
    returncode: int
    stdout: str
    stderr: str
    seconds: float  # CPU time
    wall_seconds: float
    peak_mb: float


def _limit_memory():
    if not SANITIZED:
        limit = MEMORY_LIMIT_MB * 1024 * 1024
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))


@pytest.fixture(scope="session")
def cli():
    return cli_path()


@pytest.fixture(scope="session")
def run(cli):
    """run(*args, user=None) -> Run: spdfit with args, under the memory limit, with its CPU time and
    peak resident memory taken from wait4. user: a uid to run as (for unreadable files as root)."""

    def run(*args, user=None):
        def preexec():
            _limit_memory()
            if user is not None:
                os.setgroups([])
                os.setgid(user)
                os.setuid(user)

        with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
            start = time.monotonic()
            # OpenBLAS (spdfit's LAPACK) reserves about 136 MB of address space per worker thread
            # when the program starts, which RLIMIT_AS counts although nothing touches it. No
            # hostile file gets as far as LAPACK, so its workers are turned off here, and the
            # limit bounds what spdfit itself maps.
            env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
            proc = subprocess.Popen([cli, *map(str, args)], stdin=subprocess.DEVNULL, stdout=out, stderr=err,
                                    preexec_fn=preexec, env=env)
            while True:
                pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
                if pid:
                    break
                if time.monotonic() - start > HANG_S:
                    os.kill(proc.pid, signal.SIGKILL)
                    os.wait4(proc.pid, 0)
                    proc.returncode = -9
                    pytest.fail(f"spdfit {' '.join(map(str, args))} hangs (killed after {HANG_S} s)")
                time.sleep(0.002)
            wall_seconds = time.monotonic() - start
            proc.returncode = os.waitstatus_to_exitcode(status)
            out.seek(0)
            err.seek(0)
            return Run(proc.returncode, out.read().decode("utf-8", "replace"), err.read().decode("utf-8", "replace"),
                       usage.ru_utime + usage.ru_stime, wall_seconds, usage.ru_maxrss / 1024.0)

    return run


@pytest.fixture
def rejects(run):
    """rejects(args, path, *fragments): spdfit exits 1 within the time limit and memory bound, with one
    line 'spdfit: error: PATH...' on stderr holding every fragment, and nothing on stdout."""

    def rejects(args, path, *fragments, user=None):
        r = run(*args, user=user)
        command = "spdfit " + " ".join(map(str, args))
        assert r.returncode == 1, f"{command}: exit {r.returncode}\n{r.stderr}"
        assert r.stdout == "", command
        assert r.stderr.startswith(f"spdfit: error: {path}"), f"{command}: {r.stderr}"
        assert r.stderr.count("\n") == 1, f"{command}: more than one line on stderr:\n{r.stderr[:2000]}"
        for fragment in fragments:
            assert fragment in r.stderr, f"{command}: no {fragment!r} in {r.stderr}"
        assert len(r.stderr) < 1000, f"{command}: a {len(r.stderr)}-character message"
        if TIME_LIMIT_S is not None:
            assert r.seconds < TIME_LIMIT_S, f"{command}: {r.seconds:.2f} s of CPU time"
        assert r.peak_mb < MEMORY_LIMIT_MB, f"{command}: {r.peak_mb:.0f} MB"
        return r

    return rejects
