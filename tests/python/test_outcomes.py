"""Outcome codes in Python: one warning class per warning code, each a subclass of SpdfitWarning;
warnings issued with their code's class; errors raised as their code's class, whatever their
message; docs/errors.md's table is the library's."""
import os
import pathlib
import warnings

import numpy as np
import pytest

import spdfit
import spdfit.hexapod as hx

ROOT = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


def test_every_warning_code_has_its_class():
    codes = spdfit.outcome_codes()
    assert len({row[0] for row in codes}) == len(codes)
    for name, tier, python_class, matlab, meaning in codes:
        assert matlab.startswith("spdfit:")
        assert meaning
        if tier != "warning":
            assert python_class in ("TypeError", "ValueError", "DataError", "NumericalError", "MemoryError",
                                    "RuntimeError"), (name, python_class)
            continue
        cls = getattr(spdfit, python_class)
        assert issubclass(cls, spdfit.SpdfitWarning) and issubclass(cls, UserWarning), name
        assert python_class in spdfit.__all__
    assert spdfit.RankDeficientWarning is not spdfit.NotConvergedWarning


def test_a_warning_is_issued_with_its_codes_class():
    # A rank-deficient A: ls says so with RankDeficientWarning, and filtering that class alone
    # silences it.
    A = np.array([[1.0, 2], [2, 4], [3, 6], [4, 8]])
    B = np.array([[1.0, 0], [0, 1], [1, 1], [2, 1]])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = spdfit.least_squares(A, B)
    kinds = {type(w.message) for w in caught}
    assert spdfit.RankDeficientWarning in kinds
    assert "rank_deficient" in result.warning_codes
    assert len(result.warning_codes) == len(result.warnings)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        warnings.simplefilter("ignore", spdfit.RankDeficientWarning)
        spdfit.least_squares(A, B)
    assert not any(isinstance(w.message, spdfit.RankDeficientWarning) for w in caught)


def test_errors_are_raised_as_their_codes_class():
    A = np.random.default_rng(1).normal(size=(20, 3))
    B = A @ np.diag([1.0, 2, 3])
    # Usage: an option's value out of range, or of the wrong type.
    with pytest.raises(ValueError) as info:
        spdfit.fit(A, B, "spd-tls", max_iter=0)
    assert not isinstance(info.value, spdfit.DataError)
    with pytest.raises(TypeError):
        spdfit.fit(A, B, "spd-tls", max_iter="ten")
    # Data: a noise model the data refuse is a DataError (a ValueError), as the command line's exit 1.
    indefinite = np.array([[1.0, 2, 0], [2, 1, 0], [0, 0, 1]])
    model = None
    with pytest.raises(spdfit.DataError):
        model = spdfit.NoiseModel(cov_a=indefinite, cov_b=np.eye(3))
    assert model is None
    # NaN in memory: the library's refusal of data, a DataError.
    A_nan = A.copy()
    A_nan[0, 0] = np.nan
    with pytest.raises(spdfit.DataError):
        spdfit.fit(A_nan, B, "spde")


def test_identify_follows_the_librarys_rules():
    sim = hx.simulate(samples=60, noise_var=0.1, truth=hx.cubic_geometry(), seed=2)
    # physical needs a geometry, in Python as on the command line.
    with pytest.raises(ValueError, match="geometry"):
        hx.identify(sim.A, sim.B, physical=True)
    # A physical fit's option without physical=True: a usage error naming both.
    with pytest.raises(ValueError, match="fit_strut_mass.*physical"):
        hx.identify(sim.A, sim.B, fit_strut_mass="common")
    # geometry and stiffness exclude each other.
    with pytest.raises(ValueError, match="geometry.*stiffness|stiffness.*geometry"):
        hx.identify(sim.A, sim.B, geometry=hx.cubic_geometry(), stiffness=1e6)
    # The stiffness as one number for every strut: the modes of K = k I.
    out = hx.identify(sim.A, sim.B, stiffness=2e6)
    X = out["spd-tls"].result.X
    expected = np.sqrt(np.linalg.eigvalsh(np.linalg.solve(X, 2e6 * np.eye(6)))) / (2 * np.pi)
    np.testing.assert_allclose(np.sort(out["spd-tls"].modes_hz), np.sort(expected), rtol=1e-10)


def outcome_table():
    """docs/errors.md's table of codes, as the library's table gives it."""
    lines = ["| code | kind | command line | Python | MATLAB | meaning |", "|---|---|---|---|---|---|"]
    for name, tier, python_class, matlab, meaning in spdfit.outcome_codes():
        exit_status = {"usage": "exit 2", "warning": "warning on stderr, exit 0"}.get(tier, "exit 1")
        python = f"`spdfit.{python_class}`" if python_class in ("DataError", "NumericalError") or \
            python_class.endswith("Warning") else f"`{python_class}`"
        lines.append(f"| `{name}` | {tier} | {exit_status} | {python} | `{matlab}` | {meaning} |")
    return "\n".join(lines) + "\n"


def test_the_docs_table_is_the_librarys():
    text = (ROOT / "docs" / "errors.md").read_text()
    table = outcome_table()
    if os.environ.get("SPDFIT_REGENERATE_OUTCOMES") == "1":
        start = text.index("| code | kind |")
        end = text.index("\n\n", start) + 1
        (ROOT / "docs" / "errors.md").write_text(text[:start] + table + text[end:])
        return
    assert table in text, "docs/errors.md's table of outcome codes differs from spdfit.outcome_codes(); " \
                          "regenerate it with SPDFIT_REGENERATE_OUTCOMES=1"
