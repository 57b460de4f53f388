"""`spdfit inertia repair` against independent references: with `--metric second-moment` the repaired
inertia is the eigenvalue clip of the second moment (1/2) tr(I) 1 - I with the relative floor
(NumPy); with the default `--metric inertia` it is the nearest consistent inertia in ||I' - I||_F
(CVXOPT's cone QP over the semidefinite cone); a consistent inertia comes back unchanged, the output
reads back, URDF files keep every byte but the repaired numbers, and bad input gets clear errors
with the documented exit statuses."""
import json
import os
import pathlib

import numpy as np
import pytest

ROOT = pathlib.Path(os.environ.get("SPDFIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
EXAMPLES = ROOT / "examples" / "inertia"
FLOOR = 1e-6  # the default relative floor


def clip(inertia, rel=FLOOR):
    """The reference: the second moment's eigenvalues raised to rel times the largest |eigenvalue|."""
    I = np.asarray(inertia, dtype=float)
    S = 0.5 * np.trace(I) * np.eye(3) - I
    w, V = np.linalg.eigh(S)
    Sp = V @ np.diag(np.maximum(w, rel * np.abs(w).max())) @ V.T
    return np.trace(Sp) * np.eye(3) - Sp


def body_file(tmp_path, inertia, mass=2.0, com=(0.1, 0.0, -0.2), name="body.json"):
    path = tmp_path / name
    path.write_text(json.dumps({"mass": mass, "center_of_mass": list(com), "inertia": np.asarray(inertia).tolist()}))
    return path


def test_json_repair_is_the_eigenvalue_clip(spdfit, tmp_path):
    rng = np.random.default_rng(34)
    for _ in range(5):
        Q, _r = np.linalg.qr(rng.standard_normal((3, 3)))
        I = Q @ np.diag([0.1, 0.2, 0.5]) @ Q.T
        I = 0.5 * (I + I.T)
        result = spdfit("inertia", "repair", "--metric", "second-moment", body_file(tmp_path, I))
        assert result.returncode == 0, result.stderr
        out = json.loads(result.stdout)
        assert out["changed"] is True and out["metric"] == "second-moment"
        assert out["mass"] == 2.0 and out["center_of_mass"] == [0.1, 0.0, -0.2]
        np.testing.assert_allclose(out["inertia"], clip(I), rtol=0, atol=1e-15)
        assert out["distance"] == pytest.approx(np.linalg.norm(clip(I) - I), abs=1e-15)
        moments = np.sort(np.linalg.eigvalsh(out["inertia"]))
        assert moments[2] < moments[0] + moments[1]  # strict, with the floor's margin
        cert = out["certificate"]
        assert cert["primal_min_eig"] >= -1e-15 and cert["dual_min_eig"] >= -1e-15
        assert abs(cert["complementarity"]) < 1e-15


def test_floor_option_and_plain_projection(spdfit, tmp_path):
    I = np.diag([0.1, 0.2, 0.5])
    clip_metric = ("--metric", "second-moment")
    out = json.loads(spdfit("inertia", "repair", *clip_metric, "--min-eig-rel", "0", body_file(tmp_path, I)).stdout)
    np.testing.assert_allclose(out["inertia"], clip(I, 0.0), rtol=0, atol=1e-15)
    assert out["min_eig"] == 0.0
    out = json.loads(spdfit("inertia", "repair", *clip_metric, "--min-eig-rel", "1e-3", body_file(tmp_path, I)).stdout)
    np.testing.assert_allclose(out["inertia"], clip(I, 1e-3), rtol=0, atol=1e-15)


def test_consistent_inertia_is_unchanged_and_the_output_reads_back(spdfit, tmp_path):
    I = np.array([[0.3, 0.01, 0.0], [0.01, 0.4, 0.02], [0.0, 0.02, 0.5]])
    path = body_file(tmp_path, I)
    out = json.loads(spdfit("inertia", "repair", path).stdout)
    assert out["changed"] is False and out["distance"] == 0.0
    assert out["inertia"] == I.tolist()
    # -o writes the result; the repaired output of an inconsistent body repairs to itself.
    bad = body_file(tmp_path, np.diag([0.1, 0.2, 0.5]), name="bad.json")
    written = tmp_path / "fixed.json"
    result = spdfit("inertia", "repair", bad, "-o", written)
    assert result.returncode == 0 and result.stdout == ""
    again = json.loads(spdfit("inertia", "repair", written).stdout)
    assert again["changed"] is False
    assert again["inertia"] == json.loads(written.read_text())["inertia"]


def nearest_in_inertia_norm(I, floor):
    """min ||I' - I||_F over I' = tr(S) 1 - S with S >= floor 1, by CVXOPT's cone QP over the 3 x 3
    semidefinite cone (S - floor 1 = s in the cone), in the six entries of S."""
    pytest.importorskip("cvxopt")
    from cvxopt import matrix, solvers
    pairs = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]

    def basis(k):
        E = np.zeros((3, 3))
        i, j = pairs[k]
        E[i, j] = E[j, i] = 1.0
        return E

    T = np.array([(np.trace(basis(k)) * np.eye(3) - basis(k)).ravel() for k in range(6)]).T  # I = T x
    P = 2 * T.T @ T
    q = -2 * T.T @ np.asarray(I, dtype=float).ravel()
    G = -np.array([basis(k).ravel(order="F") for k in range(6)]).T
    h = -floor * np.eye(3).ravel(order="F")
    solvers.options.update({"show_progress": False, "abstol": 1e-15, "reltol": 1e-15, "feastol": 1e-15})
    x = np.array(solvers.coneqp(matrix(P), matrix(q), matrix(G), matrix(h), {"l": 0, "q": [], "s": [3]})["x"]).ravel()
    return (T @ x).reshape(3, 3)


def test_default_metric_is_the_nearest_inertia_and_closer_than_the_clip(spdfit, tmp_path):
    rng = np.random.default_rng(35)
    ratios = []
    for _ in range(8):
        Q, _r = np.linalg.qr(rng.standard_normal((3, 3)))
        moments = np.sort(rng.uniform(0.05, 0.2, 3))
        moments[2] = moments[0] + moments[1] + rng.uniform(0.005, 0.05)  # a broken triangle inequality
        I = Q @ np.diag(moments) @ Q.T
        I = 0.5 * (I + I.T)
        out = json.loads(spdfit("inertia", "repair", body_file(tmp_path, I)).stdout)
        assert out["metric"] == "inertia" and out["changed"] is True
        floor = out["min_eig"]
        reference = nearest_in_inertia_norm(I, floor)
        assert out["distance"] <= np.linalg.norm(reference - I) * (1 + 1e-7) + 1e-15
        np.testing.assert_allclose(out["inertia"], reference, atol=1e-7 * np.abs(I).max())
        cert = out["certificate"]
        assert cert["primal_min_eig"] >= -1e-15 and cert["dual_min_eig"] >= -1e-14
        assert abs(cert["complementarity"]) < 1e-14
        ratios.append(out["distance"] / np.linalg.norm(clip(I) - I))
    assert max(ratios) <= 1.0 + 1e-12 and np.mean(ratios) < 0.9


def test_typo_and_zero_inertia_warnings(spdfit, tmp_path):
    typo = body_file(tmp_path, np.diag([0.01, 0.02, 0.3]), name="typo.json")
    result = spdfit("inertia", "repair", typo)
    assert result.returncode == 0 and "may hold a typo" in result.stderr
    zero = body_file(tmp_path, np.zeros((3, 3)), name="zero.json")
    result = spdfit("inertia", "repair", zero)
    assert result.returncode == 0 and "all zero" in result.stderr


def test_urdf_keeps_every_byte_but_the_repaired_numbers(spdfit, tmp_path):
    source = (EXAMPLES / "arm.urdf").read_text()
    out = tmp_path / "fixed.urdf"
    result = spdfit("inertia", "repair", "--metric", "second-moment", EXAMPLES / "arm.urdf", "-o", out)
    assert result.returncode == 0, result.stderr
    assert result.stderr.splitlines()[-1] == "2 of 3 links repaired"
    assert 'link "base" (line 11): consistent' in result.stderr
    fixed = out.read_text()
    before, after = source.splitlines(), fixed.splitlines()
    assert len(before) == len(after)
    assert [i + 1 for i, (a, b) in enumerate(zip(before, after)) if a != b] == [20, 28]
    # The tool's ixy = 2e-5 and izz = 3e-4 are left as written; the repaired entries are the clip.
    assert 'ixy="2e-5"' in after[27] and 'izz="3e-4"' in after[27]
    forearm = np.diag([0.0004, 0.0093, 0.0101])
    values = dict(part.split("=") for part in after[19].strip()[len("<inertia "):-2].split())
    repaired = {k: float(v.strip('"')) for k, v in values.items()}
    # (to the rounding of the two routes: the clip formed whole here, as a change of I in spdfit)
    np.testing.assert_allclose([repaired["ixx"], repaired["iyy"], repaired["izz"]], np.diag(clip(forearm)),
                               rtol=1e-14, atol=0)
    # To stdout without -o; a second repair changes nothing.
    again = spdfit("inertia", "repair", out)
    assert again.returncode == 0 and again.stdout == fixed
    assert again.stderr.splitlines()[-1] == "0 of 3 links repaired"


@pytest.mark.parametrize("text, message", [
    ('{"mass": 1, "center_of_mass": [0, 0, 0]}', 'missing key "inertia"'),
    ('{"mass": 1, "center_of_mass": [0, 0, 0], "inertia": [[1, 0, 0], [0, 1, 0]]}', "inertia must be a 3x3 matrix"),
    ('{"mass": -2, "center_of_mass": [0, 0, 0], "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}',
     "mass must be positive (kg), not -2"),
    ('{"mass": 1, "center_of_mass": [0, 0, 0], "inertia": [[1, 0.5, 0], [0, 1, 0], [0, 0, 1]]}',
     "inertia is not symmetric: [0][1] differs from [1][0]"),
    ('{"mass": 1, "centre": [0, 0, 0]}', 'unknown key "centre"'),
    ('{"mass": 1,\n "inertia": [}', "body.json:2:"),
])
def test_json_errors_name_the_file_and_key(spdfit, tmp_path, text, message):
    (tmp_path / "body.json").write_text(text)
    result = spdfit("inertia", "repair", tmp_path / "body.json")
    assert result.returncode == 1
    assert result.stderr.startswith(f"spdfit: error: {tmp_path / 'body.json'}")
    assert message in result.stderr, result.stderr


@pytest.mark.parametrize("text, message", [
    ("<robot><link name='a'>", "not valid XML"),
    ("<sdf version='1.9'/>", "a URDF file's root element must be <robot>, found <sdf>"),
    ("<robot>\n<link name='a'><inertial><mass value='1'/>\n<inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0'/>"
     "</inertial></link></robot>", ':3: link "a": <inertia izz> is missing'),
    ("<robot><link name='a'><inertial><mass value='0'/><inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/>"
     "</inertial></link></robot>", 'link "a": mass must be positive'),
    # tinyxml2's error in words, without its numeric ErrorID (issue 45).
    ("<robot>\n<link name='a'></robot>", ":2: not valid XML: mismatched element"),
    # A second <inertia> (or <inertial>) was silently ignored.
    ("<robot><link name='a'><inertial><mass value='1'/><inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/>\n"
     "<inertia ixx='2' ixy='0' ixz='0' iyy='2' iyz='0' izz='2'/></inertial></link></robot>",
     ':2: link "a": <inertial> has a second <inertia> (the first is on line 1): keep the one that is meant'),
    ("<robot><link name='a'><inertial><mass value='1'/><inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/>"
     "</inertial>\n<inertial/></link></robot>", ':2: link "a": <link> has a second <inertial>'),
])
def test_urdf_errors_name_the_file_line_and_link(spdfit, tmp_path, text, message):
    (tmp_path / "robot.urdf").write_text(text)
    result = spdfit("inertia", "repair", tmp_path / "robot.urdf")
    assert result.returncode == 1
    assert message in result.stderr, result.stderr
    assert "ErrorID" not in result.stderr


@pytest.mark.parametrize("name, text, message", [
    ("robot.urdf.xacro", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r"/>',
     "is a xacro file (macros that make a URDF), not a JSON body: expand it first (xacro"),
    ("robot.txt", '<robot name="r"/>', "is XML, not a JSON body: a URDF file is read as one when its name ends in .urdf"),
])
def test_xml_where_a_json_body_was_expected_says_what_it_is(spdfit, tmp_path, name, text, message):
    (tmp_path / name).write_text(text)
    result = spdfit("inertia", "repair", tmp_path / name)
    assert result.returncode == 1
    assert result.stderr.startswith(f"spdfit: error: {tmp_path / name}: {message}"), result.stderr


def test_usage_errors(spdfit, tmp_path):
    path = body_file(tmp_path, np.eye(3))
    result = spdfit("inertia", "repair", "--min-eig-rel", "1", path)
    assert result.returncode == 2
    assert "--min-eig-rel: '1' is not a number in [0, 1)" in result.stderr
    assert spdfit("inertia", "repair").returncode == 2
    assert spdfit("inertia").returncode == 2
    missing = spdfit("inertia", "repair", tmp_path / "nope.json")
    assert missing.returncode == 1 and "no such file" in missing.stderr
    # A value the option table refuses after parsing names the nested command's help, as a parse error does.
    metric = spdfit("inertia", "repair", "--metric", "clip", path)
    assert metric.returncode == 2
    assert metric.stderr == ("spdfit: error: --metric must be one of 'inertia' or 'second-moment', got 'clip'\n"
                             "Run 'spdfit inertia repair --help' for usage.\n")
