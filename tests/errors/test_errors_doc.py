"""docs/errors.md stays true: every `$` command in its code blocks runs, in order, in one empty
directory, and prints the lines the page shows ("..." elides lines). `spdfit` is the built CLI;
other commands (printf, mkfifo, python3 ...) are set-up and must succeed. The exit status of a
spdfit command is what the page's contract says its output implies: 2 for an error followed by
"Run 'spdfit [COMMAND] --help' for usage.", 1 for any other error, 0 otherwise."""
import os
import re
import pathlib
import subprocess
import sys

import pytest

import spdfit_testing

DOC = spdfit_testing.SOURCE_DIR / "docs" / "errors.md"


def doc_commands():
    """[(command, [expected output lines])] from the page's code blocks; "..." elides lines."""
    return spdfit_testing.doc_commands(DOC)


def expected_status(lines):
    if any(line.startswith("spdfit: error:") for line in lines):
        usage = any(re.fullmatch(r"Run 'spdfit ([a-z]+ )?--help' for usage\.", line) for line in lines)
        return 2 if usage else 1
    return 0


def test_the_page_shows_commands():
    assert len(doc_commands()) >= 30


def test_every_command_runs_as_shown(tmp_path):
    cli = spdfit_testing.cli_path()
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "spdfit").symlink_to(cli)
    work = tmp_path / "work"
    work.mkdir()
    # The page's python3 is the one running the tests (it has numpy).
    env = dict(os.environ, PATH=f"{bin_dir}:{pathlib.Path(sys.executable).parent}:{os.environ.get('PATH', '')}")
    for command, expected in doc_commands():
        proc = subprocess.run(["bash", "-c", command], cwd=work, env=env, capture_output=True, text=True, timeout=600)
        produced = [line.rstrip() for line in (proc.stdout + proc.stderr).splitlines()]
        status = expected_status(expected) if command.startswith("spdfit ") else 0
        assert proc.returncode == status, f"{command}: exit {proc.returncode}, expected {status}\n{proc.stderr}"
        for line in expected:
            assert line in produced, f"{command}: the page shows\n{line}\nbut the command printed\n" + "\n".join(produced)
