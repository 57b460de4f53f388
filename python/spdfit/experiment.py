"""The Monte Carlo experiments of the source documents. Trials run on all cores (threads=0) and
a given seed gives the same numbers whatever the number of threads.

    thesis(noise_var)          the thesis' chapter 6: ||M_p - M_hat||_F per method over trials
    paper_hexapod()            the paper's Figure 2: per-entry error statistics, Procrustes vs SPDE
    paper_2x2(std_a)           the paper's second example (Figure 3) at one noise level
    paper_2x2_sweep()          the same for std_a = 0, 0.1, ..., 1.9
    physical()                 physical identification of the payload against the generic methods
"""
from ._common import _as_matrix, _takes_options
from ._records import PhysicalExperiment, record as _record
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

__all__ = ["EntryExperimentResult", "EntryStatistics", "MethodErrors", "PairedComparison", "PhysicalExperiment",
           "SIGNIFICANCE", "Summary",
           "THESIS_NOISE_VARIANCES", "THESIS_REPORTED", "ThesisExperimentResult", "paper_2x2", "paper_2x2_sweep",
           "paper_hexapod", "physical", "thesis"]


@_takes_options("experiment.thesis", given=("noise_var",))
def thesis(noise_var=None, *, truth=None, **options):
    """The thesis' experiment (M_p of eq. 6.1, appendix-B generator) repeated `trials` times.

    The options are `spdfit experiment thesis`'s, and the same options give the same numbers.

    Parameters
    ----------
    noise_var : float, optional
        The noise variance V in every entry of A and B (the thesis' experiments 1-3:
        THESIS_NOISE_VARIANCES); or the per-column deviations noise_std_a and noise_std_b.
    truth : array_like, optional
        The true matrix (default M_p of eq. 6.1).
    {options}

    Returns
    -------
    ThesisExperimentResult
        .methods is a list (one per method and noise model, in the order asked) with .method,
        .errors (||M_p - M_hat||_F per trial, NaN where the method failed) and .summary (mean,
        std, median, max, standard_error).

    Raises
    ------
    ValueError
        Bad options: no noise, a negative variance, trials < 1, an unknown distribution or method,
        a method listed twice, fit_noise "rest" without rest_samples.
    TypeError
        An option the experiment does not take, or a value of the wrong type.

    Examples
    --------
    >>> import spdfit.experiment as ex
    >>> r = ex.thesis(0.86, trials=20, seed=1, methods=["procrustes", "spde"])
    >>> [(m.method, m.errors.shape) for m in r.methods]
    [('procrustes', (20,)), ('spde', (20,))]
    >>> r.methods[1].summary.count
    20
    """
    if noise_var is not None:
        options["noise_var"] = noise_var
    return _core.run("experiment.thesis", options, None if truth is None else _as_matrix("truth", truth))


@_takes_options("experiment.paper_hexapod")
def paper_hexapod(**options):
    """The paper's Figure 2 on simulated data.

    For the 21 independent entries of M_p, the mean (bias), mean absolute value and standard
    deviation of the estimation error over the trials, Procrustes against SPDE. The options are
    `spdfit experiment paper-hexapod`'s.

    Parameters
    ----------
    {options}

    Returns
    -------
    EntryExperimentResult
        Per method (.methods) the statistics of each entry (.mae, .std, .bias); the entries (i, j)
        in .entries.

    Raises
    ------
    ValueError
        Bad options: a negative variance, trials < 1, an unknown method, a method listed twice.

    Examples
    --------
    >>> import spdfit.experiment as ex
    >>> r = ex.paper_hexapod(trials=10)
    >>> [s.method for s in r.methods], len(r.entries), r.methods[0].mae.shape
    (['procrustes', 'spde'], 21, (21,))
    """
    return _core.run("experiment.paper_hexapod", options)


@_takes_options("experiment.paper_2x2", given=("std_a",))
def paper_2x2(std_a, **options):
    """The paper's second example at one noise level.

    X = [3 1; 1 1], A = A0 + N(0, std_a^2), B = A0 X + N(0, std_b^2); per method (procrustes, tls,
    spde) the mean absolute error (.mae), its standard deviation (.std) and the bias of x11, x12,
    x22. The options are `spdfit experiment paper-2x2`'s.

    Parameters
    ----------
    std_a : float
        The noise standard deviation in A.
    {options}

    Returns
    -------
    EntryExperimentResult
        Per method (.methods) the statistics of x11, x12 and x22 (.entries).

    Raises
    ------
    ValueError
        Bad options: a negative or non-finite standard deviation, trials < 1, an unknown method.

    Examples
    --------
    >>> import spdfit.experiment as ex
    >>> r = ex.paper_2x2(0.5, trials=200)
    >>> [s.method for s in r.methods], r.entries
    (['procrustes', 'tls', 'spde'], [(0, 0), (0, 1), (1, 1)])
    """
    options["std_a"] = std_a
    return _core.run("experiment.paper_2x2", options)


@_takes_options("experiment.paper_2x2_sweep")
def paper_2x2_sweep(levels=None, **options):
    """paper_2x2 at each std_a in `levels`: the paper's Figure 3.

    Trial k draws the same standard normal numbers at every level (common random numbers), as
    `spdfit experiment paper-2x2 --sweep`.

    Parameters
    ----------
    levels : iterable of float, optional
        The values of std_a (default 0, 0.1, ..., 1.9: the paper's Figure 3).
    {options}

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
    return list(zip(levels, _core.run("experiment.paper_2x2_sweep", options, None, levels)))


@_takes_options("experiment.physical")
def physical(**options):
    """Physical identification of the hexapod's payload against the generic estimators.

    The error ||M_hat - M_p||_F of M_p over m on the thesis' set-up (the built-in hexapod and its
    nominal payload, uniform noise, unless geometry and the payload options say otherwise), for
    generic methods and the physical variants ("physical": errors in variables, physically
    consistent; "physical-ls"; "grey-box-tls" and "grey-box-ls", the same model unconstrained).
    The options are `spdfit experiment physical`'s, and the same options give the same numbers.

    Parameters
    ----------
    {options}

    Returns
    -------
    PhysicalExperiment
        The JSON of `spdfit experiment physical --json`: "rows", one per m, each with "samples",
        "methods" ({name: {"mean", "standard_error", ..., "inconsistent"}}), "best_generic" and
        "physical_ratio" (physical's mean error over the best generic method's).

    Raises
    ------
    ValueError
        An unknown method or variant, m < 6, bad noise or trials, a payload that is not a body.

    Examples
    --------
    >>> import spdfit.experiment as ex
    >>> r = ex.physical(samples=[30], trials=20, seed=1)
    >>> row = r["rows"][0]
    >>> row["best_generic"] in ("spde", "spd-tls"), row["physical_ratio"] < 1, row["methods"]["physical"]["inconsistent"]
    (True, True, 0)
    """
    import json

    return _record(PhysicalExperiment, json.loads(_core.run("experiment.physical", options)))
