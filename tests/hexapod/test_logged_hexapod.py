"""The hexapod rows of issue 42's table, through the command line: forces logged untared (a static
load, rest rows given) and forces logged in kN against a geometry in SI. Each gives the truth with
the option the warning or error names, or a clear error; never a "physically consistent" payload
of the wrong mass. References: the same data tared or converted to SI by hand in NumPy, fitted
plainly, and the simulated payload."""
import json

import numpy as np

from conftest import read_csv

# The same arithmetic on rows that differ by a subtraction or a power of ten: rounding.
SAME = 1e-9
PRELOAD = np.array([21.0, 20.0, 22.0, 21.5, 20.5, 21.0])  # N: a payload's weight along the struts


def geometry(cli, tmp_path):
    cli("hexapod", "model", "--write-geometry", "g.json")
    return tmp_path / "g.json"


def write(path, M):
    np.savetxt(path, M, delimiter=",", fmt="%.17g")
    return str(path)


def physical(cli, *args, expect=0):
    proc = cli("hexapod", "identify", "--json", "--physical", *args, expect=expect)
    return (json.loads(proc.stdout) if expect == 0 else None), proc.stderr


def untared_log(cli, tmp_path, g):
    """A simulated log as an untared logger writes it: the static load in every row of B, moving or
    at rest (hexapod simulate --preload)."""
    cli("hexapod", "simulate", "--geometry", g, "--samples", 400, "--noise-var", 0.5, "--rest-samples", 200,
        "--seed", 3, "--preload", ",".join(repr(float(v)) for v in PRELOAD), "--out", "run")
    run = tmp_path / "run"
    A, B = read_csv(run / "A.csv"), read_csv(run / "B.csv")
    rest_A, rest_B = read_csv(run / "rest_A.csv"), read_csv(run / "rest_B.csv")
    # The load is in both, as the simulator was asked (NumPy's means against PRELOAD, to the noise).
    assert np.all(np.abs(rest_B.mean(0) - PRELOAD) < 5 * np.sqrt(0.5 / 200))
    return A, B, rest_A, rest_B


def test_untared_forces_warn_and_offsets_rest_gives_the_tared_answer(cli, tmp_path):
    g = geometry(cli, tmp_path)
    A, B, rest_A, rest_B = untared_log(cli, tmp_path, g)
    rest = ["--rest-a", write(tmp_path / "rA.csv", rest_A), "--rest-b", write(tmp_path / "rB.csv", rest_B)]
    files = [write(tmp_path / "A.csv", A), write(tmp_path / "B.csv", B), "--geometry", g, *rest]
    # As logged: a warning that names the fix.
    _, err = physical(cli, *files)
    assert "the forces look untared" in err and "--offsets rest" in err, err
    # With the fix: the fit of the data tared by hand (NumPy subtracts the rest rows' means).
    tared, err = physical(cli, *files, "--offsets", "rest")
    assert "untared" not in err
    by_hand, _ = physical(cli, write(tmp_path / "At.csv", A - rest_A.mean(0)),
                          write(tmp_path / "Bt.csv", B - rest_B.mean(0)), "--geometry", g, *rest)
    p, q = tared["physical"], by_hand["physical"]
    assert abs(p["mass"] - q["mass"]) <= SAME * q["mass"]
    np.testing.assert_allclose(p["M_p"], q["M_p"], rtol=SAME, atol=SAME * np.abs(q["M_p"]).max())
    assert p["offsets"]["mode"] == "rest" and q["offsets"] == {"mode": "none"}
    np.testing.assert_allclose(p["offsets"]["b"], rest_B.mean(0), rtol=1e-12)
    # And that is the simulated payload's mass, to the noise; untared it was not.
    truth = json.loads(g.read_text())["payload_mass"]
    assert abs(p["mass"] - truth) < 0.05 * truth
    untared, _ = physical(cli, *files)
    assert abs(untared["physical"]["mass"] - truth) > 5 * abs(p["mass"] - truth)
    # --offsets rest without rest rows: a usage error naming them.
    _, err = physical(cli, "A.csv", "B.csv", "--geometry", g, "--offsets", "rest", expect=2)
    assert "--rest-a" in err


def test_forces_in_kn_are_refused_with_the_factor_and_converted_give_the_si_answer(cli, tmp_path):
    g = geometry(cli, tmp_path)
    cli("hexapod", "simulate", "--geometry", g, "--samples", 300, "--noise-var", 0.5, "--seed", 5, "--out", "si")
    A, B = read_csv(tmp_path / "si" / "A.csv"), read_csv(tmp_path / "si" / "B.csv")
    kn = [write(tmp_path / "A.csv", A), write(tmp_path / "Bkn.csv", B / 1000), "--geometry", g]
    _, err = physical(cli, *kn, expect=1)
    assert "(kN instead of N?)" in err and "multiply the forces by 1000 (--scale-b 1000;" in err, err
    assert "physically consistent" not in err
    # The option it names gives the SI data's payload from the kN file itself (issue 42 item 2).
    scaled, _ = physical(cli, *kn, "--scale-b", "1000")
    # The fix it names (B times 1000) gives the SI data's payload.
    fixed, _ = physical(cli, "A.csv", write(tmp_path / "Bn.csv", read_csv(tmp_path / "Bkn.csv") * 1000),
                        "--geometry", g)
    si, _ = physical(cli, "si/A.csv", "si/B.csv", "--geometry", g)
    assert abs(fixed["physical"]["mass"] - si["physical"]["mass"]) <= SAME * si["physical"]["mass"]
    assert abs(scaled["physical"]["mass"] - si["physical"]["mass"]) <= SAME * si["physical"]["mass"]
    np.testing.assert_allclose(scaled["physical"]["M_p"], si["physical"]["M_p"], rtol=SAME, atol=SAME)
    # The generic estimators, given the geometry, warn about the units instead of reporting kg
    # and modes a thousand times off.
    proc = cli("hexapod", "identify", "--json", *kn)
    assert "the geometry is in SI units" in proc.stderr and "multiply the forces by 1000 (--scale-b 1000" in proc.stderr
    assert proc.stderr.count("the geometry is in SI units") == 1, proc.stderr  # once, not once per estimator
    # --no-plausibility-check fits them as they are (the user's decision).
    physical(cli, *kn, "--no-plausibility-check")


def test_offsets_estimate_with_the_physical_fit_is_the_fit_of_the_centred_data(cli, tmp_path):
    # A log without rest rows: the physical model with constants, B ~= A M_p + 1 c^T. Reference:
    # the plain physical fit of the data centred by NumPy's column means, and c from its M_p.
    g = geometry(cli, tmp_path)
    A, B, _, _ = untared_log(cli, tmp_path, g)
    est, err = physical(cli, write(tmp_path / "A.csv", A), write(tmp_path / "B.csv", B), "--geometry", g,
                        "--offsets", "estimate")
    assert "untared" not in err, err
    by_hand, _ = physical(cli, write(tmp_path / "Ac.csv", A - A.mean(0)), write(tmp_path / "Bc.csv", B - B.mean(0)),
                          "--geometry", g)
    p, q = est["physical"], by_hand["physical"]
    assert abs(p["mass"] - q["mass"]) <= SAME * q["mass"]
    np.testing.assert_allclose(p["M_p"], q["M_p"], rtol=SAME, atol=SAME * np.abs(q["M_p"]).max())
    assert p["offsets"]["mode"] == "estimate"
    c = B.mean(0) - np.array(p["M_p"]).T @ A.mean(0)
    np.testing.assert_allclose(p["offsets"]["c"], c, rtol=1e-9, atol=1e-9 * np.abs(c).max())
    # The constants are the preload, to the noise, and the mass the simulated payload's.
    assert np.all(np.abs(np.array(p["offsets"]["c"]) - PRELOAD) < 0.5)
    truth = json.loads(g.read_text())["payload_mass"]
    assert abs(p["mass"] - truth) < 0.05 * truth


def spiked_log(cli, tmp_path):
    """The untared log with one reading of strut 2 (row 150) off by 60 N, about 85 of its noise's
    standard deviations: the arguments of the clean and of the spiked log (tared by the rest rows)
    and the rest rows' arguments."""
    g = geometry(cli, tmp_path)
    A, B, rest_A, rest_B = untared_log(cli, tmp_path, g)
    rest = ["--rest-a", write(tmp_path / "rA.csv", rest_A), "--rest-b", write(tmp_path / "rB.csv", rest_B)]
    spiked = B.copy()
    spiked[149, 1] += 60.0
    a = write(tmp_path / "A.csv", A)
    clean = [a, write(tmp_path / "B.csv", B), "--geometry", g, *rest, "--offsets", "rest"]
    files = [a, write(tmp_path / "Bs.csv", spiked), "--geometry", g, *rest, "--offsets", "rest"]
    return clean, files, rest


def test_robust_physical_fit_down_weights_a_spike(cli, tmp_path):
    # The untared log tared, with a spike: the plain physical fit moves, Huber's and Tukey's hardly.
    clean_files, files, rest = spiked_log(cli, tmp_path)
    clean, _ = physical(cli, *clean_files)
    plain, _ = physical(cli, *files)
    ref = np.array(clean["physical"]["M_p"])
    plain_error = np.linalg.norm(np.array(plain["physical"]["M_p"]) - ref)
    for loss in ("huber", "tukey"):
        robust, err = physical(cli, *files, "--robust", loss)
        r = robust["physical"]
        assert r["robust"]["method"] == loss and r["robust"]["converged"], err
        assert 150 in r["robust"]["rows_downweighted"]
        assert r["physically_consistent"]
        assert np.linalg.norm(np.array(r["M_p"]) - ref) < 0.2 * plain_error, loss
        # The generic estimators are refitted robustly too, each as `fit --robust` fits it.
        X = read_csv_json(cli, "fit", "--method", "spd-tls", "--robust", loss, *rest, "--offsets", "rest",
                          str(tmp_path / "A.csv"), str(tmp_path / "Bs.csv"))
        assert robust["methods"]["spd-tls"]["X"] == X


def test_robust_bootstrap_refits_each_resample_robustly(cli, tmp_path):
    # With the bootstrap, every resample is reweighted from the robust estimate. A tuning constant so
    # large that every row weighs 1 makes the robust fit the plain one, resample by resample (the
    # same multinomial draws of the same seed): its standard errors are the plain bootstrap's, for
    # the physical fit and for each generic estimator, modes included. With Huber's usual constant on
    # a log with a spike they are finite, positive, and differ from the plain ones.
    _, files, _ = spiked_log(cli, tmp_path)
    boot = ["--bootstrap", 12, "--seed", 5]
    plain, _ = physical(cli, *files, *boot)
    flat, _ = physical(cli, *files, *boot, "--robust", "huber", "--robust-tuning", "1e9")
    huber, err = physical(cli, *files, *boot, "--robust", "huber")
    for key in ("mass", "center_of_mass", "inertia", "M_p"):
        p = np.array(plain["physical"]["standard_errors"][key], dtype=float)
        f = np.array(flat["physical"]["standard_errors"][key], dtype=float)
        assert np.allclose(f, p, rtol=1e-6, atol=1e-9 * np.abs(p).max()), key
    assert flat["physical"]["bootstrap"]["replicates"] == 12 and flat["physical"]["robust"]["method"] == "huber"
    assert "modes_hz" in plain["methods"]["spd-tls"]["bootstrap"]
    for method in ("ls", "procrustes", "spd-tls"):
        p, f = plain["methods"][method], flat["methods"][method]
        assert np.allclose(f["standard_errors"], p["standard_errors"], rtol=1e-6), method
        if "modes_hz" in p["bootstrap"]:  # the symmetric estimates'
            assert np.allclose(f["bootstrap"]["modes_hz"]["standard_errors"],
                               p["bootstrap"]["modes_hz"]["standard_errors"], rtol=1e-6), method
    se = np.array(huber["physical"]["standard_errors"]["M_p"], dtype=float)
    assert np.all(np.isfinite(se)) and np.all(se >= 0) and se.max() > 0, err
    assert huber["physical"]["bootstrap"]["failed"] == 0
    assert not np.allclose(se, np.array(plain["physical"]["standard_errors"]["M_p"], dtype=float), rtol=1e-3)
    assert huber["methods"]["ls"]["robust"]["method"] == "huber" and "standard_errors" in huber["methods"]["ls"]
    # spde is not refitted robustly: its bootstrap is the plain one's, resample by resample.
    assert huber["methods"]["spde"]["standard_errors"] == plain["methods"]["spde"]["standard_errors"]


def read_csv_json(cli, *args):
    return json.loads(cli(*args, "--json").stdout)["X"]
