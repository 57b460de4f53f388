"""Issue 18: long runs show a progress line (percent, rate, time left) on standard error when it
is a terminal, and nothing when it is not or with -q. SPDFIT_TEST_PROGRESS_NOW=1 shows it from
the first update instead of after a second, so that short test runs exercise it."""
import os
import pty
import subprocess

import numpy as np
import pytest

from spdfit_testing import SLOWDOWN, cli_path


def run_with_terminal(args, env):
    """(stdout, what the terminal on stderr received, exit status)."""
    master, slave = pty.openpty()
    process = subprocess.Popen([cli_path(), *map(str, args)], stdout=subprocess.PIPE, stderr=slave, env=env)
    os.close(slave)
    seen = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:  # the other end closed
            break
        if not chunk:
            break
        seen += chunk
    os.close(master)
    stdout = process.stdout.read()
    return stdout, seen.decode(), process.wait()


@pytest.fixture
def files(tmp_path):
    rng = np.random.default_rng(2)
    A = rng.standard_normal((5000, 3))
    np.savetxt(tmp_path / "A.csv", A, delimiter=",")
    np.savetxt(tmp_path / "B.csv", A * 2 + 1e-3 * rng.standard_normal(A.shape), delimiter=",")
    return tmp_path


def test_a_terminal_sees_progress_and_a_pipe_does_not(files):
    env = dict(os.environ, SPDFIT_TEST_PROGRESS_NOW="1")
    args = ["fit", "--method", "ls", "--stream", "--block-rows", "500", "--bootstrap", "50", "--json",
            files / "A.csv", files / "B.csv"]
    stdout, terminal, status = run_with_terminal(args, env)
    assert status == 0
    assert "spdfit: reading A and B" in terminal and "MB/s" in terminal and "100%" in terminal
    assert "spdfit: bootstrap replicates" in terminal
    # The line is cleared before anything else is printed (here the bootstrap's warnings).
    after = terminal[terminal.rfind("spdfit: bootstrap replicates"):]
    assert "spdfit: warning" in after
    assert after.index("\r\x1b[K") < after.index("spdfit: warning")
    assert b'"X"' in stdout  # the output itself is untouched
    piped = subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True, env=env)
    assert piped.returncode == 0 and "reading A and B" not in piped.stderr
    _, quiet, _ = run_with_terminal(["-q", *args], env)
    assert "reading A and B" not in quiet


def test_short_runs_show_nothing(files):
    # Without the test switch the line waits a second: this run ends well before.
    env = {k: v for k, v in os.environ.items() if k != "SPDFIT_TEST_PROGRESS_NOW"}
    _, terminal, status = run_with_terminal(["fit", "--method", "ls", files / "A.csv", files / "B.csv"], env)
    assert status == 0 and "spdfit:" not in terminal


def test_the_experiments_show_the_same_progress_line():
    env = dict(os.environ, SPDFIT_TEST_PROGRESS_NOW="1")
    # Over 0.1 s (updates come that often): 40000 trials, fewer in the sanitizer build, which runs
    # them about SLOWDOWN times slower (40000 there took 100 s).
    trials = str(40000 // SLOWDOWN)
    args = ["experiment", "thesis", "--noise-var", "0.86", "--trials", trials, "--seed", "3"]
    stdout, terminal, status = run_with_terminal(args, env)
    assert status == 0 and b"Thesis experiment" in stdout
    assert "spdfit: experiment thesis" in terminal and "%, " in terminal and "left" in terminal
    assert terminal.endswith("\r\x1b[K")  # cleared when the trials end
    piped = subprocess.run([cli_path(), *args], capture_output=True, text=True, env=env)
    assert piped.returncode == 0 and "experiment thesis" not in piped.stderr
