"""spdfit linkage synthesize / analyze: the JSON contract of issue 4, the design solution against
numpy.linalg.lstsq, the structural solution against an independent NumPy Gauss-Newton (eq. 3.18),
the steering worked example, bad input files and usage errors."""
import numpy as np
import pytest

import reference
from conftest import ROOT, fails

EXAMPLES = ROOT / "examples" / "linkage"
SOLUTION_KEYS = {"k", "lengths", "design_error_norm", "structural_error_rms_deg", "structural_error_max_deg"}
TOP_KEYS = {"design", "structural", "condition_number", "grashof", "transmission_angle_deg", "branch_defect"}


def check_contract(out):
    assert TOP_KEYS <= out.keys()
    assert SOLUTION_KEYS <= out["design"].keys()
    assert SOLUTION_KEYS | {"iterations"} <= out["structural"].keys()
    for solution in (out["design"], out["structural"]):
        assert len(solution["k"]) == 3
        assert set(solution["lengths"]) == {"a1", "a2", "a3", "a4"}
    assert set(out["transmission_angle_deg"]) == {"min", "max"}
    assert isinstance(out["branch_defect"], bool)
    assert isinstance(out["structural"]["iterations"], int)


def test_steering_worked_example(spdfit_json):
    """docs/linkage.md's example, checked against the NumPy reference."""
    out = spdfit_json("linkage", "synthesize", "--steering", "--rho", "0.5")
    check_contract(out)
    gamma = np.arctan(0.25)
    dpsi = np.radians(np.linspace(-30, 30, 21))
    psi, phi = np.pi / 2 - gamma + dpsi, np.pi / 2 + gamma + reference.steering(0.5, dpsi)
    assert np.allclose(np.radians(out["pairs"]["psi_deg"]), psi, rtol=0, atol=1e-14)
    assert np.allclose(np.radians(out["pairs"]["phi_deg"]), phi, rtol=0, atol=1e-14)

    k_design, cond = reference.design(psi, phi)
    assert np.allclose(out["design"]["k"], k_design, rtol=1e-12)
    assert out["condition_number"] == pytest.approx(cond, rel=1e-10)
    s = reference.structural_error(k_design, psi, phi, 1)
    assert out["design"]["structural_error_rms_deg"] == pytest.approx(np.degrees(np.sqrt(np.mean(s**2))), rel=1e-9)
    assert out["design"]["structural_error_max_deg"] == pytest.approx(np.degrees(np.abs(s).max()), rel=1e-9)

    k_structural, _ = reference.gauss_newton(k_design, psi, phi, 1)
    assert np.allclose(out["structural"]["k"], k_structural, rtol=1e-9)
    s = reference.structural_error(k_structural, psi, phi, 1)
    assert out["structural"]["structural_error_rms_deg"] == pytest.approx(np.degrees(np.sqrt(np.mean(s**2))), rel=1e-9)
    lengths = reference.lengths(k_structural)
    assert [out["structural"]["lengths"][f"a{i}"] for i in range(1, 5)] == pytest.approx(lengths, rel=1e-9)
    # Gauss-Newton roughly halves the RMS structural error here and the worst error drops by 4.
    assert out["structural"]["structural_error_rms_deg"] < 0.6 * out["design"]["structural_error_rms_deg"]
    assert out["structural"]["structural_error_max_deg"] < 0.3 * out["design"]["structural_error_max_deg"]
    assert out["grashof"] == "triple-rocker"
    assert out["branch_defect"] is False


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("weighted", [False, True])
def test_design_solution_is_numpy_lstsq(spdfit_json, write_csv, seed, weighted):
    rng = np.random.default_rng(seed)
    bar = [1.0, 0.4, 1.1, 0.9]
    k_true = np.array([(1 + 0.16 + 0.81 - 1.21) / (2 * 0.4 * 0.9), 2.5, 1 / 0.9])
    psi = np.sort(rng.uniform(0, 2 * np.pi * 0.8, 15 + seed))
    phi = reference.output_angle(k_true, psi, 1) + np.radians(0.5) * rng.standard_normal(psi.size)
    args = ["linkage", "synthesize", "--pairs",
            write_csv("pairs.csv", np.degrees(np.c_[psi, phi]), header="psi_deg,phi_deg")]
    w = rng.uniform(0.5, 3.0, psi.size) if weighted else None
    if weighted:
        args += ["--weights", write_csv("w.csv", w[:, None])]
    out = spdfit_json(*args)
    check_contract(out)
    k, cond = reference.design(psi, phi, w)
    assert np.allclose(out["design"]["k"], k, rtol=1e-11)
    assert out["condition_number"] == pytest.approx(cond, rel=1e-10)
    # Gauss-Newton from there lowers the (weighted) structural error and agrees with the reference.
    if not weighted:
        k_gn, _ = reference.gauss_newton(k, psi, phi, 1)
        assert np.allclose(out["structural"]["k"], k_gn, rtol=1e-8)
        assert out["structural"]["structural_error_rms_deg"] < out["design"]["structural_error_rms_deg"]
    assert [out["design"]["lengths"][f"a{i}"] for i in range(1, 5)] == pytest.approx(bar, rel=0.05)


def test_exact_pairs_give_the_linkage_back(spdfit_json):
    out = spdfit_json("linkage", "synthesize", "--pairs", EXAMPLES / "crank_rocker_pairs.csv")
    for solution in ("design", "structural"):
        lengths = out[solution]["lengths"]
        assert [lengths[f"a{i}"] for i in range(1, 5)] == pytest.approx([1.0, 0.4, 1.1, 0.9], rel=1e-12)
        assert out[solution]["structural_error_max_deg"] < 1e-10
    assert out["grashof"] == "crank-rocker"
    assert out["structural"]["iterations"] == 0


def test_radians_and_precision_points(spdfit_json, write_csv):
    k = np.array([1.0555555555555556, 2.5, 1.1111111111111112])
    psi = np.radians([20.0, 95.0, 170.0])
    phi = reference.output_angle(k, psi, 1)
    out = spdfit_json("linkage", "synthesize", "--radians", "--pairs", write_csv("p.csv", np.c_[psi, phi]))
    assert out["precision_point"] is True
    assert np.allclose(out["design"]["k"], k, rtol=1e-12)
    assert out["structural"]["iterations"] == 0


def test_dial_zeros_are_fitted(spdfit_json, write_csv):
    k = np.array([1.0555555555555556, 2.5, 1.1111111111111112])
    alpha, beta = np.radians(35.0), np.radians(110.0)
    dpsi = np.radians(np.linspace(0, 100, 12))
    dphi = reference.wrap(reference.output_angle(k, alpha + dpsi, 1) - beta)
    out = spdfit_json("linkage", "synthesize", "--fit-dial-zeros",
                      "--pairs", write_csv("p.csv", np.degrees(np.c_[dpsi, dphi])))
    zeros = out["structural"]["dial_zeros_deg"]
    assert zeros["alpha"] == pytest.approx(35.0, abs=1e-7)
    assert zeros["beta"] == pytest.approx(110.0, abs=1e-7)
    assert np.allclose(out["structural"]["k"], k, rtol=1e-8)


def test_function_generator(spdfit_json):
    out = spdfit_json("linkage", "synthesize", "--function", "log10", "--x-range", "1:10", "--psi-range", "0:60",
                      "--phi-range", "0:60", "--points", "15", "--spacing", "chebyshev", "--alpha", "35",
                      "--beta", "105")
    check_contract(out)
    x = 5.5 - 4.5 * np.cos((2 * np.arange(15) + 1) * np.pi / 30)
    assert np.allclose(out["pairs"]["psi_deg"], 35 + (x - 1) / 9 * 60, atol=1e-12)
    assert np.allclose(out["pairs"]["phi_deg"], 105 + np.log10(x) * 60, atol=1e-12)
    assert out["structural"]["structural_error_rms_deg"] < out["design"]["structural_error_rms_deg"]


def test_analyze_json(spdfit_json):
    out = spdfit_json("linkage", "analyze", "--lengths", "1,0.9,1.1,0.4", "--psi-range", "-180:180", "--points", "73")
    assert out["grashof"] == "rocker-crank"
    assert out["input_fully_rotates"] is False
    a1, a2, a3, a4 = 1.0, 0.9, 1.1, 0.4
    k = np.array([(a1**2 + a2**2 + a4**2 - a3**2) / (2 * a2 * a4), a1 / a2, a1 / a4])
    assert np.allclose(out["k"], k, rtol=1e-14)
    # Dead points: the diagonal e = a3 + a4 or |a3 - a4|.
    expected = []
    for e in (a3 + a4, abs(a3 - a4)):
        c = (a1**2 + a2**2 - e**2) / (2 * a1 * a2)
        expected += [np.degrees(np.arccos(c)), -np.degrees(np.arccos(c))]
    assert np.allclose(sorted(out["dead_points_deg"]), sorted(expected), atol=1e-10)
    assembled = 0
    for sample in out["samples"]:
        psi = np.radians(sample["psi_deg"])
        for key in ("phi_plus_deg", "phi_minus_deg"):
            if sample[key] is None:
                continue
            phi = np.radians(sample[key])
            assert abs(k[0] + k[1] * np.cos(phi) - k[2] * np.cos(psi) - np.cos(psi - phi)) < 1e-12
            assembled += 1
        if sample["transmission_angle_deg"] is not None:
            e2 = a1**2 + a2**2 - 2 * a1 * a2 * np.cos(psi)
            mu = np.degrees(np.arccos((a3**2 + a4**2 - e2) / (2 * a3 * a4)))
            assert sample["transmission_angle_deg"] == pytest.approx(mu, abs=1e-9)
    assert 0 < assembled < 2 * 73


def test_analyze_text(spdfit):
    result = spdfit("linkage", "analyze", "--lengths", "1,0.4,1.1,0.9")
    assert result.returncode == 0, result.stderr
    assert "crank-rocker" in result.stdout and "turns fully" in result.stdout
    assert len(result.stdout.splitlines()) > 37


def test_no_real_linkage_exits_1(spdfit, write_csv):
    k = np.array([1.0555555555555556, 2.5, 1.1111111111111112])
    psi = np.radians(np.linspace(0, 200, 9))
    phi = reference.output_angle(k, psi, 1) + np.pi  # the output link turned by 180 degrees
    pairs = write_csv("p.csv", np.degrees(np.c_[psi, phi]))
    fails(spdfit("linkage", "synthesize", "--pairs", pairs), 1, "not a real linkage", "negative output link a4")


def test_unreachable_inputs_exit_1(spdfit):
    fails(spdfit("linkage", "synthesize", "--steering", "--rho", "0.5", "--psi-range=-40:40"), 1,
          "cannot be assembled", "psi = ")


def pairs_file(tmp_path, text, name="pairs.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_bad_pairs_files_exit_1_with_file_and_line(spdfit, tmp_path):
    nan = pairs_file(tmp_path, "psi,phi\n0,80\n10,nan\n20,85\n30,90\n")
    fails(spdfit("linkage", "synthesize", "--pairs", nan), 1, f"{nan}:3:4", "NaN")
    text = pairs_file(tmp_path, "0,80\n10,abc\n20,85\n", "text.csv")
    fails(spdfit("linkage", "synthesize", "--pairs", text), 1, f"{text}:2:4", "'abc' is not a number")
    three = pairs_file(tmp_path, "0,80,1\n10,82,1\n20,85,1\n", "three.csv")
    fails(spdfit("linkage", "synthesize", "--pairs", three), 1, three, "3 columns")
    two = pairs_file(tmp_path, "0,80\n10,82\n", "two.csv")
    fails(spdfit("linkage", "synthesize", "--pairs", two), 1, two, "2 pair(s): at least 3 are needed")
    four = pairs_file(tmp_path, "0,80\n10,82\n20,85\n30,90\n", "four.csv")
    fails(spdfit("linkage", "synthesize", "--fit-dial-zeros", "--pairs", four), 1, four, "at least 5")
    fails(spdfit("linkage", "synthesize", "--pairs", tmp_path / "missing.csv"), 1, "missing.csv")


def test_bad_weights_exit_1(spdfit, tmp_path):
    pairs = EXAMPLES / "crank_rocker_pairs.csv"
    short = pairs_file(tmp_path, "1\n2\n", "short.csv")
    fails(spdfit("linkage", "synthesize", "--pairs", pairs, "--weights", short), 1, short, "13 weights")
    negative = pairs_file(tmp_path, "\n".join(["1"] * 12 + ["-1"]) + "\n", "negative.csv")
    fails(spdfit("linkage", "synthesize", "--pairs", pairs, "--weights", negative), 1, negative,
          "weight 13 is -1")


@pytest.mark.parametrize("args", [
    ["linkage"],
    ["linkage", "synthesize"],
    ["linkage", "synthesize", "--steering"],
    ["linkage", "synthesize", "--steering", "--rho", "0.5", "--pairs", "p.csv"],
    ["linkage", "synthesize", "--steering", "--rho", "0.5", "--psi-range", "a:b"],
    ["linkage", "synthesize", "--steering", "--rho", "0.5", "--psi-range", "30:-30"],
    ["linkage", "synthesize", "--steering", "--rho", "0.5", "--phi-range", "0:10"],
    ["linkage", "synthesize", "--steering", "--rho", "0.5", "--spacing", "random"],
    ["linkage", "synthesize", "--function", "gamma", "--x-range", "1:2", "--psi-range", "0:1", "--phi-range", "0:1"],
    ["linkage", "synthesize", "--function", "log10", "--x-range", "1:2"],
    ["linkage", "synthesize", "--function", "log10", "--x-range", "-1:2", "--psi-range", "0:1", "--phi-range", "0:1"],
    ["linkage", "synthesize", "--pairs", "p.csv", "--points", "5"],
    ["linkage", "synthesize", "--steering", "--rho", "0.5", "--radians"],
    ["linkage", "synthesize", "--steering", "--rho", "0.5", "--tolerance", "0"],
    ["linkage", "analyze"],
    ["linkage", "analyze", "--lengths", "1,2,3"],
    ["linkage", "analyze", "--lengths", "1,-2,3,4"],
    ["linkage", "analyze", "--lengths", "1,2,3,4", "--psi-range", "10"],
    ["linkage", "analyze", "--lengths", "1,2,3,4", "--points", "1"],
    ["linkage", "bend"],
])
def test_usage_errors_exit_2(spdfit, args):
    result = spdfit(*args)
    assert result.returncode == 2, (args, result.returncode, result.stderr)
    assert result.stderr.startswith("spdfit: error: ")
    assert result.stdout == ""


def test_a_logarithm_at_zero_is_reported_as_minus_infinity(spdfit):
    # Issue 18: log10(0) was reported as nan; it is -inf (and a negative argument stays nan).
    zero = spdfit("linkage", "synthesize", "--function", "log10", "--x-range", "0:10", "--psi-range", "0:60",
                  "--phi-range", "0:60")
    fails(zero, 2, "log10(0) = -inf", "log10(10) = 1")
    negative = spdfit("linkage", "synthesize", "--function", "ln", "--x-range", "-1:10", "--psi-range", "0:60",
                      "--phi-range", "0:60")
    fails(negative, 2, "ln(-1) = nan")
