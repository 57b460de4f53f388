"""fit --noise-ratio and the noise estimate through the CLI: the ratio is a usage error (exit 2)
with methods that do not take it and with a value that is not a finite number > 0; --json reports
status and noise_sigma."""
import json

import numpy as np
import pytest


def save(tmp_path, A, B):
    a, b = tmp_path / "A.csv", tmp_path / "B.csv"
    np.savetxt(a, A, delimiter=",", fmt="%.17g")
    np.savetxt(b, B, delimiter=",", fmt="%.17g")
    return a, b


def test_noise_ratio_reaches_tls_and_the_noise_estimate(spdfit, data, tmp_path):
    a, b = save(tmp_path, *data)
    A, B = data
    out = json.loads(spdfit("fit", "--method", "tls", "--noise-ratio", "4", "--json", a, b).stdout)
    assert out["status"] == "success"
    n = A.shape[1]
    s = np.linalg.svd(np.hstack([A, B / 4.0]), compute_uv=False)
    assert out["diagnostics"]["noise_sigma"] == pytest.approx(np.sqrt(np.sum(s[n:] ** 2) / (n * (A.shape[0] - n))),
                                                               rel=1e-12)
    V = np.linalg.svd(np.hstack([A, B / 4.0]))[2].T
    X = -4.0 * V[:n, n:] @ np.linalg.inv(V[n:, n:])
    assert np.allclose(np.array(out["X"]), X, rtol=0, atol=1e-10 * np.linalg.norm(X))


@pytest.mark.parametrize("method", ["ls", "procrustes", "spde"])
def test_noise_ratio_is_a_usage_error_for_other_methods(spdfit, data, tmp_path, method):
    a, b = save(tmp_path, *data)
    r = spdfit("fit", "--method", method, "--noise-ratio", "2", a, b)
    assert r.returncode == 2
    assert "--noise-ratio applies to the total least-squares methods" in r.stderr


@pytest.mark.parametrize("value", ["0", "-1", "inf", "nan", "two"])
def test_noise_ratio_must_be_a_finite_positive_number(spdfit, data, tmp_path, value):
    a, b = save(tmp_path, *data)
    r = spdfit("fit", "--method", "tls", "--noise-ratio", value, a, b)
    assert r.returncode == 2
    assert "--noise-ratio" in r.stderr and "finite number > 0" in r.stderr


def test_x_alone_skips_the_noise_estimate(spdfit, tmp_path):
    """Printing X alone (CSV, --header, -o) does not compute the noise estimate (nor the
    column-scaled condition numbers), so its warning about thin data is not given; --json and
    --report still have both. X is the same bits."""
    rng = np.random.default_rng(5)
    A = rng.standard_normal((7, 4))  # m - n < n: the estimate's thin-data warning
    B = A @ np.diag([1.0, 2.0, 3.0, 4.0]) + 0.1 * rng.standard_normal((7, 4))
    a, b = save(tmp_path, A, B)
    plain = spdfit("fit", "--method", "spde", a, b)
    assert plain.returncode == 0, plain.stderr
    assert "noise estimate" not in plain.stderr
    full = spdfit("fit", "--method", "spde", "--json", a, b)
    out = json.loads(full.stdout)
    assert out["diagnostics"]["noise_sigma"] > 0
    assert any(w.startswith("the noise estimate (noise_sigma) rests on") for w in out["warnings"])
    report = spdfit("fit", "--method", "spde", "--report", a, b)
    assert "noise estimate: sigma = " in report.stdout
    assert "rests on" in report.stderr
    X = np.loadtxt(plain.stdout.splitlines(), delimiter=",")
    assert np.array_equal(X, np.array(out["X"]))
