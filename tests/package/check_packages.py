"""Every Debian package spdfit uses is on one of its two lists (scripts/packages-runtime.txt,
scripts/packages-test.txt), or is installed because a listed package depends on it.

    /usr/bin/python3 tests/package/check_packages.py SOURCE_DIR BUILD_DIR

"Used" is found, not declared: the system headers each object of BUILD_DIR was compiled with
(the compiler's .o.d files), the files each target links and the shared libraries its programs
load, the tools CMake found (CMakeCache.txt), the modules the Python package, setup.py and the
test suites import (also `pytest.importorskip("X")` and `python3 -m X` in scripts), and the
programs the tests and scripts run. Each file is mapped to its package with `dpkg -S`. What the
main job builds and runs (the library, the spdfit command, the Python package) must be covered
by the runtime list alone; everything else by the two together. Exit status 1 with one line per
package used but not listed.
"""
import ast
import glob
import importlib.util
import os
import re
import shutil
import subprocess
import sys

# Programs the test suites and scripts start by name (what shutil.which finds), with whether a
# missing one skips tests instead of failing them. R is an optional extra reference: its
# answers are stored in tests/data/r_matrix, and the tests that run it skip without it.
PROGRAMS = {"octave-cli": "test", "mpirun": "test", "clang++-14": "runtime", "cmake": "runtime"}
OPTIONAL_PROGRAMS = {"Rscript"}
# CMake cache entries of tools used when present (CMakeLists.txt: ccache). CMake's own toolchain
# entries (CMAKE_AR, CMAKE_LINKER, ...) are left out too: CMake picks whichever archiver and
# binary tools are installed (with clang, LLVM's when llvm-14 is there; else binutils').
OPTIONAL_CACHE_ENTRIES = {"SPDFIT_CCACHE"}
OPTIONAL_CACHE_PREFIX = "CMAKE_"

# Build-tree directories whose targets the main job builds (scripts/demo.sh), and the targets there
# that are built only when their packages are present (apps/CMakeLists.txt: mpirun support when
# Open MPI is found), whose packages are on the test list.
RUNTIME_DIRECTORIES = ("src", "apps", "python")
OPTIONAL_TARGETS = ("spdfit_mpi", "spdfit-mpi")
# Modules the Python package imports only when a caller's argument needs them: pandas, for a
# DataFrame given (repair.py). Tested with the test list's python3-pandas.
OPTIONAL_RUNTIME_MODULES = {"pandas"}

APT_DEPENDS = ["apt-cache", "depends", "--recurse", "--installed", "--no-recommends", "--no-suggests",
               "--no-conflicts", "--no-breaks", "--no-replaces", "--no-enhances"]


def read_list(path):
    """The package names of a list file (one per line, # comments)."""
    names = []
    with open(path, encoding="utf-8") as handle:
        for line in handle:
            line = line.split("#", 1)[0].strip()
            if line:
                names.append(line)
    return names


def bare(name):
    """A package name without its architecture qualifier or apt's <virtual> brackets."""
    return name.strip().strip("<>").split(":", 1)[0]


def closure(packages):
    """The listed packages and every installed package they depend on (recursively)."""
    if not packages:
        return set()
    out = subprocess.run(APT_DEPENDS + list(packages), capture_output=True, text=True, check=True).stdout
    return {bare(line) for line in out.splitlines() if line and not line.startswith(" ")}


def owners(paths):
    """{path: package} for the paths dpkg knows (symbolic links resolved when the link itself is
    not a package's file), and the list of paths no package owns."""
    found, unowned = {}, []
    candidates = {}
    for path in sorted(set(paths)):
        candidates[path] = [path]
        real = os.path.realpath(path)
        if real != path:
            candidates[path].append(real)
    queries = sorted({c for cs in candidates.values() for c in cs})
    owner_of = {}
    for start in range(0, len(queries), 500):
        chunk = queries[start:start + 500]
        out = subprocess.run(["dpkg-query", "-S"] + chunk, capture_output=True, text=True).stdout
        for line in out.splitlines():
            if line.startswith("diversion by") or ": " not in line:
                continue
            packages, path = line.split(": ", 1)
            owner_of.setdefault(path, bare(packages.split(",")[0]))
    for path, cs in candidates.items():
        package = next((owner_of[c] for c in cs if c in owner_of), None)
        if package is None:
            unowned.append(path)
        else:
            found[path] = package
    return found, unowned


def cmake_cache(build_dir):
    """BUILD_DIR's CMakeCache.txt entries: name -> (type, value)."""
    cache = {}
    with open(os.path.join(build_dir, "CMakeCache.txt"), encoding="utf-8") as handle:
        for line in handle:
            match = re.match(r"([A-Za-z0-9_]+):([A-Z]+)=(.*)$", line.strip())
            if match:
                cache[match.group(1)] = (match.group(2), match.group(3))
    return cache


def main_job_configuration(build_dir):
    """Whether BUILD_DIR is configured as the main job builds (scripts/setup.sh: Release, not the
    sanitizer build, whose clang and its runtime are on the test list)."""
    cache = cmake_cache(build_dir)
    value = lambda name, default: cache.get(name, ("", default))[1]  # noqa: E731
    return value("CMAKE_BUILD_TYPE", "") == "Release" and value("SPDFIT_SANITIZE", "OFF").upper() in ("OFF", "0", "FALSE", "")


MAIN_JOB = {}  # build_dir -> main_job_configuration(build_dir)


def role_of(path, build_dir):
    """'runtime' for the files of the targets the main job builds, 'test' for the others (and for
    every file of a build configured otherwise)."""
    if build_dir not in MAIN_JOB:
        MAIN_JOB[build_dir] = main_job_configuration(build_dir)
    if not MAIN_JOB[build_dir]:
        return "test"
    parts = os.path.relpath(path, build_dir).split(os.sep)
    optional = any(target in part for part in parts for target in OPTIONAL_TARGETS)
    return "runtime" if parts[0] in RUNTIME_DIRECTORIES and not optional else "test"


def is_system_path(path, source_dir, build_dir):
    path = os.path.abspath(path)
    return path.startswith("/") and not path.startswith((source_dir + os.sep, build_dir + os.sep)) \
        and not path.startswith(("/tmp/", "/proc/"))


def compiled_headers(build_dir, source_dir):
    """{'runtime'|'test': set of system files} from the compiler's dependency files."""
    used = {"runtime": set(), "test": set()}
    for depfile in glob.glob(os.path.join(build_dir, "**", "*.o.d"), recursive=True):
        role = role_of(depfile, build_dir)
        with open(depfile, encoding="utf-8", errors="replace") as handle:
            text = handle.read().replace("\\\n", " ")
        for token in text.split():
            if token.endswith(":") or not token.startswith("/"):
                continue
            if is_system_path(token, source_dir, build_dir):
                used[role].add(os.path.normpath(token))
    return used


def linked_files(build_dir, source_dir):
    """{'runtime'|'test': set of system files} that the link lines name and that the programs and
    modules built load (ldd)."""
    used = {"runtime": set(), "test": set()}
    for link in glob.glob(os.path.join(build_dir, "**", "link.txt"), recursive=True):
        role = role_of(link, build_dir)
        with open(link, encoding="utf-8") as handle:
            for token in handle.read().split():
                if token.startswith("/") and re.search(r"\.(so(\.\d+)*|a)$", token) \
                        and is_system_path(token, source_dir, build_dir):
                    used[role].add(token)
    for path in glob.glob(os.path.join(build_dir, "**", "*"), recursive=True):
        if not os.path.isfile(path) or "CMakeFiles" in path or path.endswith((".o", ".a")):
            continue
        if not (os.access(path, os.X_OK) or re.search(r"\.(so|mex)$", path)):
            continue
        with open(path, "rb") as handle:
            if handle.read(4) != b"\x7fELF":
                continue
        role = role_of(path, build_dir)
        out = subprocess.run(["ldd", path], capture_output=True, text=True).stdout
        for match in re.finditer(r"=> (/\S+)", out):
            if is_system_path(match.group(1), source_dir, build_dir):
                used[role].add(match.group(1))
    return used


def cmake_tools(build_dir, source_dir):
    """System files CMake found (FILEPATH entries: compilers, mkoctfile, libraries)."""
    used = set()
    for name, (kind, path) in cmake_cache(build_dir).items():
        if kind != "FILEPATH" or not path.startswith("/") or " " in path:
            continue
        if name in OPTIONAL_CACHE_ENTRIES or name.startswith(OPTIONAL_CACHE_PREFIX):
            continue
        if os.path.exists(path) and is_system_path(path, source_dir, build_dir):
            used.add(path)
    return used


def local_module_names(source_dir):
    """Top-level names the repository itself provides (the package, test helpers, test files)."""
    names = {"spdfit", "setup", "conftest"}
    for path in glob.glob(os.path.join(source_dir, "**", "*.py"), recursive=True):
        names.add(os.path.splitext(os.path.basename(path))[0])
    for path in glob.glob(os.path.join(source_dir, "**", "__init__.py"), recursive=True):
        names.add(os.path.basename(os.path.dirname(path)))
    return names


def imported_modules(files):
    """Absolute module names imported by the Python files (every import statement, also inside
    functions), named by pytest.importorskip, or run with `python3 -m`."""
    modules = set()
    for path in files:
        with open(path, encoding="utf-8") as handle:
            text = handle.read()
        if path.endswith(".py"):
            for node in ast.walk(ast.parse(text, filename=path)):
                if isinstance(node, ast.Import):
                    modules.update(alias.name for alias in node.names)
                elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                    modules.add(node.module)
        modules.update(re.findall(r"importorskip\([\"']([A-Za-z0-9_.]+)", text))
        # `python3 -m X` in a script, [sys.executable, "-m", "X"] in Python (the spdfit command's
        # own -m is its --method)
        for line in text.splitlines():
            if "python" in line or "executable" in line:
                modules.update(re.findall(r"(?<![A-Za-z-])-m[\"', ]+([A-Za-z_][A-Za-z0-9_.]*)", line))
    return modules


def module_files(modules, local_names):
    """{module: file} for the installed top-level modules (found without importing anything), and
    the list of those that are not installed. Built-in modules (part of the interpreter) have no
    file and are not listed."""
    files, missing = {}, []
    for top in sorted({module.split(".")[0] for module in modules} - set(local_names)):
        spec = importlib.util.find_spec(top)
        if spec is None:
            missing.append(top)
        elif spec.origin and spec.origin.startswith("/"):
            files[top] = spec.origin
        elif spec.submodule_search_locations:
            files[top] = os.path.join(list(spec.submodule_search_locations)[0], "__init__.py")
    return files, missing


def main(source_dir, build_dir):
    source_dir, build_dir = os.path.realpath(source_dir), os.path.realpath(build_dir)
    runtime = read_list(os.path.join(source_dir, "scripts", "packages-runtime.txt"))
    test = read_list(os.path.join(source_dir, "scripts", "packages-test.txt"))
    problems = []
    for package in runtime + test:
        status = subprocess.run(["dpkg-query", "-W", "-f=${Status}", package], capture_output=True, text=True)
        if "install ok installed" not in status.stdout:
            problems.append(f"{package}: listed but not installed (scripts/setup.sh installs the lists)")
    covered = {"runtime": closure(runtime), "test": closure(runtime + test)}

    # what uses each system file, in the role (runtime or test) that needs it
    uses = {"runtime": {}, "test": {}}

    def add(role, path, why):
        uses[role].setdefault(path, why)

    for role, paths in compiled_headers(build_dir, source_dir).items():
        for path in paths:
            add(role, path, "a header the build includes")
    for role, paths in linked_files(build_dir, source_dir).items():
        for path in paths:
            add(role, path, "a library a target links or loads")
    for path in cmake_tools(build_dir, source_dir):
        add("test", path, "a tool or library CMake found")

    local_names = local_module_names(source_dir)
    python_files = {
        "runtime": glob.glob(os.path.join(source_dir, "python", "spdfit", "**", "*.py"), recursive=True)
                   + [os.path.join(source_dir, "scripts", "demo.sh")],
        "test": [path for path in glob.glob(os.path.join(source_dir, "tests", "**", "*.py"), recursive=True)
                 if os.path.basename(path) != os.path.basename(__file__)]
                + glob.glob(os.path.join(source_dir, "tests", "**", "*.sh"), recursive=True)
                + glob.glob(os.path.join(source_dir, "bench", "**", "*.py"), recursive=True)
                + glob.glob(os.path.join(source_dir, "scripts", "*.sh"), recursive=True)
                + [os.path.join(source_dir, "setup.py")],
    }
    for role, files in python_files.items():
        modules = imported_modules(files)
        if role == "runtime":
            optional = {m for m in modules if m.split(".")[0] in OPTIONAL_RUNTIME_MODULES}
            modules -= optional
            found, _ = module_files(optional, local_names)
            for module, path in found.items():
                add("test", path, f"the Python module {module} (optional at run time)")
        found, missing = module_files(modules, local_names)
        for module in missing:
            problems.append(f"Python module {module}: imported ({role}) but not installed")
        for module, path in found.items():
            add(role, path, f"the Python module {module}")

    for program, role in sorted(PROGRAMS.items()):
        path = shutil.which(program)
        if path is None:
            problems.append(f"{program}: run by the {role} scripts or tests but not installed")
        else:
            add(role, path, f"the program {program}")
    for program in sorted(OPTIONAL_PROGRAMS):
        if shutil.which(program):
            print(f"note: {program} is present; the tests that use it run (it is optional, not listed)")

    for role in ("runtime", "test"):
        found, unowned = owners(uses[role])
        for path in unowned:
            problems.append(f"{path} ({uses[role][path]}, {role}): no Debian package owns it")
        reported = set()
        for path, package in sorted(found.items()):
            if package in covered[role] or package in reported:
                continue
            reported.add(package)
            where = ("scripts/packages-runtime.txt, which the main job installs" if role == "runtime"
                     else "scripts/packages-runtime.txt or scripts/packages-test.txt")
            problems.append(f"{package}: used ({uses[role][path]}: {path}) but not on {where}, "
                            f"nor a dependency of a package listed there")
    for problem in problems:
        print(problem)
    print(f"checked {sum(len(u) for u in uses.values())} files against {len(runtime)} runtime and "
          f"{len(test)} test packages: {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
