"""The front ends agree: one table of cases, each run through the command line (`--json`), Python
and GNU Octave (the MATLAB package), comparing the numbers bit for bit and the outcome's tier
(success, usage error, data error, numerical failure). A new command or option gets one row here.

The CLI reads the data from CSV files written with 17 significant digits (exact round trips);
Python gets the same arrays; Octave reads them from raw float64 files. All Octave cases run in one
Octave process (its start-up costs seconds). Octave's part is skipped, saying so, when the MEX was
not built (SPDFIT_MATLAB_DIR unset)."""

import json
import os
import subprocess
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Optional

import numpy as np
import pytest

import spdfit
import spdfit.experiment as experiment
import spdfit.hexapod as hexapod
import spdfit.linkage as linkage
import spdfit.payload as payload
import spdfit.physical as physical

SOURCE = Path(os.environ.get("SPDFIT_SOURCE_DIR", Path(__file__).resolve().parents[2]))
CLI = os.environ.get("SPDFIT_CLI")
MATLAB_DIR = os.environ.get("SPDFIT_MATLAB_DIR")
OCTAVE = os.environ.get("SPDFIT_OCTAVE", "octave-cli")

# The tier of each outcome in each front end (docs/errors.md, "Outcome codes").
CLI_EXIT = {"ok": 0, "usage": 2, "data": 1, "numerical": 1}
MATLAB_ID = {"ok": "ok", "usage": "spdfit:UsageError", "data": "spdfit:DataError",
             "numerical": "spdfit:NumericalError"}


def python_tier(error):
    if error is None:
        return "ok"
    if isinstance(error, spdfit.DataError):
        return "data"
    if isinstance(error, spdfit.NumericalError):
        return "numerical"
    if isinstance(error, (TypeError, ValueError)):
        return "usage"
    return "other: " + type(error).__name__


@dataclass
class Case:
    name: str
    outcome: str  # "ok", "usage", "data" or "numerical"
    cli: Optional[list]  # arguments; {A}, {B}, ... are the data files
    python: Optional[Callable]  # f(data) -> the compared value
    octave: Optional[str]  # statements setting v, the compared value
    json_path: tuple = ()  # where the compared value is in the CLI's JSON
    code: Optional[str] = None  # the Python exception's code, for errors
    rtol: float = 0.0  # 0: bit for bit
    # Octave against the CLI: 0 is bit for bit. Inside Octave the MEX's LAPACK calls resolve to the
    # LAPACK Octave loaded, whose eigensolver can differ from the CLI's in the last bits.
    octave_rtol: float = 0.0
    extra: dict = field(default_factory=dict)


def get(doc, path):
    for key in path:
        doc = key(doc) if callable(key) else doc[key]
    return np.asarray(doc, dtype=float)


def method(name):
    """A selector for get(): the entry of a list of results whose "method" is name."""
    return lambda results: next(r for r in results if r["method"] == name)


CASES = [
    # fit
    Case("fit spde", "ok", ["fit", "--method", "spde", "--json", "{A}", "{B}"],
         lambda d: spdfit.fit(d["A"], d["B"], "spde").X, "v = spdfit.fit(A, B, 'spde');", ("X",)),
    Case("fit spd-tls with noise standard deviations", "ok",
         ["fit", "--method", "spd-tls", "--noise-std-a", "0.01,0.02,0.03", "--noise-std-b", "0.1", "--json", "{A}",
          "{B}"],
         lambda d: spdfit.fit(d["A"], d["B"], "spd-tls",
                                     noise=spdfit.NoiseModel.from_std([0.01, 0.02, 0.03], 0.1)).X,
         "v = spdfit.fit(A, B, 'spd-tls', 'NoiseStdA', [0.01 0.02 0.03], 'NoiseStdB', 0.1);", ("X",)),
    Case("fit auto with a bootstrap", "ok",
         ["fit", "--method", "auto", "--bootstrap", "20", "--seed", "3", "--json", "{A}", "{B}"],
         lambda d: spdfit.fit(d["A"], d["B"], "auto", bootstrap=20, seed=3).standard_errors,
         "[~, info] = spdfit.fit(A, B, 'auto', 'Bootstrap', 20, 'Seed', 3); v = info.standard_errors;",
         ("standard_errors",)),
    Case("fit: an unknown method", "usage", ["fit", "--method", "nonsense", "{A}", "{B}"],
         lambda d: spdfit.fit(d["A"], d["B"], "nonsense"), "v = spdfit.fit(A, B, 'nonsense');", code="option_value"),
    Case("fit: a confidence outside (0, 1)", "usage",
         ["fit", "--method", "spde", "--bootstrap", "10", "--confidence", "1.5", "{A}", "{B}"],
         lambda d: spdfit.fit(d["A"], d["B"], "spde", bootstrap=10, confidence=1.5),
         "v = spdfit.fit(A, B, 'spde', 'Bootstrap', 10, 'Confidence', 1.5);", code="option_value"),
    Case("fit: a noise model for a method without one", "usage",
         ["fit", "--method", "spde", "--noise-std-a", "0.1", "--noise-std-b", "0.1", "{A}", "{B}"],
         lambda d: spdfit.fit(d["A"], d["B"], "spde", noise=spdfit.NoiseModel.from_std(0.1, 0.1)),
         "v = spdfit.fit(A, B, 'spde', 'NoiseStdA', 0.1, 'NoiseStdB', 0.1);"),
    Case("fit: A's and B's rows differ", "data", ["fit", "--method", "ls", "{A}", "{B_short}"],
         lambda d: spdfit.fit(d["A"], d["B_short"], "ls"), "v = spdfit.fit(A, B_short, 'ls');", code="data_shape"),
    Case("fit: a noise covariance that is not one", "data",
         ["fit", "--method", "spd-tls", "--noise-cov-a", "{Cbad}", "--noise-cov-b", "{I3}", "{A}", "{B}"],
         lambda d: spdfit.fit(d["A"], d["B"], "spd-tls", noise=spdfit.NoiseModel(cov_a=d["Cbad"], cov_b=d["I3"])),
         "v = spdfit.fit(A, B, 'spd-tls', 'NoiseCovA', Cbad, 'NoiseCovB', I3);", code="noise_model_refused"),
    # nearest
    Case("nearest", "ok", ["nearest", "--json", "{C}"], lambda d: spdfit.nearest_spd(d["C"]),
         "v = spdfit.nearest(C);", ("X",)),
    Case("nearest --corr", "ok", ["nearest", "--corr", "--json", "{C}"], lambda d: spdfit.nearest_correlation(d["C"]),
         "v = spdfit.nearest(C, 'Corr', true);", ("X",), octave_rtol=1e-13),
    Case("nearest: a negative relative floor", "usage", ["nearest", "--min-eig-rel", "-1", "{C}"],
         lambda d: spdfit.nearest_spd(d["C"], min_eig_rel=-1.0), "v = spdfit.nearest(C, 'MinEigRel', -1);",
         code="option_value"),
    # solve
    Case("solve, rank-deficient", "ok", ["solve", "--json", "{As}", "{bs}"],
         lambda d: spdfit.solve(d["As"], d["bs"]).solution, "v = spdfit.solve(As, bs);", ("solution",)),
    Case("solve: b's rows are not A's", "data", ["solve", "{As}", "{B_short}"],
         lambda d: spdfit.solve(d["As"], d["B_short"]), "v = spdfit.solve(As, B_short);", code="data_shape"),
    # hexapod identify
    Case("hexapod identify", "ok", ["hexapod", "identify", "--json", "{Ah}", "{Bh}"],
         lambda d: hexapod.identify(d["Ah"], d["Bh"])["spd-tls"].result.X,
         "r = spdfit.hexapod.identify(Ah, Bh); v = r.methods.spd_tls.X;", ("methods", "spd-tls", "X")),
    Case("hexapod identify --physical", "ok",
         ["hexapod", "identify", "--physical", "--geometry", "{G}", "--json", "{Ah}", "{Bh}"],
         lambda d: hexapod.identify(d["Ah"], d["Bh"], physical=True, geometry=d["G"])["physical"]["M_p"],
         "r = spdfit.hexapod.identify(Ah, Bh, 'Physical', true, 'Geometry', G); v = r.physical.M_p;",
         ("physical", "M_p")),
    Case("hexapod identify --physical --unconstrained", "ok",
         ["hexapod", "identify", "--physical", "--unconstrained", "--geometry", "{G}", "--json", "{Ah}", "{Bh}"],
         lambda d: hexapod.identify(d["Ah"], d["Bh"], physical=True, consistent=False,
                                    geometry=d["G"])["physical"]["M_p"],
         "r = spdfit.hexapod.identify(Ah, Bh, 'Physical', true, 'Consistent', false, 'Geometry', G); "
         "v = r.physical.M_p;", ("physical", "M_p")),
    Case("hexapod identify: physical without a geometry", "usage", ["hexapod", "identify", "--physical", "{Ah}", "{Bh}"],
         lambda d: hexapod.identify(d["Ah"], d["Bh"], physical=True),
         "r = spdfit.hexapod.identify(Ah, Bh, 'Physical', true);"),
    Case("hexapod identify: a physical option without physical", "usage",
         ["hexapod", "identify", "--strut-masses", "common", "{Ah}", "{Bh}"],
         lambda d: hexapod.identify(d["Ah"], d["Bh"], fit_strut_mass="common"),
         "r = spdfit.hexapod.identify(Ah, Bh, 'StrutMasses', 'common');"),
    Case("hexapod identify: a truth of the wrong size", "data",
         ["hexapod", "identify", "--truth", "{I3}", "{Ah}", "{Bh}"],
         lambda d: hexapod.identify(d["Ah"], d["Bh"], truth=d["I3"]),
         "r = spdfit.hexapod.identify(Ah, Bh, 'Truth', I3);"),
    # hexapod model (no MATLAB function)
    Case("hexapod model", "ok", ["hexapod", "model", "--json"], lambda d: hexapod.model().mass_matrix, None,
         ("mass_matrix",)),
    Case("hexapod model --geometry", "ok", ["hexapod", "model", "--geometry", "{G}", "--json"],
         lambda d: hexapod.model(d["G"]).modes_hz, None, ("modes_hz",)),
    Case("hexapod model: no such geometry file", "data", ["hexapod", "model", "--geometry", "{G}.missing"],
         lambda d: hexapod.model(d["G"] + ".missing"), None),
    # physical regress
    Case("physical regress", "ok", ["physical", "regress", "--json", "{Y}", "{tau}"],
         lambda d: physical.regress(d["Y"], d["tau"])["parameters"],
         "r = spdfit.physical.regress(Y, tau); v = r.parameters;", ("parameters",), octave_rtol=1e-12),
    Case("physical regress --unconstrained", "ok", ["physical", "regress", "--unconstrained", "--json", "{Y}", "{tau}"],
         lambda d: physical.regress(d["Y"], d["tau"], unconstrained=True)["parameters"],
         "r = spdfit.physical.regress(Y, tau, 'Unconstrained', true); v = r.parameters;", ("parameters",),
         octave_rtol=1e-12),
    Case("physical regress: more bodies than Y's columns hold", "data", ["physical", "regress", "--bodies", "2", "{Y}", "{tau}"],
         lambda d: physical.regress(d["Y"], d["tau"], bodies=2),
         "r = spdfit.physical.regress(Y, tau, 'Bodies', 2);", code="data_shape"),
    Case("physical regress: a prior weight without a prior", "usage",
         ["physical", "regress", "--prior-weight", "2", "{Y}", "{tau}"],
         lambda d: physical.regress(d["Y"], d["tau"], prior_weight=2.0),
         "r = spdfit.physical.regress(Y, tau, 'PriorWeight', 2);", code="option_conflict"),
    # payload identify (static poses: gravity alone)
    Case("payload identify", "ok", ["payload", "identify", "--wrench-cols", "1:6", "--quat-cols", "7:10", "--json", "{W}"],
         lambda d: payload.identify(wrench=d["W"][:, :6], quaternion=d["W"][:, 6:10])["parameters"],
         "r = spdfit.payload.identify(W(:, 1:6), 'Quaternion', W(:, 7:10)); v = r.parameters;", ("parameters",),
         rtol=1e-12, octave_rtol=1e-12),
    Case("payload identify: quaternions and rotations both", "usage",
         ["payload", "identify", "--wrench-cols", "1:6", "--quat-cols", "7:10", "--rotation-cols", "1:9", "{W}"],
         lambda d: payload.identify(wrench=d["W"][:, :6], quaternion=d["W"][:, 6:10], rotation=np.tile(np.eye(3).ravel(), (len(d["W"]), 1))),
         None),
    # inertia repair (no MATLAB function)
    Case("inertia repair", "ok", ["inertia", "repair", "{body}"],
         lambda d: physical.inertia_repair(2.0, [0.01, 0.0, -0.02], np.diag([0.1, 0.2, 0.5]))["inertia"], None,
         ("inertia",)),
    Case("inertia repair --metric second-moment", "ok", ["inertia", "repair", "--metric", "second-moment", "{body}"],
         lambda d: physical.inertia_repair(2.0, [0.01, 0.0, -0.02], np.diag([0.1, 0.2, 0.5]),
                                           metric="second-moment")["inertia"], None, ("inertia",)),
    Case("inertia repair: a floor of 1", "usage", ["inertia", "repair", "--min-eig-rel", "1", "{body}"],
         lambda d: physical.inertia_repair(2.0, [0.01, 0.0, -0.02], np.diag([0.1, 0.2, 0.5]), min_eig_rel=1.0),
         None, code="option_value"),
    # linkage (no MATLAB function)
    Case("linkage synthesize --steering", "ok", ["linkage", "synthesize", "--steering", "--rho", "0.5", "--json"],
         lambda d: linkage.synthesize(steering=0.5).structural.k, None, ("structural", "k")),
    Case("linkage synthesize --function", "ok",
         ["linkage", "synthesize", "--function", "log10", "--x-range", "1:10", "--psi-range", "0:60", "--phi-range",
          "0:60", "--alpha", "90", "--beta", "90", "--json"],
         lambda d: linkage.synthesize(function="log10", x_range=(1, 10), psi_range=(0, 60), phi_range=(0, 60), alpha=90,
                                      beta=90).structural.k,
         None, ("structural", "k")),
    Case("linkage synthesize --pairs", "ok", ["linkage", "synthesize", "--pairs", "{pairs}", "--json"],
         lambda d: linkage.synthesize(d["pairs"][:, 0], d["pairs"][:, 1]).design.k, None, ("design", "k")),
    Case("linkage synthesize: no prescription", "usage", ["linkage", "synthesize"],
         lambda d: linkage.synthesize(), None),
    Case("linkage analyze", "ok", ["linkage", "analyze", "--lengths", "1,0.6,0.7,0.6", "--json"],
         lambda d: linkage.analyze([1, 0.6, 0.7, 0.6]).k, None, ("k",)),
    # Python's linkage takes the commands' tables and workflows: the same defaults (37 angles over
    # 0..360), ranges as (lo, hi), pairs and weights as arrays, and the same refusals.
    Case("linkage analyze: the default angles", "ok", ["linkage", "analyze", "--lengths", "4,1,3.5,3", "--json"],
         lambda d: [s.transmission_angle * 180 / np.pi for s in linkage.analyze([4, 1, 3.5, 3]).samples], None,
         ("samples", lambda rows: [r["transmission_angle_deg"] for r in rows]), rtol=1e-15),
    Case("linkage analyze --psi-range --points", "ok",
         ["linkage", "analyze", "--lengths", "4,1,3.5,3", "--psi-range", "-180:180", "--points", "361", "--json"],
         lambda d: [s.phi_plus * 180 / np.pi for s in linkage.analyze([4, 1, 3.5, 3], psi_range=(-180, 180),
                                                                        points=361).samples], None,
         ("samples", lambda rows: [r["phi_plus_deg"] for r in rows]), rtol=1e-15),
    Case("linkage analyze: LO >= HI", "usage", ["linkage", "analyze", "--lengths", "4,1,3.5,3", "--psi-range", "90:10"],
         lambda d: linkage.analyze([4, 1, 3.5, 3], psi_range=(90, 10)), None, code="option_value"),
    Case("linkage synthesize --pairs --weights", "ok",
         ["linkage", "synthesize", "--pairs", "{pairs}", "--weights", "{pair_weights}", "--json"],
         lambda d: linkage.synthesize(d["pairs"][:, 0], d["pairs"][:, 1], weights=d["pair_weights"]).structural.k,
         None, ("structural", "k")),
    Case("linkage synthesize --rho (steering implied)", "ok", ["linkage", "synthesize", "--rho", "0.5", "--json"],
         lambda d: linkage.synthesize(steering=0.5).structural.k, None, ("structural", "k")),
    Case("linkage synthesize: points with pairs", "usage",
         ["linkage", "synthesize", "--pairs", "{pairs}", "--points", "9"],
         lambda d: linkage.synthesize(d["pairs"][:, 0], d["pairs"][:, 1], points=9), None, code="option_conflict"),
    Case("linkage synthesize: a steering range with LO >= HI", "usage",
         ["linkage", "synthesize", "--rho", "0.5", "--psi-range", "30:-30"],
         lambda d: linkage.synthesize(steering=0.5, psi_range=(30, -30)), None, code="option_value"),
    Case("linkage synthesize: a weight that is not positive", "data",
         ["linkage", "synthesize", "--pairs", "{pairs}", "--weights", "{bad_weights}"],
         lambda d: linkage.synthesize(d["pairs"][:, 0], d["pairs"][:, 1], weights=d["bad_weights"]), None),
    # experiment thesis (no MATLAB function)
    Case("experiment thesis", "ok",
         ["experiment", "thesis", "--noise-var", "0.86", "--trials", "5", "--samples", "20", "--seed", "3", "--json"],
         lambda d: next(m.summary.mean for m in experiment.thesis(0.86, trials=5, samples=20, seed=3).methods
                        if m.method == "spde"), None, ("methods", "spde", "mean")),
    Case("experiment thesis: per-sensor noise, rest rows", "ok",
         ["experiment", "thesis", "--noise-std-a", "0.5", "--noise-std-b", "1,2,3,4,5,6", "--rest-samples", "10",
          "--fit-noise", "none,rest", "--methods", "spd-tls", "--trials", "5", "--json"],
         lambda d: next(m.summary.mean for m in experiment.thesis(
             noise_std_a=0.5, noise_std_b=[1, 2, 3, 4, 5, 6], rest_samples=10, fit_noise=["none", "rest"],
             methods=["spd-tls"], trials=5).methods if m.noise == "rest"), None, ("methods", "spd-tls/rest", "mean")),
    Case("experiment thesis: no noise", "usage", ["experiment", "thesis", "--trials", "5"],
         lambda d: experiment.thesis(trials=5), None),
    Case("experiment thesis: a method twice", "usage",
         ["experiment", "thesis", "--noise-var", "1", "--methods", "spde,spde"],
         lambda d: experiment.thesis(1.0, methods=["spde", "spde"]), None),
    Case("experiment paper-2x2", "ok", ["experiment", "paper-2x2", "--std-a", "0.5", "--trials", "50", "--json"],
         lambda d: experiment.paper_2x2(0.5, trials=50).methods[2].mae, None, ("methods", "spde", "mae")),
    Case("experiment physical", "ok",
         ["experiment", "physical", "--samples", "12", "--trials", "3", "--methods", "spde,physical",
          "--payload-mass", "15", "--json"],
         lambda d: experiment.physical(samples=[12], trials=3, methods=["spde", "physical"],
                                       payload_mass=15.0)["rows"][0]["methods"]["physical"]["mean"],
         None, ("rows", 0, "methods", "physical", "mean")),
    Case("experiment physical: a payload that is not a body", "usage",
         ["experiment", "physical", "--samples", "12", "--trials", "3", "--payload-mass", "-3"],
         lambda d: experiment.physical(samples=[12], trials=3, payload_mass=-3.0), None),
    # compare (no MATLAB function: the command line against Python's fit_all)
    Case("compare", "ok", ["compare", "--json", "{A}", "{B}"],
         lambda d: spdfit.fit_all(d["A"], d["B"])["spd-tls"].X, None,
         ("results", method("spd-tls"), "X")),
]


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    work = tmp_path_factory.mktemp("parity")
    rng = np.random.default_rng(41)
    X = np.array([[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]])
    A0 = rng.standard_normal((40, 3))
    d = {
        "A": A0 + 0.01 * rng.standard_normal((40, 3)),
        "B": A0 @ X + 0.1 * rng.standard_normal((40, 3)),
        "B_short": rng.standard_normal((7, 3)),
        "C": np.array([[2.0, -1.0, 0.0, 0.95], [-1.0, 2.0, -1.0, 0.0], [0.0, -1.0, 2.0, -1.0], [0.95, 0.0, -1.0, 2.0]]),
        "As": np.array([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]]),
        "bs": np.array([[6.0], [12.0], [2.0], [2.0]]),
        "Cbad": np.array([[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
        "I3": np.eye(3),
    }
    # linkage synthesize --pairs: the exact pairs (degrees) of a crank-rocker.
    d["pairs"] = spdfit.read_matrix(SOURCE / "examples" / "linkage" / "crank_rocker_pairs.csv")
    d["pair_weights"] = np.linspace(1.0, 2.0, len(d["pairs"]))
    d["bad_weights"] = np.r_[0.0, np.ones(len(d["pairs"]) - 1)]
    # physical regress: one body's 10 parameters (physically consistent) and a random regressor.
    phi = np.array([2.0, 0.02, -0.04, 0.06, 0.1, 0.001, 0.002, 0.12, 0.003, 0.09])
    d["Y"] = rng.standard_normal((60, 10))
    d["tau"] = (d["Y"] @ phi + 0.01 * rng.standard_normal(60))[:, None]
    # payload identify: a 1.5 kg payload at rest in 8 orientations; the sensor reads the load on it
    # (gravity's reaction) plus a bias and noise; columns fx..tz, qx, qy, qz, qw.
    mass, com = 1.5, np.array([0.01, -0.02, 0.05])
    q = rng.standard_normal((8, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    rows = []
    for x, y, z, w in q:
        R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                      [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                      [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
        g = R.T @ np.array([0.0, 0.0, -9.80665])
        f = mass * g
        wrench = np.concatenate([f, np.cross(com, f)]) + np.array([0.3, -0.2, 0.1, 0.01, 0.02, -0.01])
        rows.append(np.concatenate([wrench + 1e-3 * rng.standard_normal(6), [x, y, z, w]]))
    d["W"] = np.array(rows)
    d["Ah"] = spdfit.read_matrix(SOURCE / "examples" / "hexapod" / "A.csv")
    d["Bh"] = spdfit.read_matrix(SOURCE / "examples" / "hexapod" / "B.csv")
    files = {}
    for name, value in d.items():
        files[name] = work / f"{name}.csv"
        np.savetxt(files[name], np.atleast_2d(value), delimiter=",", fmt="%.17g")
        np.asarray(value, dtype="<f8").T.tofile(work / f"{name}.bin")  # column-major, as Octave reads
        (work / f"{name}.shape").write_text(" ".join(str(s) for s in np.atleast_2d(value).shape))
    body = work / "body.json"
    body.write_text(json.dumps({"mass": 2.0, "center_of_mass": [0.01, 0.0, -0.02],
                                "inertia": np.diag([0.1, 0.2, 0.5]).tolist()}))
    files["body"] = body
    geometry = work / "G.json"
    subprocess.run([CLI, "hexapod", "model", "--write-geometry", str(geometry)], check=True, capture_output=True)
    d["G"] = str(geometry)
    files["G"] = geometry
    return {"values": d, "files": files, "work": work}


def cli_outcome(case, data):
    args = [a.format(**{k: str(v) for k, v in data["files"].items()}) for a in case.cli]
    run = subprocess.run([CLI, *args], capture_output=True, text=True)
    value = None
    if run.returncode == 0 and case.json_path:
        value = get(json.loads(run.stdout), case.json_path)
    return run.returncode, value, run.stderr


def python_outcome(case, data):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            value = case.python(data["values"])
        except Exception as error:  # the tier is checked below
            return error, None
    return None, np.asarray(value, dtype=float)


def same(a, b, rtol):
    a, b = np.squeeze(np.asarray(a, dtype=float)), np.squeeze(np.asarray(b, dtype=float))
    if a.shape != b.shape:
        return False
    if rtol == 0.0:
        return np.array_equal(a, b, equal_nan=True)
    return np.allclose(a, b, rtol=rtol, atol=0.0, equal_nan=True)


@pytest.mark.skipif(not CLI, reason="SPDFIT_CLI is not set")
@pytest.mark.parametrize("case", [c for c in CASES if c.cli and c.python], ids=lambda c: c.name)
def test_cli_and_python_agree(case, data):
    status, cli_value, stderr = cli_outcome(case, data)
    error, py_value = python_outcome(case, data)
    assert status == CLI_EXIT[case.outcome], f"{case.name}: exit {status} ({stderr.strip()})"
    assert python_tier(error) == case.outcome, f"{case.name}: Python raised {error!r}"
    if error is not None and case.code is not None:
        assert getattr(error, "code", None) == case.code, f"{case.name}: {error!r} has code {getattr(error, 'code', None)}"
    if case.outcome == "ok" and case.json_path:
        assert same(cli_value, py_value, case.rtol), f"{case.name}: CLI {cli_value} Python {py_value}"
    if case.outcome != "ok":
        assert stderr.strip(), f"{case.name}: the CLI's error says nothing"


OCTAVE_SCRIPT = r"""
function parity_run(work, names, cases)
  for k = 1:numel(names)
    shape = str2num(fileread(fullfile(work, [names{k} '.shape'])));
    fid = fopen(fullfile(work, [names{k} '.bin']), 'r');
    value = reshape(fread(fid, Inf, 'double'), shape);
    fclose(fid);
    assignin('base', names{k}, value);
  end
  for k = 1:numel(cases)
    outcome = 'ok';
    v = [];
    try
      evalin('base', cases{k});
      v = evalin('base', 'v');
    catch err
      outcome = err.identifier;
      if isempty(outcome), outcome = ['(no identifier) ' err.message]; end
    end
    fid = fopen(fullfile(work, sprintf('octave_%d.txt', k)), 'w');
    fprintf(fid, '%s\n', outcome);
    fprintf(fid, '%d ', size(v));
    fclose(fid);
    fid = fopen(fullfile(work, sprintf('octave_%d.bin', k)), 'w');
    fwrite(fid, double(v), 'double');
    fclose(fid);
    evalin('base', 'clear v r');
  end
end
"""


@pytest.fixture(scope="module")
def octave_results(data):
    if not MATLAB_DIR:
        pytest.skip("SPDFIT_MATLAB_DIR is not set: the Octave MEX was not built")
    work = data["work"]
    cases = [c for c in CASES if c.octave]
    (work / "parity_run.m").write_text(OCTAVE_SCRIPT)
    names = [n for n in data["values"] if n != "G"]
    quote = lambda s: "'" + s.replace("'", "''") + "'"
    statements = [f"G = {quote(str(data['files']['G']))}; " + c.octave for c in cases]
    script = (f"addpath({quote(MATLAB_DIR)}); addpath({quote(str(work))}); "
              f"parity_run({quote(str(work))}, {{{', '.join(quote(n) for n in names)}}}, "
              f"{{{', '.join(quote(s) for s in statements)}}});")
    run = subprocess.run([OCTAVE, "--no-gui", "--norc", "--quiet", "--no-history", "--eval", script],
                         capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"), timeout=600)
    assert run.returncode == 0, run.stderr
    out = {}
    for k, case in enumerate(cases, start=1):
        outcome, shape = (work / f"octave_{k}.txt").read_text().split("\n")[:2]
        raw = np.fromfile(work / f"octave_{k}.bin", dtype="<f8")
        dims = [int(s) for s in shape.split()]
        out[case.name] = (outcome, raw.reshape(dims[::-1]).T if raw.size else raw)
    return out


@pytest.mark.skipif(not CLI, reason="SPDFIT_CLI is not set")
@pytest.mark.parametrize("case", [c for c in CASES if c.octave], ids=lambda c: c.name)
def test_octave_agrees(case, data, octave_results):
    outcome, value = octave_results[case.name]
    assert outcome == MATLAB_ID[case.outcome], f"{case.name}: Octave gave {outcome}"
    if case.outcome == "ok" and case.cli and case.json_path:
        _, cli_value, _ = cli_outcome(case, data)
        assert same(value, cli_value, case.octave_rtol), f"{case.name}: Octave {value} CLI {cli_value}"


def test_every_command_has_a_row():
    # The commands with a library workflow (issue 41); each has at least one case and, for those
    # with options, an error case.
    commands = {" ".join(a for a in c.cli[:2] if not a.startswith("-") and "{" not in a) for c in CASES if c.cli}
    for command in ("fit", "nearest", "solve", "hexapod identify", "hexapod model", "compare", "physical regress",
                    "payload identify", "inertia repair", "linkage synthesize", "linkage analyze", "experiment thesis",
                    "experiment paper-2x2", "experiment physical"):
        assert command in commands, command
        assert any(c.outcome != "ok" for c in CASES if c.cli and " ".join(c.cli[:2]).startswith(command)) or \
            command in ("compare", "linkage analyze", "experiment paper-2x2"), f"{command}: no error case"


# hexapod simulate writes files, not JSON: Python's spdfit.hexapod.simulate against the files the
# command line writes (CSV with 17 significant digits: exact), for the generator's options of
# data as logged (per-sensor noise, rows at rest, a preload, forces in kN) and a changed payload.
SIMULATIONS = [
    (["--noise-var", "0.86"], dict(noise_var=0.86)),
    (["--samples", "40", "--noise-std-a", "0.01,0.02,0.03,0.01,0.01,0.01", "--noise-std-b", "0.1",
      "--rest-samples", "20", "--scale-b", "0.001", "--preload", "21", "--seed", "7", "--distribution", "gaussian"],
     dict(samples=40, noise_std_a=[0.01, 0.02, 0.03, 0.01, 0.01, 0.01], noise_std_b=0.1, rest_samples=20,
          scale_b=0.001, preload=21.0, seed=7, distribution="gaussian")),
    (["--noise-var", "0.1", "--geometry", "{G}", "--payload-mass", "12.5", "--payload-com", "0.01,0,-0.02",
      "--payload-inertia", "0.1,0.12,0.09"],
     dict(noise_var=0.1, geometry="{G}", payload_mass=12.5, payload_com=[0.01, 0.0, -0.02],
          payload_inertia=[0.1, 0.12, 0.09])),
]


@pytest.mark.skipif(not CLI, reason="SPDFIT_CLI is not set")
@pytest.mark.parametrize("cli_args,keywords", SIMULATIONS, ids=["thesis", "as logged", "payload"])
def test_simulate_python_writes_what_the_cli_writes(cli_args, keywords, data, tmp_path):
    geometry = str(data["files"]["G"])
    args = [a.replace("{G}", geometry) for a in cli_args]
    run = subprocess.run([CLI, "hexapod", "simulate", *args, "--out", str(tmp_path)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    keywords = {k: (geometry if v == "{G}" else v) for k, v in keywords.items()}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sim = hexapod.simulate(**keywords)
    read = lambda name: np.loadtxt(tmp_path / name, delimiter=",", ndmin=2)
    assert np.array_equal(sim.A, read("A.csv")) and np.array_equal(sim.B, read("B.csv"))
    assert np.array_equal(sim.truth, read("truth.csv"))
    if "rest_samples" in keywords:
        assert np.array_equal(sim.rest_A, read("rest_A.csv")) and np.array_equal(sim.rest_B, read("rest_B.csv"))
    else:
        assert sim.rest_A.shape[0] == 0


@pytest.mark.skipif(not CLI, reason="SPDFIT_CLI is not set")
@pytest.mark.parametrize("cli_args,keywords,code", [
    (["--noise-var", "1", "--payload-mass", "3"], dict(noise_var=1.0, payload_mass=3.0), "option_conflict"),
    (["--noise-std-a", "1"], dict(noise_std_a=1.0), "option_conflict"),
    (["--noise-var", "1", "--preload", "1,2"], dict(noise_var=1.0, preload=[1.0, 2.0]), "option_value"),
    (["--noise-var", "1", "--geometry", "{G}", "--payload-mass", "-1"],
     dict(noise_var=1.0, geometry="{G}", payload_mass=-1.0), "option_value"),
], ids=["payload without geometry", "std of A alone", "preload count", "negative mass"])
def test_simulate_refuses_alike(cli_args, keywords, code, data, tmp_path):
    geometry = str(data["files"]["G"])
    run = subprocess.run([CLI, "hexapod", "simulate", *[a.replace("{G}", geometry) for a in cli_args], "--out",
                          str(tmp_path)], capture_output=True, text=True)
    assert run.returncode == 2, run.stderr
    with pytest.raises(ValueError) as error:
        hexapod.simulate(**{k: (geometry if v == "{G}" else v) for k, v in keywords.items()})
    assert getattr(error.value, "code", None) == code, error.value


# The results Python returns as records (spdfit._records: a class per result, its keys also its
# attributes) hold the command line's whole JSON document, key for key and number for number:
# (name, CLI arguments, Python, the document's place in the CLI's JSON, the keys only Python adds,
# rtol). Pickling gives the same class with the same items.
RECORDS = [
    ("hexapod identify --physical", ["hexapod", "identify", "--physical", "--geometry", "{G}", "--json", "{Ah}", "{Bh}"],
     lambda d: hexapod.identify(d["Ah"], d["Bh"], physical=True, geometry=d["G"])["physical"], ("physical",), (), 0.0,
     physical.PhysicalEstimate),
    ("physical regress", ["physical", "regress", "--json", "{Y}", "{tau}"],
     lambda d: physical.regress(d["Y"], d["tau"]), (), ("report",), 0.0, physical.RegressFit),
    ("inertia repair", ["inertia", "repair", "{body}"],
     lambda d: physical.inertia_repair(2.0, [0.01, 0.0, -0.02], np.diag([0.1, 0.2, 0.5])), (), (), 0.0,
     physical.InertiaRepair),
    ("payload identify", ["payload", "identify", "--wrench-cols", "1:6", "--quat-cols", "7:10", "--json", "{W}"],
     lambda d: payload.identify(wrench=d["W"][:, :6], quaternion=d["W"][:, 6:10]), (), ("residuals", "report"), 1e-12,
     payload.PayloadEstimate),
    ("payload design", ["payload", "design", "--quat-cols", "7:10", "--poses", "4", "--random", "30", "--json", "{W}"],
     lambda d: payload.design(quaternion=d["W"][:, 6:10], poses=4, random=30), (), ("report",), 1e-12,
     payload.PayloadDesign),
    ("experiment physical", ["experiment", "physical", "--samples", "12", "--trials", "3", "--methods", "spde,physical",
                             "--json"],
     lambda d: experiment.physical(samples=[12], trials=3, methods=["spde", "physical"]), (), (), 0.0,
     experiment.PhysicalExperiment),
]


def same_document(python, cli, rtol, where="document"):
    """Whether two JSON values agree: the same keys (in any order: hexapod identify's document
    sorts them), lists of the same length, numbers equal (or within rtol), null for null."""
    if isinstance(cli, dict):
        assert isinstance(python, dict) and sorted(python) == sorted(cli), f"{where}: keys {list(python)} and {list(cli)}"
        for key in cli:
            same_document(python[key], cli[key], rtol, f"{where}.{key}")
    elif isinstance(cli, list):
        assert isinstance(python, list) and len(python) == len(cli), f"{where}: {python} and {cli}"
        for k, (p, c) in enumerate(zip(python, cli)):
            same_document(p, c, rtol, f"{where}[{k}]")
    elif isinstance(cli, (int, float)) and not isinstance(cli, bool) and not isinstance(python, bool):
        assert isinstance(python, (int, float)), f"{where}: {python!r} and {cli!r}"
        assert python == cli or (rtol > 0 and abs(python - cli) <= rtol * abs(cli)), f"{where}: {python!r} and {cli!r}"
    else:
        assert python == cli, f"{where}: {python!r} and {cli!r}"


@pytest.mark.skipif(not CLI, reason="SPDFIT_CLI is not set")
@pytest.mark.parametrize("name,cli_args,python,path,python_keys,rtol,cls", RECORDS, ids=[r[0] for r in RECORDS])
def test_records_hold_the_cli_document(name, cli_args, python, path, python_keys, rtol, cls, data):
    import copy
    import pickle

    args = [a.format(**{k: str(v) for k, v in data["files"].items()}) for a in cli_args]
    run = subprocess.run([CLI, *args], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    document = json.loads(run.stdout)
    for key in path:
        document = document[key]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = python(data["values"])
    assert type(result) is cls
    plain = result.to_dict()
    for key in python_keys:
        assert key in plain, key
        del plain[key]
    same_document(plain, document, rtol)
    assert json.loads(result.to_json()) == result.to_dict()
    for key in result:  # the keys are attributes, read-only
        if key.isidentifier():
            assert getattr(result, key) is result[key]
    with pytest.raises(AttributeError, match="read-only"):
        result.status = "changed"
    for twin in (pickle.loads(pickle.dumps(result)), copy.deepcopy(result), copy.copy(result)):
        assert type(twin) is cls
        assert twin.to_json() == result.to_json()
