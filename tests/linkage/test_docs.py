"""docs/linkage.md cannot go stale: every `$ spdfit ...` block in it is run again and its output
compared with the page; and examples/linkage/make_examples.py regenerates the example files."""
import re
import runpy
import shutil

import pytest

from conftest import ROOT

DOC = ROOT / "docs" / "linkage.md"
NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")
# Values this small or this large are rounding (a singular value that should be zero, its
# reciprocal as a condition number): their digits differ between machines, their regime does not.
ROUNDING_SMALL, ROUNDING_LARGE = 1e-12, 1e12


def blocks():
    text = DOC.read_text()
    found = re.findall(r"```console\n\$ (spdfit [^\n]*)\n(.*?)```", text, flags=re.S)
    assert found, "no commands in docs/linkage.md"
    return found


def same_number(shown, got):
    a, b = float(shown), float(got)
    if abs(a) < ROUNDING_SMALL and abs(b) < ROUNDING_SMALL:
        return True
    if abs(a) > ROUNDING_LARGE and abs(b) > ROUNDING_LARGE:
        return (a > 0) == (b > 0)
    # The page shows what was printed: agree to the printed digits (half a unit in the last
    # place, or a relative 1e-9 for full-precision JSON numbers).
    decimals = len(shown.split(".")[1].split("e")[0].split("E")[0]) if "." in shown else 0
    exponent = int(re.split("[eE]", shown)[1]) if re.search("[eE]", shown) else 0
    return abs(a - b) <= 0.5001 * 10.0 ** (exponent - decimals) + 1e-9 * abs(a)


@pytest.mark.parametrize("command,shown", blocks(), ids=[c for c, _ in blocks()])
def test_doc_command_output(spdfit, command, shown):
    result = spdfit(*command.split()[1:])
    assert result.returncode == 0, (command, result.stderr)
    got = result.stdout
    assert NUMBER.sub("#", got).rstrip() == NUMBER.sub("#", shown).rstrip(), command
    for a, b in zip(NUMBER.findall(shown), NUMBER.findall(got)):
        assert same_number(a, b), (command, a, b)


def test_doc_quotes_the_steering_numbers():
    text = DOC.read_text()
    for fragment in ("1.69259 | 1.66656 | 1.65662", "1.96307 | 2.20198 | 2.19607", "0.7313° | 3.0870°",
                     "0.3900° | 0.7307°", "0.454138 | 0.775682 | 0.45536"):
        assert fragment in text, fragment


def test_examples_are_what_their_generator_makes(tmp_path):
    source = ROOT / "examples" / "linkage"
    copy = tmp_path / "linkage"
    shutil.copytree(source, copy)
    for path in copy.glob("*.csv"):
        path.unlink()
    runpy.run_path(str(copy / "make_examples.py"), run_name="__main__")
    for path in source.glob("*.csv"):
        # The same text, numbers to 1e-14 relative: NumPy's cos, arccos and arctan2 may differ in
        # the last bit between CPUs (their SIMD variants), which %.16g shows.
        made, kept = (copy / path.name).read_text().splitlines(), path.read_text().splitlines()
        assert len(made) == len(kept), path
        for a, b in zip(made, kept):
            if a == b:
                continue
            fields_a, fields_b = a.split(","), b.split(",")
            assert len(fields_a) == len(fields_b), (path, a, b)
            for x, y in zip(fields_a, fields_b):
                assert x == y or abs(float(x) - float(y)) <= 1e-14 * max(abs(float(y)), 1.0), (path, a, b)
    assert sorted(p.name for p in copy.glob("*.csv")) == sorted(p.name for p in source.glob("*.csv"))
