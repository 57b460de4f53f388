"""Every public function of the package (the functions in the __all__ of spdfit and of its modules,
and the classes there written in Python, such as spdfit.Factor, with their public methods) has a
docstring in the NumPy format, parsed with numpydoc (Debian's python3-numpydoc): a summary,
Parameters naming exactly the function's parameters (a function without parameters has none to
name), Returns, Raises naming exception classes that
exist (a function without parameters has no input to refuse), and Examples that run as doctests
and check at least one printed value. A docstring that is not NumPy's format, or a doctest that
prints something else, fails. The modules' own docstrings' examples run too."""
import builtins
import doctest
import inspect
import warnings

import pytest

import spdfit
import spdfit.experiment
import spdfit.fitting
import spdfit.hexapod
import spdfit.io
import spdfit.linear_system
import spdfit.linkage
import spdfit.payload
import spdfit.physical
import spdfit.repair

docscrape = pytest.importorskip("numpydoc.docscrape", reason="numpydoc is not installed (Debian: python3-numpydoc)")

MODULES = [spdfit, spdfit.fitting, spdfit.io, spdfit.linear_system, spdfit.repair, spdfit.hexapod, spdfit.linkage,
           spdfit.experiment, spdfit.physical, spdfit.payload]


def is_python_class(value):
    """A class of the package written in Python: not compiled by pybind11, and neither an exception
    or a warning nor a named tuple of results, whose docstrings are one line."""
    return (isinstance(value, type) and type(value) is type and value.__module__.startswith("spdfit")
            and not issubclass(value, (BaseException, tuple)))


def public_functions():
    """(qualified name, function) for every function in the modules' __all__, and for every class
    there written in Python the class (its docstring documents the constructor) and its public
    methods."""
    found = []
    for module in MODULES:
        for name in module.__all__:
            value = getattr(module, name)
            if is_python_class(value):
                found.append((f"{module.__name__}.{name}", value))
                found += [(f"{module.__name__}.{name}.{attribute}", getattr(value, attribute))
                          for attribute, member in vars(value).items()
                          if not attribute.startswith("_")
                          and (inspect.isfunction(member) or isinstance(member, (classmethod, staticmethod)))]
            elif callable(value) and not isinstance(value, type):
                found.append((f"{module.__name__}.{name}", value))
    return found


FUNCTIONS = public_functions()


def parse(function):
    """The numpydoc parse of the function's docstring; numpydoc's warnings (an unknown section, a
    malformed one) are errors."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return docscrape.NumpyDocString(inspect.getdoc(function) or "")


def exception_class(name):
    """The exception class a Raises entry names (spdfit's or a built-in), or None."""
    value = getattr(spdfit, name, None) or getattr(builtins, name, None)
    return value if isinstance(value, type) and issubclass(value, BaseException) else None


def problems(function):
    """What the function's docstring lacks, in words (empty when nothing)."""
    found = []
    try:
        doc = parse(function)
    except Exception as error:  # numpydoc raises ValueError or warns for what it cannot parse
        return [f"not in the NumPy format: {error}"]
    if not doc["Summary"]:
        found.append("no summary line")

    parameters = list(inspect.signature(function).parameters)
    if parameters[:1] == ["self"]:  # a method, taken from its class
        parameters = parameters[1:]
    documented = [name.strip() for entry in doc["Parameters"] for name in entry.name.split(",")]
    if documented != parameters:
        found.append(f"Parameters documents {documented}, the function takes {parameters}")
    if not doc["Returns"] and not isinstance(function, type):  # a class's docstring documents its constructor
        found.append("no Returns section")
    raised = [entry.type or entry.name for entry in doc["Raises"]]
    if parameters and not raised:
        found.append("no Raises section")
    found += [f"Raises names {name!r}, which is not an exception class" for name in raised if not exception_class(name)]

    examples = "\n".join(doc["Examples"])
    if ">>>" not in examples:
        found.append("no Examples with doctests")
    elif not any(example.want for example in doctest.DocTestParser().get_examples(examples)):
        found.append("no example checks a printed value")
    outside = (inspect.getdoc(function) or "").replace(examples, "")
    if ">>>" in outside:
        found.append("doctests outside the Examples section")
    return found


@pytest.mark.parametrize("name,function", FUNCTIONS, ids=[name for name, _ in FUNCTIONS])
def test_numpy_format(name, function):
    assert not problems(function), f"{name}: " + "; ".join(problems(function))


@pytest.mark.parametrize("name,function", FUNCTIONS, ids=[name for name, _ in FUNCTIONS])
def test_examples_run(name, function, tmp_path, monkeypatch):
    """The Examples run as doctests, each function's in fresh globals, in a scratch directory,
    with spdfit's warnings as errors: an example that warns shows how it handles the warning."""
    monkeypatch.chdir(tmp_path)
    examples = "\n".join(parse(function)["Examples"])
    test = doctest.DocTestParser().get_doctest(examples, {}, name, None, 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    with warnings.catch_warnings():
        warnings.simplefilter("error", spdfit.SpdfitWarning)
        runner.run(test)
    failed, attempted = runner.summarize(verbose=False)
    assert attempted > 0 and failed == 0, f"{failed} of {attempted} examples of {name} failed (output above)"


@pytest.mark.parametrize("module", [m for m in MODULES if ">>>" in (m.__doc__ or "")], ids=lambda m: m.__name__)
def test_module_examples_run(module, tmp_path, monkeypatch):
    """The modules' own docstrings' examples run too (their warnings are not the point there)."""
    monkeypatch.chdir(tmp_path)
    test = doctest.DocTestParser().get_doctest(module.__doc__, {}, module.__name__, None, 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", spdfit.SpdfitWarning)
        runner.run(test)
    failed, attempted = runner.summarize(verbose=False)
    assert attempted > 0 and failed == 0, f"{failed} of {attempted} examples of {module.__name__} failed"


def test_every_module_function_is_covered():
    """The list is not empty and covers each module, so that the tests above cannot pass on
    nothing."""
    modules = {name.rsplit(".", 1)[0] for name, _ in FUNCTIONS}
    assert {module.__name__ for module in MODULES} <= modules
    assert {"spdfit.fit", "spdfit.solve", "spdfit.hexapod.simulate", "spdfit.linkage.synthesize",
            "spdfit.experiment.thesis", "spdfit.Factor", "spdfit.Factor.from_data", "spdfit.Factor.merge",
            "spdfit.Factor.fit"} <= {name for name, _ in FUNCTIONS}


def test_the_checks_find_what_is_missing():
    def undocumented(a, b=1):
        """Add.

        Parameters
        ----------
        a : float
            A number.

        Raises
        ------
        NoSuchError
            Never.

        Examples
        --------
        >>> undocumented(1)
        """

    found = problems(undocumented)
    assert any("Parameters documents ['a'], the function takes ['a', 'b']" in p for p in found), found
    assert "no Returns section" in found
    assert "Raises names 'NoSuchError', which is not an exception class" in found
    assert "no example checks a printed value" in found
    assert "no summary line" in problems(lambda x: x)

    def misspelt(x):
        """Identity.

        Retruns
        -------
        float
            x.
        """
    assert any(p.startswith("not in the NumPy format") for p in problems(misspelt)), problems(misspelt)
