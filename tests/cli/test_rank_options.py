"""Every relative rank cut-off option (fit --rank-tol, solve --threshold/--rank-tol, linkage
synthesize --threshold) follows the library's one rule and is validated in one place: a number in
[0, 1), anything else a usage error (exit 2)."""
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]

COMMANDS = {
    "fit": ["fit", "--method", "ls", "--rank-tol", "{}", "examples/paper_2x2/A.csv", "examples/paper_2x2/B.csv"],
    "solve": ["solve", "--threshold", "{}", "examples/linkage/notes_ex1_A.csv", "examples/linkage/notes_ex1_b.csv"],
    "solve-alias": ["solve", "--rank-tol", "{}", "examples/linkage/notes_ex1_A.csv",
                    "examples/linkage/notes_ex1_b.csv"],
    "linkage": ["linkage", "synthesize", "--steering", "--rho", "0.5", "--threshold", "{}"],
}


def command(name, value):
    return [arg.format(value) if arg == "{}" else arg for arg in COMMANDS[name]]


@pytest.mark.parametrize("name", sorted(COMMANDS))
@pytest.mark.parametrize("value", ["1", "1.5", "-0.1", "nan", "inf", "x"])
def test_out_of_range_cutoffs_are_usage_errors(spdfit, name, value, monkeypatch):
    monkeypatch.chdir(ROOT)
    result = spdfit(*command(name, value))
    assert result.returncode == 2, (result.returncode, result.stderr)
    assert "is not a number in [0, 1)" in result.stderr


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_a_cutoff_in_range_is_accepted(spdfit, name, monkeypatch):
    monkeypatch.chdir(ROOT)
    assert spdfit(*command(name, "0.001")).returncode == 0
