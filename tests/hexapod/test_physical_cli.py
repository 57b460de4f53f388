"""`spdfit hexapod identify --physical`, `hexapod simulate --payload-*` and `spdfit experiment
physical` at the user's level: exit statuses, the JSON contract, errors that name the option or
the confounded combination, and agreement of the CLI's physical estimate with the truth simulated
(noise-free: exact recovery) and with the Python module's (the same library call)."""
import json

import numpy as np
import pytest

from conftest import read_csv

# Noise-free data: every identifiable parameter comes back to this relative accuracy (the goal of
# physical identification; the library's own tests check it with an independent model).
RECOVERY = 1e-9
# The contract of the `physical` object (physical_json adds more keys).
PHYSICAL_KEYS = {"mass", "center_of_mass", "inertia", "strut_mass", "M_p", "pseudo_inertia_min_eig",
                 "certificate", "criterion", "iterations", "converged"}
BOOTSTRAP_KEYS = {"standard_errors", "interval"}
CERTIFICATE_KEYS = {"stationarity", "primal_min_eig", "dual_min_eig", "complementarity"}
PAYLOAD = {"mass": 14.0, "com": [0.012, -0.007, 0.021],
           "inertia": [[0.13, 0.004, -0.002], [0.004, 0.09, 0.006], [-0.002, 0.006, 0.11]]}


def write_geometry(cli, tmp_path, name="g.json"):
    cli("hexapod", "model", "--write-geometry", name)
    return tmp_path / name


def asymmetric_geometry(cli, tmp_path):
    """The cubic hexapod with its joints moved by up to 2 cm and its payload turned: no two struts
    parallel, so that every strut's mass is identified."""
    g = json.loads(write_geometry(cli, tmp_path, "cubic.json").read_text())
    rng = np.random.default_rng(11)
    g["base_points"] = (np.asarray(g["base_points"]) + rng.uniform(-0.02, 0.02, (6, 3))).tolist()
    g["payload_points"] = (np.asarray(g["payload_points"]) + rng.uniform(-0.02, 0.02, (6, 3))).tolist()
    g["payload_rotation"] = [[np.cos(0.3), -np.sin(0.3), 0], [np.sin(0.3), np.cos(0.3), 0], [0, 0, 1]]
    g["strut_mass"] = [0.4, 0.5, 0.6, 0.45, 0.55, 0.35]
    path = tmp_path / "asym.json"
    path.write_text(json.dumps(g))
    return path


def payload_args():
    I = np.asarray(PAYLOAD["inertia"])
    six = [I[0, 0], I[0, 1], I[0, 2], I[1, 1], I[1, 2], I[2, 2]]  # URDF's order
    return ["--payload-mass", PAYLOAD["mass"], "--payload-com", ",".join(map(str, PAYLOAD["com"])),
            "--payload-inertia", ",".join(map(repr, six))]


def test_noise_free_payload_comes_back_exactly(cli, cli_json, tmp_path):
    g = write_geometry(cli, tmp_path)
    out = cli("hexapod", "simulate", "--geometry", g, "--samples", 40, "--noise-var", 0, "--out", "run",
              *payload_args()).stdout
    assert "--physical --geometry" in out
    settings = json.loads((tmp_path / "run" / "simulation.json").read_text())
    assert settings["payload"]["mass"] == PAYLOAD["mass"]
    np.testing.assert_allclose(settings["payload"]["inertia"], PAYLOAD["inertia"], rtol=0, atol=0)
    doc = cli_json("hexapod", "identify", "run/A.csv", "run/B.csv", "--truth", "run/truth.csv", "--geometry", g,
                   "--physical")
    p = doc["physical"]
    assert PHYSICAL_KEYS <= p.keys() and CERTIFICATE_KEYS == p["certificate"].keys()
    assert not BOOTSTRAP_KEYS & p.keys()
    assert p["mass"] == pytest.approx(PAYLOAD["mass"], rel=RECOVERY)
    np.testing.assert_allclose(p["center_of_mass"], PAYLOAD["com"], rtol=RECOVERY)
    np.testing.assert_allclose(p["inertia"], PAYLOAD["inertia"], rtol=0, atol=RECOVERY * 0.13)
    np.testing.assert_allclose(p["M_p"], read_csv(tmp_path / "run" / "truth.csv"), rtol=RECOVERY, atol=RECOVERY)
    assert p["physically_consistent"] and p["converged"] and p["strut_masses"] == "geometry"
    assert p["error_vs_truth"] < RECOVERY * np.linalg.norm(read_csv(tmp_path / "run" / "truth.csv"))
    assert set(doc["methods"]) >= {"spde", "spd-tls"}  # the generic estimators are still there


def test_report_shows_nominal_values_and_the_bootstrap(cli, tmp_path):
    g = write_geometry(cli, tmp_path)
    cli("hexapod", "simulate", "--geometry", g, "--samples", 200, "--noise-var", 0.86, "--out", "run")
    text = cli("hexapod", "identify", "run/A.csv", "run/B.csv", "--truth", "run/truth.csv", "--geometry", g,
               "--physical", "--bootstrap", 50, "--threads", 2).stdout
    assert "Physical estimate (errors in variables, physically consistent" in text
    for label in ("mass (kg)", "centre of mass x (m)", "inertia xy (kg m^2)", "principal moment 3 (kg m^2)",
                  "principal axes", "std error", "[95% interval]", "modes (Hz)", "KKT certificate"):
        assert label in text, label
    mass_line = next(line for line in text.splitlines() if line.strip().startswith("mass (kg)"))
    assert "11.973" in mass_line  # the geometry's nominal mass beside the estimate
    assert "closest to the truth:" in text
    doc = json.loads(cli("hexapod", "identify", "run/A.csv", "run/B.csv", "--geometry", g, "--physical",
                         "--bootstrap", 50, "--threads", 2, "--json").stdout)
    p = doc["physical"]
    assert BOOTSTRAP_KEYS <= p.keys()
    assert {"mass", "center_of_mass", "inertia", "strut_mass", "M_p"} <= p["standard_errors"].keys()
    assert p["interval"]["level"] == 0.95
    assert p["interval"]["lower"]["mass"] <= p["mass"] <= p["interval"]["upper"]["mass"]
    # Membership can be read (issue 45 item 2): each row shows the estimate, the standard error and
    # the bounds to the standard error's third significant digit, and they are the JSON's numbers
    # rounded there (the same seed: the same replicates).
    values = {"mass (kg)": lambda d: d["mass"], "centre of mass z (m)": lambda d: d["center_of_mass"][2],
              "inertia xx (kg m^2)": lambda d: d["inertia"][0][0]}
    text_again = cli("hexapod", "identify", "run/A.csv", "run/B.csv", "--geometry", g, "--physical",
                     "--bootstrap", 50, "--threads", 2).stdout
    rows = {line[:31].strip(): line[31:].replace("[", " ").replace("]", " ").replace(",", " ").split()
            for line in text_again.splitlines() if line.startswith("  ") and line[:31].strip() in values}
    assert rows.keys() == values.keys()
    for label, value in values.items():
        estimate, _nominal, se, lower, upper = rows[label]
        se_json = value(p["standard_errors"])
        decimals = 2 - int(np.floor(np.log10(se_json)))
        for shown, exact in ((estimate, value(p)), (se, se_json), (lower, value(p["interval"]["lower"])),
                             (upper, value(p["interval"]["upper"]))):
            assert len(shown.split(".")[1]) == decimals, (label, shown, se_json)
            assert float(shown) == pytest.approx(exact, abs=0.51 * 10.0 ** -decimals), (label, shown, exact)


def test_each_strut_mass_on_an_asymmetric_geometry(cli, cli_json, tmp_path):
    g = asymmetric_geometry(cli, tmp_path)
    cli("hexapod", "simulate", "--geometry", g, "--samples", 60, "--noise-var", 0, "--out", "run", *payload_args())
    p = cli_json("hexapod", "identify", "run/A.csv", "run/B.csv", "--geometry", g, "--physical",
                 "--fit-strut-mass", "each")["physical"]
    assert p["strut_masses"] == "each" and len(p["strut_mass"]) == 6
    np.testing.assert_allclose(p["strut_mass"], [0.4, 0.5, 0.6, 0.45, 0.55, 0.35], rtol=RECOVERY)
    assert p["mass"] == pytest.approx(PAYLOAD["mass"], rel=RECOVERY)
    text = cli("hexapod", "identify", "run/A.csv", "run/B.csv", "--geometry", g, "--physical",
               "--fit-strut-mass", "each").stdout
    assert "strut mass 6 (kg)" in text


def test_confounded_strut_mass_is_a_data_error_naming_the_combination(cli, tmp_path):
    g = write_geometry(cli, tmp_path)
    cli("hexapod", "simulate", "--geometry", g, "--samples", 40, "--noise-var", 0.86, "--out", "run")
    proc = cli("hexapod", "identify", "run/A.csv", "run/B.csv", "--geometry", g, "--physical",
               "--fit-strut-mass", "common", expect=1)
    assert "--fit-strut-mass = common cannot be estimated on this geometry: adding 1 kg" in proc.stderr
    assert proc.stdout == ""


@pytest.mark.parametrize("args, message", [
    (["--physical"], "--physical needs --geometry"),
    (["--fit-strut-mass", "each"], "--fit-strut-mass needs --physical"),
    (["--physical", "--geometry", "GEOMETRY", "--fit-strut-mass", "some"], "`strut_masses`"),
])
def test_usage_errors_of_identify(cli, tmp_path, args, message):
    g = write_geometry(cli, tmp_path)
    cli("hexapod", "simulate", "--samples", 20, "--noise-var", 0.86, "--out", "run")
    args = [str(g) if a == "GEOMETRY" else a for a in args]
    proc = cli("hexapod", "identify", "run/A.csv", "run/B.csv", *args, expect=2)
    assert message.replace("`strut_masses`", "--fit-strut-mass must be one of 'geometry', 'common' or 'each', "
                           "got 'some'") in proc.stderr


@pytest.mark.parametrize("args, message", [
    (["--payload-com", "1,2"], "--payload-com: give 3 comma-separated numbers"),
    (["--payload-com", "1,x,2"], "--payload-com: '1,x,2' is not a number"),
    (["--payload-inertia", "1,2,3,4"], "--payload-inertia: give 3 (the diagonal), 6"),
    (["--payload-mass", "-1"], "--payload-mass: "),
    (["--payload-inertia", "1,2,3,4,5,6,7,8,9"], "--payload-inertia: "),  # not symmetric
])
def test_bad_payload_options_are_usage_errors(cli, tmp_path, args, message):
    g = write_geometry(cli, tmp_path)
    proc = cli("hexapod", "simulate", "--geometry", g, "--noise-var", 0, "--out", "run", *args, expect=2)
    assert message in proc.stderr


def test_payload_options_need_a_geometry(cli):
    proc = cli("hexapod", "simulate", "--noise-var", 0, "--out", "run", "--payload-com", "0,0,0.01", expect=2)
    assert "--geometry" in proc.stderr


def test_experiment_physical_json_and_table(cli, cli_json):
    args = ["experiment", "physical", "--samples", "12,100", "--trials", 20, "--seed", 3, "--threads", 2]
    doc = cli_json(*args)
    assert doc["experiment"] == "physical" and doc["trials"] == 20
    assert doc["methods"] == ["spde", "spd-tls", "physical", "grey-box-ls", "grey-box-tls"]
    assert [row["samples"] for row in doc["rows"]] == [12, 100]
    for row in doc["rows"]:
        assert set(row["methods"]) == set(doc["methods"])
        assert row["methods"]["physical"]["inconsistent"] == 0
        generic = {k: row["methods"][k]["mean"] for k in ("spde", "spd-tls")}
        best = min(generic, key=generic.get)
        assert row["best_generic"] == best
        assert row["physical_ratio"] == pytest.approx(row["methods"]["physical"]["mean"] / generic[best], rel=1e-12)
    text = cli(*args).stdout
    assert "physical / best generic" in text and "Physical identification experiment" in text
    # The same seed gives the same numbers as the JSON.
    first = next(line for line in text.splitlines() if line.strip().startswith("12 "))
    assert f"{doc['rows'][0]['methods']['physical']['mean']:.3f}" in first


def test_experiment_physical_methods_and_errors(cli, cli_json):
    doc = cli_json("experiment", "physical", "--samples", 30, "--trials", 5, "--methods", "ls,physical-ls")
    assert doc["methods"] == ["ls", "physical-ls"]
    assert doc["rows"][0]["physical_ratio"] is None  # no "physical" variant ran
    proc = cli("experiment", "physical", "--methods", "spde,nonsense", expect=2)
    assert "unknown method 'nonsense'" in proc.stderr
    proc = cli("experiment", "physical", "--samples", 5, expect=2)
    assert "--samples" in proc.stderr


def test_experiment_physical_takes_a_payload(cli_json):
    doc = cli_json("experiment", "physical", "--samples", 30, "--trials", 5, "--methods", "physical",
                   "--payload-mass", 14, "--payload-com", "0.01,0,0")
    assert doc["payload"]["mass"] == 14 and doc["payload"]["center_of_mass"] == [0.01, 0, 0]
    nominal = cli_json("experiment", "physical", "--samples", 30, "--trials", 5, "--methods", "physical")
    assert "payload" not in nominal and doc["truth"] != nominal["truth"]


def test_iteration_limit_reaches_every_fit(cli, tmp_path):
    g = write_geometry(cli, tmp_path)
    cli("hexapod", "simulate", "--geometry", g, "--samples", 100, "--noise-var", 0.86, "--out", "run")
    proc = cli("hexapod", "identify", "run/A.csv", "run/B.csv", "--geometry", g, "--physical", "--max-iter", 1,
               "--json")
    doc = json.loads(proc.stdout)
    assert not doc["physical"]["converged"]
    assert "spdfit: warning: physical: the optimizer did not converge: stopped after --max-iter = 1" in proc.stderr
    assert any("did not converge in 1 iterations" in w for w in doc["methods"]["spd-tls"]["warnings"])
    default = json.loads(cli("hexapod", "identify", "run/A.csv", "run/B.csv", "--geometry", g, "--physical",
                             "--json").stdout)
    assert default["physical"]["converged"]


def test_urdf_writes_the_physical_fits_payload(cli, cli_json, tmp_path):
    import re
    g = write_geometry(cli, tmp_path)
    cli("hexapod", "simulate", "--geometry", g, "--samples", 40, "--noise-var", 0, "--out", "run", *payload_args())
    doc = cli_json("hexapod", "identify", "run/A.csv", "run/B.csv", "--geometry", g, "--physical",
                   "--urdf", "payload.urdf", "--precision", 12)
    text = (tmp_path / "payload.urdf").read_text()
    assert '<link name="payload">' in text
    # The link's numbers are the JSON's estimate, to the 12 digits asked for; the mass the truth.
    mass = float(re.search(r'<mass value="([^"]+)"', text).group(1))
    assert mass == pytest.approx(doc["physical"]["mass"], rel=1e-11)
    assert mass == pytest.approx(PAYLOAD["mass"], rel=1e-9)
    origin = [float(v) for v in re.search(r'<origin xyz="([^"]+)"', text).group(1).split()]
    np.testing.assert_allclose(origin, doc["physical"]["center_of_mass"], rtol=1e-11, atol=1e-15)
    # --urdf writes the physical fit: without --physical it is a usage error naming both.
    refused = cli("hexapod", "identify", "run/A.csv", "run/B.csv", "--geometry", g, "--urdf", "x.urdf", expect=2)
    assert "--urdf" in refused.stderr and "--physical" in refused.stderr
