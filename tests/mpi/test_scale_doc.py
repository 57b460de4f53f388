"""docs/scale.md's examples run as shown: each `$ mpirun -n K spdfit ...` command, in a scratch
directory in which `examples` is the repository's examples folder, prints the lines the page shows
(in any order; `...` elides) with exit status 0."""
import os
import pathlib
import shlex
import shutil
import subprocess
import sys

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "support"))

from spdfit_testing import SLOWDOWN, cli_path, doc_commands, mpirun_environment  # noqa: E402

ROOT = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
MPIRUN = shutil.which("mpirun")


def examples():
    return doc_commands(ROOT / "docs/scale.md")


def test_the_page_has_examples():
    assert examples()


@pytest.mark.skipif(MPIRUN is None, reason="no mpirun (Debian: openmpi-bin)")
@pytest.mark.parametrize("command,expected", examples(), ids=[e[0] for e in examples()])
def test_console_example(tmp_path, command, expected):
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    words = shlex.split(command)
    assert words[0] == "mpirun" and "spdfit" in words, command
    at = words.index("spdfit")
    launcher = [MPIRUN, "--oversubscribe"] + (["--allow-run-as-root"] if os.geteuid() == 0 else []) + words[1:at]
    result = subprocess.run(launcher + [cli_path(), *words[at + 1:]], cwd=tmp_path, capture_output=True, text=True,
                            timeout=120 * SLOWDOWN, env=mpirun_environment())
    assert result.returncode == 0, f"{command}\n{result.stderr}"
    printed = {line.rstrip() for line in (result.stdout + result.stderr).splitlines()}
    for line in expected:
        assert line in printed, f"{command}\nthe page shows\n{line}\nbut the command printed\n{result.stdout}"
