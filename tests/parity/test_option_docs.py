"""The reference documents every option: each option that `spdfit COMMAND --help` lists (the CLI
registers whole library tables, so --help is the tables' list) is named in docs/cli.md or in the
command's own page. Adding an option to a table without documenting it fails here."""

import os
import re
import subprocess
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("SPDFIT_SOURCE_DIR", Path(__file__).resolve().parents[2]))
CLI = os.environ.get("SPDFIT_CLI")

# Each command with a library option table, and the pages that document it.
COMMANDS = {
    ("fit",): ["cli.md"],
    ("compare",): ["cli.md", "guide.md"],
    ("nearest",): ["cli.md"],
    ("solve",): ["cli.md", "linkage.md"],
    ("hexapod", "identify"): ["cli.md", "hexapod.md"],
}


def help_options(command):
    run = subprocess.run([CLI, *command, "--help"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    options = set()
    for line in run.stdout.splitlines():
        m = re.match(r"^  (?:-\w,)?(--[a-z0-9][a-z0-9-]*)", line)
        if m and m.group(1) != "--help":
            options.add(m.group(1))
    return options


@pytest.mark.skipif(not CLI, reason="SPDFIT_CLI is not set")
@pytest.mark.parametrize("command", list(COMMANDS), ids=" ".join)
def test_every_option_is_documented(command):
    options = help_options(command)
    assert len(options) >= 2, f"{' '.join(command)} --help lists {options}"
    text = "\n".join((SOURCE / "docs" / page).read_text() for page in COMMANDS[command])
    missing = sorted(o for o in options if not re.search(re.escape(o) + r"(?![a-z0-9-])", text))
    assert not missing, f"spdfit {' '.join(command)}: options not in docs/{', docs/'.join(COMMANDS[command])}: {missing}"
