"""fit with spd-tls, psd-ls and auto through the CLI: their options are usage errors (exit 2)
with methods that do not take them or out of range, and --json carries iterations, converged,
the certificate and auto's choice."""
import json

import numpy as np
import pytest


def save(tmp_path, A, B):
    a, b = tmp_path / "A.csv", tmp_path / "B.csv"
    np.savetxt(a, A, delimiter=",", fmt="%.17g")
    np.savetxt(b, B, delimiter=",", fmt="%.17g")
    return a, b


@pytest.mark.parametrize("args,message", [
    (["--method", "spde", "--min-eig", "0.1"], "--min-eig applies to psd-ls, not to spde"),
    (["--method", "tls", "--max-iter", "5"], "--max-iter applies to the iterative methods"),
    (["--method", "procrustes", "--noise-ratio", "2"], "--noise-ratio applies to"),
    (["--method", "psd-ls", "--max-iter", "0"], "--max-iter"),
    (["--method", "psd-ls", "--min-eig", "-1"], "--min-eig"),
    (["--method", "psd-ls", "--min-eig", "nan"], "--min-eig"),
])
def test_options_out_of_place_or_range_are_usage_errors(spdfit, data, tmp_path, args, message):
    a, b = save(tmp_path, *data)
    result = spdfit("fit", *args, a, b)
    assert result.returncode == 2, result.stderr
    assert message in result.stderr and result.stdout == ""


def test_psd_ls_json_has_the_certificate(spdfit, data, tmp_path):
    A, B = data
    a, b = save(tmp_path, A, B)
    out = json.loads(spdfit("fit", "--method", "psd-ls", "--min-eig", "0.5", "--json", a, b).stdout)
    d = out["diagnostics"]
    assert set(d["certificate"]) == {"primal_min_eig", "dual_min_eig", "complementarity", "duality_gap"}
    assert d["converged"] is True and d["iterations"] >= 0
    X = np.array(out["X"])
    S = A.T @ A @ X - A.T @ B
    S = (S + S.T) / 2
    assert d["certificate"]["dual_min_eig"] == pytest.approx(np.linalg.eigvalsh(S)[0],
                                                           abs=1e-10 * np.linalg.norm(A.T @ B))
    assert np.linalg.eigvalsh(X)[0] >= 0.5 - 1e-12 * np.linalg.norm(X)


def test_spd_tls_reports_its_iterations_and_stops_at_max_iter(spdfit, data, tmp_path):
    a, b = save(tmp_path, *data)
    full = json.loads(spdfit("fit", "--method", "spd-tls", "--json", a, b).stdout)
    assert full["diagnostics"]["converged"] is True
    # More than one step from spde on this data, so one step stops short.
    assert full["diagnostics"]["iterations"] > 1
    one = spdfit("fit", "--method", "spd-tls", "--max-iter", "1", "--json", a, b)
    assert one.returncode == 0
    assert json.loads(one.stdout)["diagnostics"]["converged"] is False
    assert "did not converge" in one.stderr


def test_auto_reports_its_choice(spdfit, data, tmp_path):
    a, b = save(tmp_path, *data)
    out = json.loads(spdfit("fit", "--method", "auto", "--json", a, b).stdout)
    d = out["diagnostics"]
    assert d["chosen_method"] == out["method"] and out["method"] in {"spde", "spd-tls", "psd-ls"}
    assert set(d["reason"]) == {"code", "text"} and d["reason"]["text"]
    assert d["positive_definite"] is True
