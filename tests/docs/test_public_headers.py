"""The public API is what include/spdfit/ holds, and the umbrella header spdfit/spdfit.hpp
includes all of it (docs/cpp.md: "#include <spdfit/spdfit.hpp> includes them all"). Internal
state stays in src/: no public header declares the bounded-size reduction template or the
readers' format-specific parts outside a private or detail section."""
import os
import pathlib
import re

ROOT = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
INCLUDE = ROOT / "include"


def public_headers():
    return sorted(p.relative_to(INCLUDE).as_posix() for p in (INCLUDE / "spdfit").rglob("*.hpp"))


def test_umbrella_header_includes_every_public_header():
    umbrella = (INCLUDE / "spdfit" / "spdfit.hpp").read_text()
    included = set(re.findall(r'#include "([^"]+)"', umbrella))
    missing = [h for h in public_headers() if h != "spdfit/spdfit.hpp" and h not in included]
    assert not missing, f"spdfit/spdfit.hpp does not include {missing}"
    # version.hpp is generated into the build tree; every other include names a real header.
    assert {h for h in included if h != "spdfit/version.hpp"} <= set(public_headers())


def test_reduction_has_no_writable_public_state():
    header = (INCLUDE / "spdfit" / "reduction.hpp").read_text()
    public_part = header.split(" private:")[0]
    # Data members (a type, a name and ';') may appear only after "private:".
    assert not re.search(r"^\s+(Matrix|Vector|Eigen::\w+|int|FitOptions)\s+\w+(\s*=\s*[^;]+)?;", public_part, re.M)
    assert "template <int MaxN>\nstruct BasicReduction {" not in header


def test_parsers_on_bytes_are_internal():
    io = (INCLUDE / "spdfit" / "io.hpp").read_text()
    for name in ("parse_table", "parse_delimited", "parse_npy", "fewer_samples_than_columns"):
        assert name not in io


def test_front_ends_include_only_public_headers():
    """The command line and the Python module use the library as any program would: their
    includes of the library are spdfit/*.hpp (their own headers sit beside them). The build
    enforces it too (src/ is not on their include path); this names the file that breaks it."""
    internal_folders = {p.name for p in (ROOT / "src").iterdir() if p.is_dir()}
    offenders = []
    for folder in ("apps", "python"):
        for source in sorted((ROOT / folder).rglob("*.[ch]pp")):
            for included in re.findall(r'#include "([^"]+)"', source.read_text()):
                first = included.split("/")[0]
                if first in internal_folders or first in ("src", "..") and "spdfit/" not in included:
                    if not (source.parent / included).exists():
                        offenders.append(f"{source.relative_to(ROOT)}: {included}")
    assert not offenders, offenders
