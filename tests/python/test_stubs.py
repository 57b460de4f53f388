"""The type stubs (python/spdfit/*.pyi) agree with the module as built.

mypy.stubtest (Debian's python3-mypy) compares every stub with the runtime object, with an
allowlist of pybind11's own artefacts only (stubtest-allowlist.txt; an entry that no longer
matches is an error too). stubtest cannot read the signature of a function pybind11 compiled, so
the parameters of those are compared here with the signature pybind11 writes into their
docstrings. Both run on a copy of the package under test, so that neither can check another
installed spdfit (CI also installs one into /usr/local), and a copy with a stub broken on purpose
shows that the check sees it."""
import ast
import inspect
import os
import pathlib
import shutil
import subprocess
import sys
import types

import pytest

import spdfit

HERE = pathlib.Path(__file__).resolve().parent
ROOT = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", HERE.parents[1]))
PACKAGE = pathlib.Path(spdfit.__file__).resolve().parent


def copy_or_link(source, destination):
    """Copies a file; links the compiled module instead (the sanitizer build's is 250 MB)."""
    if source.endswith(".so"):
        os.symlink(source, destination)
    else:
        shutil.copy2(source, destination)


@pytest.fixture
def package_copy(tmp_path):
    """A directory holding a copy of the package under test, as `spdfit`."""
    shutil.copytree(PACKAGE, tmp_path / "pkg" / "spdfit", ignore=shutil.ignore_patterns("__pycache__"),
                    copy_function=copy_or_link)
    return tmp_path / "pkg"


def stubtest(directory):
    """mypy.stubtest on the spdfit package in `directory` (its current directory, first on both
    mypy's and the interpreter's search path); the completed process."""
    pytest.importorskip("mypy.stubtest", reason="mypy is not installed (Debian: python3-mypy)")
    env = dict(os.environ, PYTHONPATH=str(directory), MYPY_CACHE_DIR=str(directory.parent / "mypy_cache"))
    command = [sys.executable, "-m", "mypy.stubtest", "spdfit", "--allowlist", str(HERE / "stubtest-allowlist.txt"),
               "--mypy-config-file", str(ROOT / "pyproject.toml")]
    return subprocess.run(command, cwd=directory, env=env, capture_output=True, text=True, timeout=600)


def test_stubtest_passes(package_copy):
    result = stubtest(package_copy)
    assert result.returncode == 0, f"mypy.stubtest found mismatches:\n{result.stdout}{result.stderr}"
    assert "Success: no issues found" in result.stdout, result.stdout


def test_stubtest_sees_a_broken_stub(package_copy):
    """A stub without a function the module has, and with one it lacks, fails, naming both."""
    stub = package_copy / "spdfit" / "_spdfit.pyi"
    text = stub.read_text()
    assert "\ndef area_criterion(" in text
    stub.write_text(text.replace("\ndef area_criterion(", "\ndef no_such_function() -> None: ...\ndef _unused(", 1))
    result = stubtest(package_copy)
    assert result.returncode != 0
    assert "spdfit._spdfit.area_criterion is not present in stub" in result.stdout, result.stdout
    assert "spdfit._spdfit.no_such_function is not present at runtime" in result.stdout, result.stdout


# ---- the functions pybind11 compiled ------------------------------------------------------------

def split_parameters(text):
    """The parameters in pybind11's signature text "a: T, b: U = 1, *, c: V = None", split at the
    commas outside brackets and quotes."""
    parts, depth, quote, start = [], 0, None, 0
    for i, char in enumerate(text):
        if quote:
            quote = None if char == quote else quote
        elif char in "'\"":
            quote = char
        elif char in "[(":
            depth += 1
        elif char in "])":
            depth -= 1
        elif char == "," and depth == 0:
            parts.append(text[start:i].strip())
            start = i + 1
    parts.append(text[start:].strip())
    return [p for p in parts if p]


def pybind11_parameters(function):
    """[(name, kind, has default)] from the signature line pybind11 puts first in a docstring;
    kind is "positional" or "keyword" (after a bare *)."""
    line = function.__doc__.splitlines()[0]
    name = function.__name__
    assert line.startswith(name + "(") and " -> " in line, f"{name}: no pybind11 signature in {line!r}"
    inside = line[len(name) + 1:line.rindex(" -> ") - 1]
    parameters, kind = [], "positional"
    for part in split_parameters(inside):
        if part == "*":
            kind = "keyword"
            continue
        assert not part.startswith("*"), f"{name}: pybind11 overloads or *args: {line}"
        parameters.append((part.split(":", 1)[0].split("=", 1)[0].strip(), kind, "=" in part))
    return parameters


def stub_parameters(node):
    """[(name, kind, has default)] of a function in a stub."""
    args = node.args
    positional = args.posonlyargs + args.args
    defaults = [False] * (len(positional) - len(args.defaults)) + [True] * len(args.defaults)
    return ([(a.arg, "positional", d) for a, d in zip(positional, defaults)]
            + [(a.arg, "keyword", d is not None) for a, d in zip(args.kwonlyargs, args.kw_defaults)])


def is_pybind11_function(value):
    return type(value).__name__ in ("builtin_function_or_method", "instancemethod") and (
        value.__doc__ or "").startswith(value.__name__ + "(")


def compiled_functions_in_stubs():
    """(qualified name, stub function, runtime function) for every function and method of the
    stubs whose runtime object pybind11 compiled."""
    found = []
    for stub in sorted(PACKAGE.glob("*.pyi")):
        module_name = "spdfit" if stub.stem == "__init__" else f"spdfit.{stub.stem}"
        module = sys.modules.get(module_name) or __import__(module_name, fromlist=["_"])
        tree = ast.parse(stub.read_text())
        scopes = [(module_name, module, tree.body)]
        scopes += [(f"{module_name}.{c.name}", getattr(module, c.name, None), c.body)
                   for c in tree.body if isinstance(c, ast.ClassDef)]
        for scope_name, scope, body in scopes:
            for node in body:
                if not isinstance(node, ast.FunctionDef) or node.decorator_list:
                    continue  # properties and overloads are stubtest's
                value = inspect.getattr_static(scope, node.name, None) if scope is not None else None
                value = getattr(scope, node.name) if value is not None else None
                if value is not None and is_pybind11_function(value):
                    found.append((f"{scope_name}.{node.name}", node, value))
    return found


COMPILED = compiled_functions_in_stubs()


def test_the_compiled_functions_are_found():
    names = {name for name, _, _ in COMPILED}
    assert {"spdfit._spdfit.fit", "spdfit._spdfit.read_table", "spdfit._spdfit.solve",
            "spdfit.linkage.FourBar.__init__", "spdfit.hexapod.Geometry.to_json"} <= names, sorted(names)


@pytest.mark.parametrize("name,node,function", COMPILED, ids=[name for name, _, _ in COMPILED])
def test_stub_parameters_are_pybind11s(name, node, function):
    stub = stub_parameters(node)
    runtime = pybind11_parameters(function)
    assert stub == runtime, f"{name}: the stub has\n  {stub}\nthe module\n  {runtime}"


def test_parameters_are_read_from_pybind11s_signature():
    def signature(text):
        return pybind11_parameters(types.SimpleNamespace(__name__="f", __doc__=text))
    assert signature("f(A: numpy.ndarray[numpy.float64[m, n]], s: str = 'a,b', *, k: Optional[int] = None) -> None") \
        == [("A", "positional", False), ("s", "positional", True), ("k", "keyword", True)]
