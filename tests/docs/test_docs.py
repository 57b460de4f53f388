"""The README's and the guide pages' examples cannot go stale: every ```console block's
`$ spdfit ...` command runs with the exit status and the output lines the page shows, every
```python block is a doctest, and docs/cpp.md shows tests/package's files verbatim.

Conventions in the pages: lines after a `$` command are expected output lines (each must be
printed, stdout or stderr, in any order); `...` elides lines; `[exit status N]` gives the
expected exit status (0 otherwise). Commands run in a scratch directory, one per page, in
which `examples` is the repository's examples folder: a page's examples run in order, and may read
what an earlier one wrote. No example may print a warning that contradicts the method
the run chose or the noise model it was given (spdfit_testing.contradicting_warnings).
(docs/hexapod.md and docs/linkage.md have their own tests in tests/hexapod and tests/linkage.)"""
import doctest
import os
import pathlib
import re
import shlex
import subprocess
import sys
import warnings

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "support"))
from spdfit_testing import command_context, contradicting_warnings  # noqa: E402

ROOT = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
PAGES = ["README.md", "docs/guide.md", "docs/cli.md", "docs/python.md", "docs/accuracy.md", "docs/payload.md"]
EXIT = re.compile(r"^\[exit status (\d+)\]$")
# The README's command lines include full-size experiments and the demo, which the plain build
# runs; under the sanitizers (SPDFIT_SANITIZED=1) they took minutes of CI for no new coverage.
SANITIZED = os.environ.get("SPDFIT_SANITIZED") == "1"


def console_examples(page):
    """[(command, expected lines, expected status)] from the page's ```console blocks."""
    examples = []
    for block in re.findall(r"```console\n(.*?)```", (ROOT / page).read_text(), flags=re.S):
        for line in block.splitlines():
            if line.startswith("$ "):
                examples.append([line[2:], [], 0])
            elif EXIT.match(line):
                examples[-1][2] = int(EXIT.match(line).group(1))
            elif line.strip() != "...":
                examples[-1][1].append(line.rstrip())
    return [tuple(e) for e in examples]


ALL = [(page, *example) for page in PAGES for example in console_examples(page)]


@pytest.fixture(scope="module")
def page_dirs():
    return {}


@pytest.fixture
def workdir(request, tmp_path_factory, page_dirs):
    """One directory per page, holding `examples`: a page's examples run in order in it, so that
    one may read what an earlier one wrote (docs/payload.md's estimate.json)."""
    page = request.node.callspec.params.get("page", "") if hasattr(request.node, "callspec") else ""
    if page not in page_dirs:
        path = tmp_path_factory.mktemp("page")
        (path / "examples").symlink_to(ROOT / "examples")
        page_dirs[page] = path
    return page_dirs[page]


def test_pages_have_examples():
    for page in PAGES:
        assert console_examples(page) or "```python" in (ROOT / page).read_text(), page


@pytest.mark.parametrize("page,command,expected,status", ALL, ids=[f"{p}: {c}" for p, c, _, _ in ALL])
def test_console_example(cli, workdir, page, command, expected, status):
    words = shlex.split(command)
    assert words[0] == "spdfit", command
    result = subprocess.run([cli, *words[1:]], cwd=workdir, capture_output=True, text=True, timeout=300)
    assert result.returncode == status, f"{page}: {command}\n{result.stderr}"
    printed = {line.rstrip() for line in (result.stdout + result.stderr).splitlines()}
    for line in expected:
        assert line in printed, f"{page}: {command}\nthe page shows\n{line}\nbut the command printed\n" \
                                f"{result.stdout}{result.stderr}"
    if words[1] in ("fit", "compare") or words[1:3] == ["hexapod", "identify"]:
        bad = contradicting_warnings((result.stdout + result.stderr).splitlines(), *command_context(words))
        assert not bad, f"{page}: {command}\nprints what contradicts its method or noise model:\n" + "\n".join(bad)


@pytest.mark.skipif(SANITIZED, reason="full-size experiments are run by the plain build")
def test_readme_command_lines_run(cli, workdir):
    """The README's indented `spdfit ...` lines (comments dropped) run with exit status 0."""
    lines = [line.split("  #", 1)[0].strip() for line in (ROOT / "README.md").read_text().splitlines()
             if line.startswith("    spdfit ")]
    assert len(lines) >= 5
    for command in lines:
        result = subprocess.run([cli, *shlex.split(command)[1:]], cwd=workdir, capture_output=True, text=True,
                                timeout=300)
        assert result.returncode == 0, f"README: {command}\n{result.stderr}"


@pytest.mark.parametrize("page", ["README.md", "docs/python.md", "docs/accuracy.md", "docs/guide.md", "docs/payload.md",
                                  "docs/linkage.md"])
def test_python_examples(workdir, page, monkeypatch):
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / page).read_text(), flags=re.S)
    if not blocks:
        pytest.skip(f"{page} has no python examples")
    monkeypatch.chdir(workdir)
    contradictions = watch_fits(monkeypatch)
    parser = doctest.DocTestParser()
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS)
    globs = {}
    for number, block in enumerate(blocks):
        test = parser.get_doctest(block, globs, f"{page} block {number + 1}", page, 0)
        runner.run(test, clear_globs=False)
        globs = test.globs  # later blocks continue where this one left off (DocTest copies globs)
    failed, attempted = runner.summarize(verbose=False)
    assert attempted > 0 and failed == 0, f"{failed} of {attempted} examples in {page} failed (output above)"
    assert not contradictions, f"{page}: warnings that contradict the run's method or noise model:\n" + \
        "\n".join(contradictions)


def watch_fits(monkeypatch):
    """The fits of the examples (spdfit.fit, fit_files, fit_all) wrapped so that each one's warnings
    are checked against the result's own method choice and noise model: returns the
    list that collects the lines that contradict them."""
    import spdfit
    found = []

    def check(result, caught):
        results = result if isinstance(result, list) else [result]
        for r in results:
            diagnostics = getattr(r, "diagnostics", None)
            if diagnostics is None:
                continue
            chosen_by_auto = diagnostics.reason is not None
            noise_model = diagnostics.noise_model is not None
            lines = [str(w.message) for w in caught] + list(r.warnings)
            found.extend(contradicting_warnings(lines, chosen_by_auto, noise_model))

    def wrap(function):
        def watched(*args, **kwargs):
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                result = function(*args, **kwargs)
            check(result, caught)
            for w in caught:  # as the example would have seen them
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
            return result
        return watched

    for name in ("fit", "fit_files", "fit_all"):
        monkeypatch.setattr(spdfit, name, wrap(getattr(spdfit, name)))
    return found


def test_cpp_page_shows_the_package_test_verbatim():
    page = (ROOT / "docs/cpp.md").read_text()
    cpp = re.search(r"```cpp\n(.*?)```", page, flags=re.S).group(1)
    cmake = re.search(r"```cmake\n(.*?)```", page, flags=re.S).group(1)
    assert cpp.strip() == (ROOT / "tests/package/consumer.cpp").read_text().strip()
    assert cmake.strip() == (ROOT / "tests/package/CMakeLists.txt").read_text().strip()


def test_the_contradiction_check_flags_what_spdfit_printed_before():
    """The check above can fail: it flags the lines that the issue (45, item 1) quotes from runs
    before the fix, and passes the ones that state a fact in agreement with the run."""
    auto_psd_ls = "spdfit: warning: psd-ls models noise in B only (weighted by --rest-b): the noise in A that " \
                  "--rest-a gives is ignored (it biases least squares towards zero; spd-tls models it)"
    bias = "spdfit: warning: psd-ls: if A carries noise (the noise estimate cannot tell A's from B's), psd-ls is " \
           "biased by it at m = 200 rows (signal-to-noise ratio 1.39e+06 in A's weakest direction)"
    report = "noise estimate: sigma = 0.304332 in every entry of A (times the noise ratio in B)"
    assert contradicting_warnings([auto_psd_ls], chosen_by_auto=True, noise_model=True) == [auto_psd_ls]
    assert contradicting_warnings([bias, report], chosen_by_auto=False, noise_model=True) == [bias, report]
    assert contradicting_warnings([report], chosen_by_auto=False, noise_model=False) == []
    spde = "spdfit: warning: auto: spde ran without the noise model (it has none)"
    assert contradicting_warnings([spde], chosen_by_auto=True, noise_model=True) == []
    assert command_context(["spdfit", "fit", "--method", "auto", "--rest-a", "r.csv"]) == (True, True)
    assert command_context(["spdfit", "fit", "-m", "psd-ls", "a.csv"]) == (False, False)


def test_local_links_and_images_exist():
    """Every relative link and image of the README and docs/*.md names a file or folder of the
    repository (docs/payload.md linked two figures that were never committed)."""
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    missing = []
    for page in pages:
        text = re.sub(r"```.*?```", "", page.read_text(), flags=re.S)  # not inside code blocks
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"[a-z]+:", target) or target.startswith("#"):
                continue  # a URL or an anchor on the same page
            path = (page.parent / target.split("#")[0]).resolve()
            if not path.exists():
                missing.append(f"{page.relative_to(ROOT)}: {target}")
    assert not missing, "links to files that do not exist:\n" + "\n".join(missing)
