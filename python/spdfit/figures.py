"""The source documents' figures, reproduced from spdfit's own computations.

    /usr/bin/python3 -m spdfit.figures [--out DIR] [--format png|svg] [--only NAME ...] [--quick]

draws, into DIR (default ./figures):
  thesis_experiments   error ||M_p - M_hat||_F of each method at the thesis' three noise levels
                       (box plots over the Monte Carlo trials; thesis ch. 6)
  paper_figure2        |mean| and standard deviation of the error of M_p's 21 entries,
                       least squares (Procrustes) against SPDE (paper Fig. 2)
  paper_figure3        mean absolute error of x11, x12, x22 against std_a, least squares, TLS and
                       SPDE (paper Fig. 3; log scale)
  linkage_steering     the steering-condition four-bar: prescribed and generated output angle,
                       structural error before and after Gauss-Newton, the linkage drawn
  hexapod_model        the built-in hexapod's geometry and its mode frequencies
  error_vs_samples     mean error against the number of samples m (log-log), one line per method,
                       at two noise levels: which method to choose for how much data
  physical_vs_generic  mean error of M_p against m (log-log): physical identification of the
                       payload against the generic estimators and the best of them at each m
  payload_frames       the frames of payload identification: the world, the sensor frame S, the
                       payload's centre of mass, gravity and the wrench (docs/payload.md)
  payload_residuals    the residuals per axis of the calibration of examples/payload/log.csv
                       (docs/payload.md; the log is found under $SPDFIT_SOURCE_DIR or ./)

Each plot_* function takes the data its *_data function returns (the experiment functions'
results, unchanged), so what is drawn is what the library computed.
"""
import argparse
import math
import os
import pathlib
import sys
import warnings

import matplotlib

matplotlib.use("Agg")  # non-interactive: files only
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import experiment, hexapod, linkage  # noqa: E402
from ._errors import SpdfitWarning  # noqa: E402
from ._spdfit import METHODS  # noqa: E402

COLORS = {"ls": "#7f7f7f", "procrustes": "#1f77b4", "tls": "#d62728", "tls-sym": "#ff7f0e",
          "tls-psd": "#e377c2", "spde": "#2ca02c", "spd-tls": "#9467bd", "psd-ls": "#17becf",
          "auto": "#000000"}
LABELS = {"ls": "least squares", "procrustes": "LS (symmetric Procrustes)", "tls": "TLS",
          "tls-sym": "TLS, symmetrized", "tls-psd": "TLS, nearest PSD", "spde": "SPDE (area criterion)",
          "spd-tls": "TLS over SPD matrices", "psd-ls": "LS over PSD matrices", "auto": "auto"}


# ---- 1. The thesis' experiments ---------------------------------------------------------------

def thesis_data(trials=2000, seed=1):
    """{noise variance: ThesisExperimentResult} for the thesis' three experiments."""
    return {v: experiment.thesis(v, trials=trials, seed=seed) for v in experiment.THESIS_NOISE_VARIANCES}


def plot_thesis(data):
    fig, axes = plt.subplots(1, len(data), figsize=(13, 4.6), sharey=False)
    for ax, (v, result) in zip(np.atleast_1d(axes), data.items()):
        errors = [m.errors[np.isfinite(m.errors)] for m in result.methods]
        names = [m.method for m in result.methods]
        box = ax.boxplot(errors, showfliers=False, patch_artist=True, medianprops={"color": "black"})
        for patch, name in zip(box["boxes"], names):
            patch.set_facecolor(COLORS[name])
            patch.set_alpha(0.7)
        ax.plot(range(1, len(names) + 1), [m.summary.mean for m in result.methods], "k^", label="mean")
        ax.set_xticks(range(1, len(names) + 1), names, rotation=30)
        ax.set_title(f"noise variance V = {v} ({result.trials} trials)")
        ax.set_xlabel("method")
        ax.set_ylabel("error ||M_p - M_hat||_F (kg)")
        ax.grid(axis="y", alpha=0.3)
        ax.legend(loc="upper left")
    fig.suptitle("Thesis experiments 1-3 (m = 12 samples): estimation error of each method "
                 "(boxes: quartiles, whiskers: 1.5 IQR)")
    fig.tight_layout()
    return fig


# ---- 2. The paper's Figure 2 ------------------------------------------------------------------

def paper_figure2_data(trials=100, seed=1):
    return experiment.paper_hexapod(trials=trials, seed=seed)


def plot_paper_figure2(result):
    labels = [f"m{i + 1}{j + 1}" for i, j in result.entries]
    x = np.arange(len(labels))
    fig, axes = plt.subplots(2, 1, figsize=(12, 6.5), sharex=True)
    width = 0.4
    for k, stats in enumerate(result.methods):
        offset = (k - 0.5) * width
        axes[0].bar(x + offset, np.abs(stats.bias), width, color=COLORS[stats.method], label=LABELS[stats.method])
        axes[1].bar(x + offset, stats.std, width, color=COLORS[stats.method], label=LABELS[stats.method])
    axes[0].set_ylabel("|mean of error| (kg)")
    axes[1].set_ylabel("std of error (kg)")
    axes[1].set_xticks(x, labels, rotation=60)
    axes[1].set_xlabel("entry of M_p")
    for ax in axes:
        ax.grid(axis="y", alpha=0.3)
        ax.legend()
    fig.suptitle(f"Paper Fig. 2 (simulated, thesis exp. 2 noise, {result.trials} trials): error of the 21 "
                 "entries of M_p")
    fig.tight_layout()
    return fig


# ---- 3. The paper's Figure 3 ------------------------------------------------------------------

def paper_figure3_data(trials=10000, seed=1):
    """[(std_a, EntryExperimentResult)] for std_a = 0, 0.1, ..., 1.9."""
    return experiment.paper_2x2_sweep(trials=trials, seed=seed)


def plot_paper_figure3(sweep):
    levels = np.array([level for level, _ in sweep])
    names = [stats.method for stats in sweep[0][1].methods]
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.4))
    for e, entry in enumerate(["x11", "x12", "x22"]):
        ax = axes[e]
        for k, name in enumerate(names):
            mae = np.array([result.methods[k].mae[e] for _, result in sweep])
            ax.semilogy(levels, mae, "o-", color=COLORS[name], label=LABELS[name], markersize=4)
        ax.set_title(f"{entry}")
        ax.set_xlabel("std of the noise in A, std_a")
        ax.set_ylabel(f"mean |{entry} estimate - {entry}| (log scale)")
        ax.grid(alpha=0.3, which="both")
        ax.legend()
    fig.suptitle(f"Paper Fig. 3: X = [3 1; 1 1], std_b = 1, {sweep[0][1].trials} trials per level")
    fig.tight_layout()
    return fig


# ---- 4. Four-bar synthesis --------------------------------------------------------------------

def linkage_data(rho=0.5):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SpdfitWarning)
        return linkage.synthesize(steering=rho)


def _draw_fourbar(ax, bar, psi, phi, color, alpha):
    o2, o4 = np.array([0.0, 0.0]), np.array([bar.a1, 0.0])
    a = o2 + bar.a2 * np.array([math.cos(psi), math.sin(psi)])
    b = o4 + bar.a4 * np.array([math.cos(phi), math.sin(phi)])
    points = np.array([o2, a, b, o4])
    ax.plot(points[:, 0], points[:, 1], "-o", color=color, alpha=alpha, markersize=3)


def plot_linkage(result):
    psi, phi = np.degrees(result.psi), np.degrees(result.phi)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    ax = axes[0]
    ax.plot(psi, phi, "k-", label="prescribed (steering condition)")
    for name, solution, style in (("design error", result.design, "--"),
                                  ("structural (Gauss-Newton)", result.structural, ":")):
        ax.plot(psi, np.degrees(solution.phi_generated), style, label=f"generated: {name}")
    ax.set_xlabel("input angle psi (deg)")
    ax.set_ylabel("output angle phi (deg)")
    ax.set_title("prescribed and generated output")
    ax.legend()
    ax.grid(alpha=0.3)
    ax = axes[1]
    for name, solution, color in (("before (design error)", result.design, COLORS["procrustes"]),
                                  ("after Gauss-Newton", result.structural, COLORS["spde"])):
        s = np.degrees(result.phi - solution.phi_generated)
        ax.plot(psi, s, "o-", color=color, markersize=3,
                label=f"{name}: RMS {math.degrees(solution.structural_error_rms):.3f} deg")
    ax.axhline(0, color="black", lw=0.5)
    ax.set_xlabel("input angle psi (deg)")
    ax.set_ylabel("structural error phi_pres - phi_gen (deg)")
    ax.set_title("structural error")
    ax.legend()
    ax.grid(alpha=0.3)
    ax = axes[2]
    bar = result.structural.lengths
    picks = np.linspace(0, len(result.psi) - 1, 5).round().astype(int)
    for n, i in enumerate(picks):
        _draw_fourbar(ax, bar, result.psi[i], result.structural.phi_generated[i], COLORS["spde"], 0.3 + 0.7 * n / 4)
    ax.set_aspect("equal")
    ax.set_xlabel("x (ground link = 1)")
    ax.set_ylabel("y (ground link = 1)")
    ax.set_title(f"the linkage at 5 inputs ({result.structural.check.grashof})")
    ax.grid(alpha=0.3)
    fig.suptitle("Four-bar steering linkage (notes 002, eq. 3.5, rho = 0.5): a1 = 1, "
                 f"a2 = {bar.a2:.4f}, a3 = {bar.a3:.4f}, a4 = {bar.a4:.4f}")
    fig.tight_layout()
    return fig


# ---- 5. The hexapod model ---------------------------------------------------------------------

def hexapod_data():
    return hexapod.model()


def plot_hexapod(model):
    g = model.geometry
    payload = g.payload_rotation @ g.payload_points + g.payload_origin[:, None]
    fig = plt.figure(figsize=(12, 5))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    base, top = g.base_points, payload
    for points, color, label in ((base, "#444444", "base attachment points"),
                                 (top, COLORS["procrustes"], "payload attachment points")):
        ring = np.hstack([points, points[:, :1]])
        ax.plot(*ring, "o-", color=color, label=label)
    for i in range(6):
        ax.plot(*np.column_stack([base[:, i], top[:, i]]), color=COLORS["tls"], lw=2,
                label="struts" if i == 0 else None)
    ax.scatter(*g.payload_origin, color="black", marker="x", label="payload centre of mass")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.set_title("built-in cubic-configuration hexapod")
    ax.legend(loc="upper left", fontsize=8)
    ax = fig.add_subplot(1, 2, 2)
    ax.bar(np.arange(1, 7), model.modes_hz, color=COLORS["spde"], label="sqrt(eig(M_p^-1 K)) / 2 pi")
    ax.set_xlabel("mode")
    ax.set_ylabel("frequency (Hz)")
    ax.set_title(f"modes (strut stiffness {g.strut_stiffness[0]:.0f} N/m)")
    ax.legend()
    ax.grid(axis="y", alpha=0.3)
    fig.tight_layout()
    return fig


# ---- 6. Error against the number of samples --------------------------------------------------

SAMPLE_SIZES = (12, 30, 100, 300, 1000, 3000)
NOISE_WIDTHS = (1.0, 3.2)
COMPARED = ("procrustes", "tls-sym", "spde", "spd-tls", "psd-ls", "auto")


def error_vs_samples_data(trials=400, seed=1):
    """{noise width nm: {m: ThesisExperimentResult}}: the thesis model with uniform noise of width nm
    (variance nm^2 / 12) in A and B, at each sample size."""
    return {w: {m: experiment.thesis(w * w / 12, samples=m, trials=trials, seed=seed, methods=list(COMPARED))
                for m in SAMPLE_SIZES} for w in NOISE_WIDTHS}


def plot_error_vs_samples(data):
    fig, axes = plt.subplots(1, len(data), figsize=(12.5, 4.8), sharey=True)
    for ax, (width, results) in zip(np.atleast_1d(axes), data.items()):
        sizes = sorted(results)
        for index, name in enumerate(COMPARED):
            means = [next(r for r in results[m].methods if r.method == name).summary.mean for m in sizes]
            style = {"color": COLORS[name], "marker": "o", "label": LABELS[name]}
            if name == "auto":  # drawn over the method it chose
                style.update(marker="x", linestyle=":", linewidth=2)
            elif name == "psd-ls":  # equal to Procrustes where that is already PSD
                style.update(marker="s", linestyle="--", markerfacecolor="none")
            ax.plot(sizes, means, **style)
        ax.set_xscale("log")
        ax.set_yscale("log")
        trials = next(iter(results.values())).trials
        ax.set_title(f"uniform noise of width nm = {width:g} in A and B ({trials} trials per point)")
        ax.set_xlabel("samples m")
        ax.set_ylabel("mean error ||M_p - M_hat||_F (kg)")
        ax.grid(which="both", alpha=0.3)
    np.atleast_1d(axes)[0].legend(loc="lower left", fontsize=8)
    fig.suptitle("Which method for how much data: spde and Procrustes level off (biased), "
                 "spd-tls keeps falling; auto follows the best")
    fig.tight_layout()
    return fig


# ---- 7. Physical identification against the generic estimators -------------------------------

PHYSICAL_SIZES = (12, 30, 100, 300, 1000)
PHYSICAL_STYLES = {"physical": {"color": "#d62728", "marker": "o", "linewidth": 2.5,
                                "label": "physical (errors in variables, consistent)"},
                   "grey-box-ls": {"color": "#8c564b", "marker": "^", "linestyle": ":",
                                   "label": "grey-box least squares (unconstrained)"},
                   "grey-box-tls": {"color": "#bcbd22", "marker": "v", "linestyle": ":",
                                    "label": "grey-box TLS (unconstrained)"}}


def physical_data(trials=200, seed=1):
    """spdfit.experiment.physical's result (a dict) on the thesis' set-up at each m."""
    return experiment.physical(samples=list(PHYSICAL_SIZES), trials=trials, seed=seed)


def plot_physical(data):
    fig, ax = plt.subplots(figsize=(8.5, 5.2))
    sizes = [row["samples"] for row in data["rows"]]
    for name in data["methods"]:
        means = [row["methods"][name]["mean"] for row in data["rows"]]
        style = PHYSICAL_STYLES.get(name, {"color": COLORS.get(name, "#000000"), "marker": "s",
                                           "label": LABELS.get(name, name)})
        ax.plot(sizes, means, **style)
    best = [row["methods"][row["best_generic"]]["mean"] for row in data["rows"] if row["best_generic"]]
    if len(best) == len(sizes):
        ax.plot(sizes, best, color="#000000", linestyle="--", linewidth=1, label="best generic method at each m")
        for m, row in zip(sizes, data["rows"]):
            ratio = row["physical_ratio"]
            if ratio is not None:
                ax.annotate(f"{ratio:.2f}x", (m, row["methods"]["physical"]["mean"]), textcoords="offset points",
                            xytext=(0, -14), ha="center", fontsize=8, color="#d62728")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("samples m")
    ax.set_ylabel("mean error ||M_p - M_hat||_F (kg)")
    ax.set_title(f"Physical identification vs generic SPD estimates ({data['trials']} trials per point; "
                 "ratio to the best generic)", fontsize=10)
    ax.grid(which="both", alpha=0.3)
    ax.legend(loc="lower left", fontsize=8)
    fig.tight_layout()
    return fig


# ---- 8. A payload on a wrist force/torque sensor ----------------------------------------------

def payload_frames_data():
    """The diagram's geometry: the sensor frame's tilt and origin, the centre of mass in S."""
    angle = np.radians(25.0)
    R = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    return {"origin": np.array([2.6, 2.5]), "R": R, "com": np.array([0.45, -1.05])}


def plot_payload_frames(data):
    from matplotlib.patches import FancyArrowPatch, Polygon

    fig, ax = plt.subplots(figsize=(8.5, 5.2))
    ax.set_aspect("equal")
    ax.axis("off")

    def arrow(start, end, color, width=1.8, **kw):
        ax.add_patch(FancyArrowPatch(tuple(start), tuple(end), arrowstyle="-|>", mutation_scale=14, color=color,
                                     lw=width, **kw))

    o, R = data["origin"], data["R"]
    local = lambda p: o + R @ np.asarray(p, dtype=float)  # noqa: E731 (a point given in S's plane)
    # The world frame W and gravity.
    arrow((0.2, 0.3), (1.1, 0.3), "black")
    arrow((0.2, 0.3), (0.2, 1.2), "black")
    ax.text(1.15, 0.2, "$x_W$", fontsize=11)
    ax.text(0.05, 1.25, "$z_W$", fontsize=11)
    ax.text(0.2, -0.05, "world W", fontsize=10)
    arrow((0.7, 4.3), (0.7, 3.4), "#1f77b4")
    ax.text(0.8, 3.7, "$g = (0, 0, -9.81)$\nin W", color="#1f77b4", fontsize=10)
    # The robot's wrist (above the sensor), the sensor, and the tool below it along z_S.
    ax.add_patch(Polygon([local(p) for p in ([-0.22, 1.3], [0.22, 1.3], [0.22, 0.0], [-0.22, 0.0])], closed=True,
                         color="#bbbbbb"))
    ax.text(*(local([0.3, 1.0]) + [0.05, 0.0]), "robot wrist", fontsize=9, color="#555555")
    ax.add_patch(Polygon([local(p) for p in ([-0.38, 0.0], [0.38, 0.0], [0.38, -0.22], [-0.38, -0.22])], closed=True,
                         color="#ff7f0e", alpha=0.85))
    ax.text(*(local([-0.45, -0.1]) + [-1.05, -0.4]), "F/T sensor", fontsize=9, color="#ff7f0e")
    tool = [[-0.3, -0.22], [0.3, -0.22], [0.3, -0.8], [0.75, -1.6], [0.5, -1.65], [0.12, -0.95], [-0.12, -0.95],
            [-0.5, -1.65], [-0.75, -1.6], [-0.3, -0.8]]
    ax.add_patch(Polygon([local(p) for p in tool], closed=True, color="#2ca02c", alpha=0.35))
    ax.text(*(local([-0.8, -1.4]) + [-1.05, 0.0]), "payload\n(gripper)", fontsize=9, color="#2ca02c")
    # The sensor frame S at O_S: x_S across the tool, z_S along it, away from the wrist.
    arrow(o, local([1.0, 0.0]), "#d62728")
    arrow(o, local([0.0, -1.0]), "#d62728")
    ax.text(*(local([1.05, 0.05])), "$x_S$", color="#d62728", fontsize=11)
    ax.text(*(local([-0.3, -1.05]) + [-0.05, -0.15]), "$z_S$", color="#d62728", fontsize=11)
    ax.plot(*o, "o", color="#d62728", zorder=5)
    ax.text(o[0] - 0.55, o[1] + 0.05, "$O_S$", color="#d62728", fontsize=11)
    # The centre of mass c (in S), gravity on the payload, the force the sensor applies.
    c = local(data["com"])
    ax.plot(*c, "o", color="black", zorder=5)
    arrow(o, c, "black", width=1.2, linestyle="--")
    ax.text(c[0] + 0.12, c[1] + 0.02, "$c$, the centre of mass (in S)", fontsize=10)
    arrow(c, c + np.array([0.0, -0.9]), "#1f77b4")
    ax.text(c[0] + 0.1, c[1] - 0.75, "$m\\,g$", color="#1f77b4", fontsize=11)
    arrow(local([-0.8, 0.0]), local([-0.8, 0.0]) + np.array([0.0, 0.95]), "#9467bd")
    ax.text(*(local([-0.8, 0.0]) + [-0.12, 0.55]), "$f$, on the payload\n(the sensor reads $-f$)", color="#9467bd",
            fontsize=9, ha="right")
    arrow(local([1.35, -0.45]), local([1.6, 0.25]), "#8c564b", connectionstyle="arc3,rad=0.5")
    ax.text(*(local([1.65, -0.2]) + [0.05, 0.0]), "$\\omega$, $\\alpha$, $a$ (in S)", color="#8c564b", fontsize=10)
    ax.text(4.9, 4.6, r"$f = m\,(a - R^T g) + \alpha \times m c + \omega \times (\omega \times m c)$" + "\n" +
            r"$\tau = I_S\,\alpha + \omega \times (I_S\,\omega) + m c \times (a - R^T g)$" + "\n" +
            r"reading $w = -(f, \tau) + b$  (the load)" + "\n" + r"R: from S to W;  $\tau$ about $O_S$",
            fontsize=10, va="top")
    ax.set_xlim(-0.2, 9.6)
    ax.set_ylim(-0.3, 4.8)
    ax.set_title("Payload identification: frames and conventions (docs/payload.md)", fontsize=11)
    fig.tight_layout()
    return fig


def payload_residuals_data(log=None):
    """The calibration of docs/payload.md on examples/payload/log.csv: the rows' times and the
    errors-in-variables fit's residuals per axis."""
    from . import payload
    if log is None:
        root = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", "."))
        log = root / "examples" / "payload" / "log.csv"
        if not log.is_file():
            raise FileNotFoundError(f"{log} not found: it is in spdfit's source tree; run from there, or set "
                                    "SPDFIT_SOURCE_DIR to it")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SpdfitWarning)
        estimate = payload.identify(str(log), wrench_cols="fx:tz", quat_cols="qx:qw", accel_cols="ax:az",
                                    omega_cols="wx:wz", time_col="t", rest_rows=":0.995", rows="1:",
                                    criterion="eiv")
    t = np.loadtxt(log, delimiter=",", skiprows=1, usecols=0)
    return {"t": t[t >= 1.0], "residuals": estimate["residuals"], "rms": estimate["residual_rms"]}


def plot_payload_residuals(data):
    fig, axes = plt.subplots(2, 3, figsize=(12, 5.5), sharex=True)
    names = ["$f_x$", "$f_y$", "$f_z$", "$\\tau_x$", "$\\tau_y$", "$\\tau_z$"]
    units = ["N"] * 3 + ["N m"] * 3
    for k, ax in enumerate(axes.ravel()):
        ax.plot(data["t"], data["residuals"][:, k], lw=0.6, color="#1f77b4" if k < 3 else "#d62728")
        ax.axhline(0.0, color="black", lw=0.5)
        ax.set_title(f"{names[k]}: RMS {data['rms'][k]:.3g} {units[k]}", fontsize=10)
        ax.grid(alpha=0.3)
        if k >= 3:
            ax.set_xlabel("t (s)")
    axes[0, 0].set_ylabel("residual (N)")
    axes[1, 0].set_ylabel("residual (N m)")
    axes[0, 0].axvspan(1.0, 3.4, color="#dddddd", alpha=0.5, lw=0)
    axes[0, 0].text(1.1, axes[0, 0].get_ylim()[1] * 0.8, "static poses", fontsize=8)
    fig.suptitle("examples/payload/log.csv: residuals of the errors-in-variables fit (docs/payload.md)", fontsize=11)
    fig.tight_layout()
    return fig


FIGURES = {
    "thesis_experiments": (thesis_data, plot_thesis),
    "paper_figure2": (paper_figure2_data, plot_paper_figure2),
    "paper_figure3": (paper_figure3_data, plot_paper_figure3),
    "linkage_steering": (linkage_data, plot_linkage),
    "hexapod_model": (hexapod_data, plot_hexapod),
    "error_vs_samples": (error_vs_samples_data, plot_error_vs_samples),
    "physical_vs_generic": (physical_data, plot_physical),
    "payload_frames": (payload_frames_data, plot_payload_frames),
    "payload_residuals": (payload_residuals_data, plot_payload_residuals),
}


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m spdfit.figures", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default="figures", help="output directory (default: ./figures)")
    parser.add_argument("--format", choices=["png", "svg"], default="png")
    parser.add_argument("--only", choices=sorted(FIGURES), action="append", help="draw only these")
    parser.add_argument("--quick", action="store_true", help="a tenth of the Monte Carlo trials (for tests)")
    args = parser.parse_args(argv)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    scale = 0.1 if args.quick else 1.0
    skipped = []
    for name, (data_function, plot_function) in FIGURES.items():
        if args.only and name not in args.only:
            continue
        kwargs = {}
        if "trials" in data_function.__code__.co_varnames:
            default = data_function.__defaults__[0]
            kwargs["trials"] = max(10, int(default * scale))
        try:
            data = data_function(**kwargs)
        except FileNotFoundError as error:
            print(f"{name}: skipped: {error}", file=sys.stderr)
            skipped.append(name)
            continue
        fig = plot_function(data)
        path = out / f"{name}.{args.format}"
        fig.savefig(path, dpi=110)
        plt.close(fig)
        print(path)
    # A figure asked for by name that could not be drawn is an error; among all of them, a note.
    return 1 if args.only and skipped else 0


if __name__ == "__main__":
    sys.exit(main())
