"""The figures script runs and writes non-empty files, and what it draws is what the experiment
functions return."""
import numpy as np
import pytest

import spdfit
from spdfit import experiment, figures


def test_script_writes_every_figure(tmp_path):
    assert figures.main(["--out", str(tmp_path), "--quick"]) == 0
    for name in figures.FIGURES:
        path = tmp_path / f"{name}.png"
        assert path.stat().st_size > 10_000, path
    assert figures.main(["--out", str(tmp_path), "--format", "svg", "--only", "hexapod_model"]) == 0
    assert (tmp_path / "hexapod_model.svg").read_text().lstrip().startswith("<?xml")


def test_figures_outside_the_source_tree_skip_the_example_log(tmp_path, monkeypatch, capsys):
    """An installed module run elsewhere: the one figure drawn from a file of the source tree is
    skipped with a note naming it (an error when asked for by name), the others are drawn."""
    monkeypatch.setenv("SPDFIT_SOURCE_DIR", str(tmp_path / "nowhere"))
    assert figures.main(["--out", str(tmp_path), "--only", "payload_residuals", "--only", "hexapod_model"]) == 1
    assert "payload_residuals: skipped" in capsys.readouterr().err
    assert (tmp_path / "hexapod_model.png").stat().st_size > 10_000
    assert not (tmp_path / "payload_residuals.png").exists()


def test_thesis_figure_plots_the_experiment_means():
    data = figures.thesis_data(trials=40, seed=3)
    for v, result in data.items():
        direct = experiment.thesis(v, trials=40, seed=3)
        for a, b in zip(result.methods, direct.methods):
            assert np.array_equal(a.errors, b.errors)
    fig = figures.plot_thesis(data)
    for ax, result in zip(fig.axes, data.values()):
        means = [line for line in ax.get_lines() if line.get_label() == "mean"][0].get_ydata()
        assert np.array_equal(means, [m.summary.mean for m in result.methods])


def test_figure3_plots_the_sweep():
    sweep = figures.paper_figure3_data(trials=200, seed=5)
    direct = experiment.paper_2x2_sweep(trials=200, seed=5)
    fig = figures.plot_paper_figure3(sweep)
    for e, ax in enumerate(fig.axes):
        for k, line in enumerate(ax.get_lines()):
            expected = [result.methods[k].mae[e] for _, result in direct]
            assert np.array_equal(line.get_ydata(), expected)
            assert np.array_equal(line.get_xdata(), [level for level, _ in direct])


def test_figure2_plots_bias_and_std():
    result = figures.paper_figure2_data(trials=30, seed=2)
    fig = figures.plot_paper_figure2(result)
    heights = [p.get_height() for p in fig.axes[0].patches]
    n = len(result.entries)
    assert np.allclose(heights[:n], np.abs(result.methods[0].bias))
    assert np.allclose(heights[n:], np.abs(result.methods[1].bias))


def test_every_axis_is_labelled():
    fig = figures.plot_hexapod(figures.hexapod_data())
    for ax in fig.axes:
        assert ax.get_xlabel() and ax.get_ylabel() and ax.get_title()


def test_the_usage_line_names_only_real_options(capsys):
    # Issue 18: the docstring's usage line (shown by --help) offered a --trials-scale that did not exist.
    import re

    import pytest

    with pytest.raises(SystemExit):
        figures.main(["--help"])
    shown = capsys.readouterr().out
    for option in set(re.findall(r"--[a-z-]+", figures.__doc__)):
        assert f"  {option}" in shown.split("options:")[-1], option


def test_physical_figure_plots_the_experiment_means():
    data = figures.physical_data(trials=10, seed=4)
    direct = experiment.physical(samples=list(figures.PHYSICAL_SIZES), trials=10, seed=4)
    assert data == direct
    fig = figures.plot_physical(data)
    lines = {line.get_label(): line for line in fig.axes[0].get_lines()}
    physical = lines[figures.PHYSICAL_STYLES["physical"]["label"]]
    assert np.array_equal(physical.get_xdata(), figures.PHYSICAL_SIZES)
    assert np.array_equal(physical.get_ydata(), [row["methods"]["physical"]["mean"] for row in direct["rows"]])
    best = lines["best generic method at each m"].get_ydata()
    assert np.array_equal(best, [min(row["methods"][k]["mean"] for k in ("spde", "spd-tls")) for row in direct["rows"]])
