"""The Monte Carlo experiments of the source documents. Trials run on all cores (threads=0) and
a given seed gives the same numbers whatever the number of threads.

    thesis(noise_var)          the thesis' chapter 6: ||M_p - M_hat||_F per method over trials
    paper_hexapod()            the paper's Figure 2: per-entry error statistics, Procrustes vs SPDE
    paper_2x2(std_a)           the paper's second example (Figure 3) at one noise level
    paper_2x2_sweep()          the same for std_a = 0, 0.1, ..., 1.9
    physical()                 physical identification of the payload against the generic methods
"""
from ._common import _as_matrix
from ._spdfit import experiment as _core

# The result classes (the library's), under the names the type stubs give them.
Summary = _core.Summary
MethodErrors = _core.MethodErrors
ThesisExperimentResult = _core.ThesisExperimentResult
EntryStatistics = _core.EntryStatistics
EntryExperimentResult = _core.EntryExperimentResult
PairedComparison = _core.PairedComparison

# How many standard errors of the paired mean difference make a difference real (the library's
# rule: PairedComparison.order, the statements of `spdfit demo`).
SIGNIFICANCE = _core.SIGNIFICANCE

# The thesis' experiments 1-3: noise variances (its M-file's nm = 1, 3.2, 3.9; V = nm^2 / 12), as
# the library's table of its reported runs gives them.
THESIS_NOISE_VARIANCES = tuple(run[1] for run in _core.THESIS_REPORTED_RUNS)

# The thesis' single runs (eq. 6.6-6.22): {experiment: (V, procrustes, tls-sym, spde)}, from the
# library's table (experiment::kThesisReportedRuns).
THESIS_REPORTED = {run[0]: tuple(run[1:]) for run in _core.THESIS_REPORTED_RUNS}

# The library's defaults (the thesis' chapter-6 set-up, the paper's), not retyped here.
_DEFAULTS = _core.DEFAULTS

__all__ = ["EntryExperimentResult", "EntryStatistics", "MethodErrors", "PairedComparison", "SIGNIFICANCE", "Summary",
           "THESIS_NOISE_VARIANCES", "THESIS_REPORTED", "ThesisExperimentResult", "paper_2x2", "paper_2x2_sweep",
           "paper_hexapod", "physical", "thesis"]


def _names(methods):
    """None, or the method names as a list of str (a single name is accepted too)."""
    if methods is None:
        return None
    return [methods] if isinstance(methods, str) else [str(m) for m in methods]


def thesis(noise_var, *, samples=_DEFAULTS["samples"], trials=1000, seed=1, threads=0, force_noise_var=None,
           signal_var=_DEFAULTS["signal_var"], distribution=_DEFAULTS["distribution"], truth=None, methods=None):
    """The thesis' experiment (M_p of eq. 6.1, appendix-B generator) repeated `trials` times.

    Same numbers as `spdfit experiment thesis --noise-var V --trials N --seed S`.

    Parameters
    ----------
    noise_var : float
        The noise variance V in every entry of A and B (the thesis' experiments 1-3:
        THESIS_NOISE_VARIANCES).
    samples : int, optional
        The samples per trial (the library's default, the thesis' 12).
    trials : int, default 1000
        The number of Monte Carlo trials.
    seed : int, default 1
        The random seed: the same seed gives the same numbers.
    threads : int, default 0
        Threads for the trials (0: one per core); the numbers do not depend on it.
    force_noise_var : float, optional
        The noise variance in B, when it differs from noise_var.
    signal_var : float, optional
        The variance of the true accelerations (the library's default).
    distribution : str, optional
        The noise: "uniform" (the thesis') or "gaussian".
    truth : array_like, optional
        The true matrix (default M_p of eq. 6.1).
    methods : str or list of str, optional
        The method names to run (default: all six), as `--methods`.

    Returns
    -------
    ThesisExperimentResult
        .methods is a list (one per method, in spdfit.METHODS order) with .method, .errors
        (||M_p - M_hat||_F per trial, NaN where the method failed) and .summary (mean, std, median,
        max, standard_error).

    Raises
    ------
    ValueError
        Bad options: a negative variance, trials < 1, an unknown distribution or method, no methods.

    Examples
    --------
    >>> import spdfit.experiment as ex
    >>> r = ex.thesis(0.86, trials=20, seed=1, methods=["procrustes", "spde"])
    >>> [(m.method, m.errors.shape) for m in r.methods]
    [('procrustes', (20,)), ('spde', (20,))]
    >>> r.methods[1].summary.count
    20
    """
    return _core.thesis(float(noise_var), int(samples), int(trials), int(seed), int(threads),
                        None if force_noise_var is None else float(force_noise_var), float(signal_var),
                        distribution, None if truth is None else _as_matrix("truth", truth), _names(methods))


def paper_hexapod(*, noise_var=_DEFAULTS["paper_hexapod_noise_var"], samples=_DEFAULTS["paper_hexapod_samples"],
                  trials=100, seed=1, threads=0, methods=None):
    """The paper's Figure 2 on simulated data.

    For the 21 independent entries of M_p, the mean (bias), mean absolute value and standard
    deviation of the estimation error over the trials, Procrustes against SPDE.

    Parameters
    ----------
    noise_var : float, optional
        The noise variance (the library's default, the paper's).
    samples : int, optional
        The samples per trial (the library's default, the paper's).
    trials : int, default 100
        The number of Monte Carlo trials.
    seed : int, default 1
        The random seed: the same seed gives the same numbers.
    threads : int, default 0
        Threads for the trials (0: one per core); the numbers do not depend on it.
    methods : str or list of str, optional
        The method names to run (default: procrustes and spde).

    Returns
    -------
    EntryExperimentResult
        Per method (.methods) the statistics of each entry (.mae, .std, .bias); the entries (i, j)
        in .entries.

    Raises
    ------
    ValueError
        Bad options: a negative variance, trials < 1, an unknown method, no methods.

    Examples
    --------
    >>> import spdfit.experiment as ex
    >>> r = ex.paper_hexapod(trials=10)
    >>> [s.method for s in r.methods], len(r.entries), r.methods[0].mae.shape
    (['procrustes', 'spde'], 21, (21,))
    """
    return _core.paper_hexapod(float(noise_var), int(samples), int(trials), int(seed), int(threads), _names(methods))


def paper_2x2(std_a, *, std_b=_DEFAULTS["paper_2x2_std_b"], trials=10000, seed=1, threads=0, methods=None):
    """The paper's second example at one noise level.

    X = [3 1; 1 1], A = A0 + N(0, std_a^2), B = A0 X + N(0, std_b^2); per method (procrustes, tls,
    spde) the mean absolute error (.mae), its standard deviation (.std) and the bias of x11, x12,
    x22.

    Parameters
    ----------
    std_a : float
        The noise standard deviation in A.
    std_b : float, optional
        The noise standard deviation in B (the library's default, the paper's).
    trials : int, default 10000
        The number of Monte Carlo trials.
    seed : int, default 1
        The random seed: the same seed gives the same numbers.
    threads : int, default 0
        Threads for the trials (0: one per core); the numbers do not depend on it.
    methods : str or list of str, optional
        The method names to run (default: procrustes, tls and spde).

    Returns
    -------
    EntryExperimentResult
        Per method (.methods) the statistics of x11, x12 and x22 (.entries).

    Raises
    ------
    ValueError
        Bad options: a negative or non-finite standard deviation, trials < 1, an unknown method, no
        methods.

    Examples
    --------
    >>> import spdfit.experiment as ex
    >>> r = ex.paper_2x2(0.5, trials=200)
    >>> [s.method for s in r.methods], r.entries
    (['procrustes', 'tls', 'spde'], [(0, 0), (0, 1), (1, 1)])
    """
    return _core.paper_2x2(float(std_a), float(std_b), int(trials), int(seed), int(threads), _names(methods))


def paper_2x2_sweep(levels=None, *, std_b=_DEFAULTS["paper_2x2_std_b"], trials=10000, seed=1, threads=0,
                    methods=None):
    """paper_2x2 at each std_a in `levels`: the paper's Figure 3.

    Parameters
    ----------
    levels : iterable of float, optional
        The values of std_a (default 0, 0.1, ..., 1.9: the paper's Figure 3).
    std_b : float, optional
        As in paper_2x2.
    trials : int, default 10000
        The number of Monte Carlo trials.
    seed : int, default 1
        The random seed: the same seed gives the same numbers.
    threads : int, default 0
        Threads for the trials (0: one per core); the numbers do not depend on it.
    methods : str or list of str, optional
        As in paper_2x2.

    Returns
    -------
    list of tuple of (float, EntryExperimentResult)
        (std_a, result) in the order of the levels.

    Raises
    ------
    ValueError
        Bad options, as in paper_2x2.

    Examples
    --------
    >>> import spdfit.experiment as ex
    >>> sweep = ex.paper_2x2_sweep([0.0, 0.5], trials=50)
    >>> [(level, [s.method for s in r.methods]) for level, r in sweep]
    [(0.0, ['procrustes', 'tls', 'spde']), (0.5, ['procrustes', 'tls', 'spde'])]
    """
    levels = list(_core.paper_2x2_sweep_levels() if levels is None else map(float, levels))
    return list(zip(levels, _core.paper_2x2_sweep(levels, float(std_b), int(trials), int(seed), int(threads),
                                                  _names(methods))))


def physical(*, samples=None, noise_var=None, trials=200, seed=1, threads=0, methods=None):
    """Physical identification of the hexapod's payload against the generic estimators.

    The error ||M_hat - M_p||_F of M_p over m on the thesis' set-up (the built-in hexapod and its
    nominal payload, uniform noise), for generic methods and the physical variants ("physical":
    errors in variables, physically consistent; "physical-ls"; "grey-box-tls" and "grey-box-ls",
    the same model unconstrained). Same numbers as `spdfit experiment physical --json`.

    Parameters
    ----------
    samples : list of int, optional
        The numbers of samples m (default 12, 30, 100, 1000).
    noise_var : float, optional
        The noise variance in every entry of A and B (default 3.2^2 / 12: uniform of width 3.2).
    trials : int, default 200
        Monte Carlo trials per m.
    seed : int, default 1
        The random seed.
    threads : int, default 0
        Threads for the trials (0: one per core); the numbers do not depend on it.
    methods : list of str, optional
        Generic method names and physical variants, as `--methods` (default spde, spd-tls,
        physical, grey-box-ls, grey-box-tls).

    Returns
    -------
    dict
        The JSON of `spdfit experiment physical --json`: "rows", one per m, each with "samples",
        "methods" ({name: {"mean", "standard_error", ..., "inconsistent"}}), "best_generic" and
        "physical_ratio" (physical's mean error over the best generic method's).

    Raises
    ------
    ValueError
        An unknown method or variant, m < 6, bad noise or trials.

    Examples
    --------
    >>> import spdfit.experiment as ex
    >>> r = ex.physical(samples=[30], trials=20, seed=1)
    >>> row = r["rows"][0]
    >>> row["best_generic"] in ("spde", "spd-tls"), row["physical_ratio"] < 1, row["methods"]["physical"]["inconsistent"]
    (True, True, 0)
    """
    import json

    text = _core.physical(None if samples is None else [int(m) for m in samples],
                          None if noise_var is None else float(noise_var), int(trials), int(seed), int(threads),
                          _names(methods))
    return json.loads(text)
