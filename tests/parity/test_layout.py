"""The tree shows the architecture: every folder of src/ is listed in the README's layout table
and in CONTRIBUTING.md's "Where things live"."""

import os
import re
from pathlib import Path

SOURCE = Path(os.environ.get("SPDFIT_SOURCE_DIR", Path(__file__).resolve().parents[2]))


def test_every_src_folder_is_documented():
    folders = sorted(p.name for p in (SOURCE / "src").iterdir() if p.is_dir())
    readme = (SOURCE / "README.md").read_text()
    layout = readme[readme.index("## Layout"):]
    src_row = next(line for line in layout.splitlines() if line.startswith("| `src/`"))
    contributing = (SOURCE / "CONTRIBUTING.md").read_text()
    missing_readme = [f for f in folders if f"`{f}/`" not in src_row]
    missing_contributing = [f for f in folders if not re.search(rf"src/{f}/", contributing)]
    assert not missing_readme, f"README's layout table does not list src/{missing_readme}"
    assert not missing_contributing, f"CONTRIBUTING.md does not name src/{missing_contributing}"


# The Python package is modules, not a hub (issue 41 item 5): the shared private helpers live in
# _common and _errors, each module imports what it uses from them or from another module (never
# from the package's __init__), the imports form no cycle, and __init__ only re-exports.
PACKAGE = SOURCE / "python" / "spdfit"


def python_imports(path):
    """The package modules `path` imports (anywhere in it, functions included): 'fitting',
    '_common', ..., and '__init__' for a name taken from the package itself."""
    import ast
    modules = {p.stem for p in PACKAGE.glob("*.py")} | {"_spdfit"}
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            if node.module:
                found.add(node.module.split(".")[0])
            else:
                found |= {alias.name if alias.name in modules else "__init__" for alias in node.names}
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            names = [node.module] if isinstance(node, ast.ImportFrom) else [a.name for a in node.names]
            for name in names:
                if name and (name == "spdfit" or name.startswith("spdfit.")):
                    found.add(name.split(".")[1] if "." in name else "__init__")
    return found - {"_spdfit"}


def test_python_modules_never_import_the_package_hub():
    hub = sorted(p.name for p in PACKAGE.glob("*.py") if p.name != "__init__.py" and "__init__" in python_imports(p))
    assert not hub, f"{hub} import names from spdfit/__init__.py; import them from the module that defines them"


def test_python_modules_import_no_cycle():
    graph = {p.stem: python_imports(p) for p in PACKAGE.glob("*.py")}
    state = {}

    def visit(module, path):
        if state.get(module) == "done":
            return
        assert state.get(module) != "open", f"an import cycle: {' -> '.join(path + [module])}"
        state[module] = "open"
        for other in sorted(graph.get(module, ())):
            visit(other, path + [module])
        state[module] = "done"

    for module in sorted(graph):
        visit(module, [])


def test_python_init_only_reexports():
    import ast
    tree = ast.parse((PACKAGE / "__init__.py").read_text())
    defined = [node.name for node in tree.body if isinstance(node, (ast.FunctionDef, ast.ClassDef))]
    assert not defined, f"spdfit/__init__.py defines {defined}: define them in a module and re-export them"
    assert len((PACKAGE / "__init__.py").read_text().splitlines()) < 120


def test_the_cycle_check_sees_a_cycle(tmp_path, monkeypatch):
    """The checks above fail on what they are meant to catch: a module importing the hub, and two
    modules importing each other (a copy of the package with both written in)."""
    import shutil
    copy = tmp_path / "spdfit"
    shutil.copytree(PACKAGE, copy)
    (copy / "io.py").write_text((copy / "io.py").read_text() + "\nfrom . import fit\n\ndef _late():\n    from .fitting import fit\n")
    (copy / "fitting.py").write_text((copy / "fitting.py").read_text() + "\nfrom .io import read_matrix\n")
    monkeypatch.setitem(globals(), "PACKAGE", copy)
    import pytest
    with pytest.raises(AssertionError, match="io.py"):
        test_python_modules_never_import_the_package_hub()
    with pytest.raises(AssertionError, match="an import cycle: .*fitting -> io"):
        test_python_modules_import_no_cycle()
