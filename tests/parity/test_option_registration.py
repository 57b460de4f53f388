"""Every option a user can give is an entry of a library option table (CONTRIBUTING.md, "Adding an
option"): the CLI registers whole tables (apps/spdfit/table_options.hpp), Python passes **options
through the tables (python/src/keywords.cpp), MATLAB reads its name-value pairs through them
(matlab/src/mex_pairs.hpp). This test fails when a front end registers an option by hand.

What is still registered by hand is listed below (Python's keywords that are data or Python's own
forms: arrays by name, a DataFrame's columns, the readers' options), so that the
list can only shrink: a new hand-registered option, in any file, fails the test; so does an entry
of the list that is no longer true (convert a function, then delete its line)."""

import ast
import os
import re
from pathlib import Path

SOURCE = Path(os.environ.get("SPDFIT_SOURCE_DIR", Path(__file__).resolve().parents[2]))

# apps/: CLI11 registrations per file. table_options.hpp is the one place that registers table
# entries, the global options' too (global_option_table); only --version is CLI11's own.
CLI_BY_HAND = {
    "apps/spdfit/table_options.hpp": 2,  # the table's entries: add_flag / add_option per spec
}

# python/spdfit/: keyword-only parameters of public functions. Options from a table arrive in
# **options; the keywords below are the readers' and structural ones (full_output, a_cols) and data
# given by name.
PYTHON_BY_HAND = {
    ("io.py", "read_matrix"): {"allow_nonfinite", "index_col", "header"},
    ("io.py", "read_table"): {"allow_nonfinite", "index_col", "header"},
    # a_cols and b_cols of a DataFrame (labels, slices, positions: Python's own forms), as fit takes them.
    ("fitting.py", "fit"): {"a_cols", "b_cols"},
    ("fitting.py", "fit_all"): {"a_cols", "b_cols"},
    ("factor.py", "from_data"): {"a_cols", "b_cols"},
    ("repair.py", "nearest_spd"): {"full_output"},
    ("repair.py", "nearest_correlation"): {"full_output"},
    ("linear_system.py", "solve"): {"threshold"},
    # The truth as an array: the command line's thesis experiment has none.
    ("experiment.py", "thesis"): {"truth"},
    ("factor.py", "from_files"): {"block_rows", "threads"},
    ("factor.py", "fit"): {"bootstrap"},
    ("hexapod.py", "simulate"): {"truth"},
    ("hexapod.py", "identify"): {"a_cols", "b_cols", "truth", "stiffness", "geometry", "physical"},
    # Every angle in radians (the command line's --radians is the pairs file's alone).
    ("linkage.py", "synthesize"): {"radians"},
    ("linkage.py", "analyze"): {"radians"},
    ("physical.py", "identify"): {"a_cols", "b_cols", "strut_masses"},
    ("physical.py", "mass_matrix"): {"mass", "center_of_mass", "inertia"},
    ("physical.py", "inertia_repair_urdf"): {"source"},
    ("physical.py", "regress"): {"noise_cov", "prior"},
    ("repair.py", "nearest_covariance"): {"full_output"},
    # The payload's signals are data (as A and B are), given by name: not options.
    ("payload.py", "identify"): {"accel", "alpha", "gravity_in_sensor", "omega", "quaternion", "rotation",
                                 "specific_force", "time", "wrench"},
    ("payload.py", "design"): {"gravity_in_sensor", "quaternion", "rotation"},
}

# matlab/src/: names compared outside mex_pairs.hpp's set_pairs. The gateway reads the payload's
# signals and regress's NoiseCov (data arrays given as pairs) by name.
MATLAB_BY_HAND = {"matlab/src/mex_gateway.cpp": 2}


# What a hand registration looks like in each front end (the tests below and their self-check).
CLI_PATTERN = re.compile(r"\badd_(?:option|flag|flag_callback|flag_function)\s*\(")
MATLAB_PATTERN = re.compile(r"\bsame_name\s*\(|\bstrcmpi?\s*\(|inputParser|\bvalidatestring\s*\(")


def keyword_only(source):
    """(function name, its keyword-only parameters) of each public function defined in `source`."""
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.FunctionDef) and not node.name.startswith("_") and node.args.kwonlyargs:
            yield node.name, {a.arg for a in node.args.kwonlyargs}


def cli_registrations():
    found = {}
    for path in sorted((SOURCE / "apps").rglob("*.[ch]pp")):
        count = len(CLI_PATTERN.findall(path.read_text()))
        if count:
            found[path.relative_to(SOURCE).as_posix()] = count
    return found


def python_keywords():
    found = {}
    for path in sorted((SOURCE / "python" / "spdfit").glob("*.py")):
        for name, keywords in keyword_only(path.read_text()):
            found[(path.name, name)] = keywords
    return found


def test_the_cli_registers_options_only_through_tables():
    found = cli_registrations()
    grown = {f: n for f, n in found.items() if n > CLI_BY_HAND.get(f, 0)}
    assert not grown, (f"options registered by hand in apps/ (file: count, allowed {CLI_BY_HAND}): {grown}; "
                       "add them to a library option table instead")
    shrunk = {f: n for f, n in CLI_BY_HAND.items() if found.get(f, 0) < n}
    assert not shrunk, f"fewer hand registrations than listed (update CLI_BY_HAND): {shrunk}, found {found}"


def test_python_takes_options_only_through_tables():
    found = python_keywords()
    new = {k: sorted(v - PYTHON_BY_HAND.get(k, set())) for k, v in found.items() if v - PYTHON_BY_HAND.get(k, set())}
    assert not new, (f"keyword-only parameters outside the option tables in python/spdfit: {new}; take them in "
                     "**options through a table (python/src/entries.cpp)")
    stale = {k: sorted(v - found.get(k, set())) for k, v in PYTHON_BY_HAND.items() if v - found.get(k, set())}
    assert not stale, f"listed keywords no longer there (update PYTHON_BY_HAND): {stale}"


def test_matlab_reads_pairs_only_through_tables():
    # Name-value pairs are matched in one place (mex_pairs.hpp's set_pairs); a name compared
    # anywhere else in the gateway or the .m files is an option read by hand.
    found = {}
    for path in sorted((SOURCE / "matlab").rglob("*")):
        if path.suffix not in (".cpp", ".hpp", ".m", ".in") or path.name in ("mex_pairs.hpp", "mex_options.cpp",
                                                                              "mex_options.hpp"):
            continue
        count = len(MATLAB_PATTERN.findall(path.read_text()))
        if count:
            found[path.relative_to(SOURCE).as_posix()] = count
    grown = {f: n for f, n in found.items() if n > MATLAB_BY_HAND.get(f, 0)}
    assert not grown, f"MATLAB options read by hand (allowed {MATLAB_BY_HAND}): {grown}"
    shrunk = {f: n for f, n in MATLAB_BY_HAND.items() if found.get(f, 0) < n}
    assert not shrunk, f"fewer than listed (update MATLAB_BY_HAND): {shrunk}"


def test_the_check_itself_sees_a_hand_registration():
    # The scans above, on a scratch hand option of each kind, find it.
    assert len(CLI_PATTERN.findall('sub->add_option("--scratch", x, "h"); sub->add_flag("--y", y);')) == 2
    assert list(keyword_only("def f(A, *, scratch=None, **options):\n    pass\n")) == [("f", {"scratch"})]
    assert len(MATLAB_PATTERN.findall("if same_name(pair.name, 'Scratch')")) == 1
