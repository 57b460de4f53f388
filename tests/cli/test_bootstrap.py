"""`spdfit fit --bootstrap N`: the JSON contract (standard_errors, interval, bias, bootstrap), the
--report table, reproducibility across threads, and the options' checks."""
import json

import numpy as np
import pytest

METHODS = ["ls", "procrustes", "tls", "tls-sym", "tls-psd", "spde", "spd-tls", "psd-ls", "auto"]


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("bootstrap")
    rng = np.random.default_rng(3)
    X = np.array([[3.0, 1.0, 0.5], [1.0, 2.0, 0.2], [0.5, 0.2, 1.5]])
    A0 = rng.uniform(-5, 5, (200, 3))
    np.savetxt(d / "A.csv", A0 + 0.2 * rng.standard_normal(A0.shape), delimiter=",", fmt="%.17g")
    np.savetxt(d / "B.csv", A0 @ X + 0.2 * rng.standard_normal(A0.shape), delimiter=",", fmt="%.17g")
    return str(d / "A.csv"), str(d / "B.csv")


@pytest.mark.parametrize("method", METHODS)
def test_json_has_the_bootstrap_fields_for_every_method(spdfit, files, method):
    out = spdfit("fit", "-m", method, "--bootstrap", "60", "--json", *files)
    assert out.returncode == 0, out.stderr
    j = json.loads(out.stdout)
    X = np.array(j["X"])
    se = np.array(j["standard_errors"])
    assert se.shape == X.shape == (3, 3) and np.all(se > 0)
    assert j["interval"]["level"] == 0.95
    lower, upper = np.array(j["interval"]["lower"]), np.array(j["interval"]["upper"])
    assert np.all(lower <= upper)
    assert np.array(j["bias"]).shape == (3, 3)
    boot = j["bootstrap"]
    assert boot["replicates"] == 60 and boot["seed"] == 1 and boot["failed"] == 0
    assert boot["scheme"] == "multinomial"
    assert boot["method"] == j["method"]  # auto: the method it chose
    if method not in ("ls", "tls"):
        eig = boot["eigenvalues"]
        assert len(eig["estimate"]) == 3 and sorted(sum(eig["clusters"], [])) == [0, 1, 2]


def test_text_output_stays_x_only(spdfit, files):
    plain = spdfit("fit", "-m", "spde", *files)
    boot = spdfit("fit", "-m", "spde", "--bootstrap", "20", *files)
    assert boot.returncode == 0 and boot.stdout == plain.stdout
    assert "--json or --report" in boot.stderr


def test_report_shows_standard_errors_and_the_noise_estimate(spdfit, files):
    out = spdfit("fit", "-m", "spd-tls", "--bootstrap", "100", "--report", *files)
    assert out.returncode == 0, out.stderr
    j = json.loads(spdfit("fit", "-m", "spd-tls", "--bootstrap", "100", "--json", *files).stdout)
    assert "bootstrap of 100 replicates (0 failed), seed 1" in out.stdout
    assert out.stdout.count("+-") >= 9 + 3
    assert "noise estimate: sigma = " in out.stdout
    assert "eigenvalues (ascending)" in out.stdout and "[95% interval]" in out.stdout
    first = out.stdout.splitlines()[3].split()
    # Row 1, column 1: "value +- se" as JSON has them, to the digits shown.
    assert float(first[1]) == pytest.approx(j["X"][0][0], abs=10 ** -len(first[1].split(".")[1]))
    assert float(first[3]) == pytest.approx(j["standard_errors"][0][0], rel=0.05)
    without = spdfit("fit", "-m", "spd-tls", "--report", *files)
    assert without.returncode == 0 and "add --bootstrap N" in without.stdout


def test_same_numbers_for_one_and_two_threads_and_seed_matters(spdfit, files):
    runs = [spdfit("fit", "-m", "spde", "--bootstrap", "200", "--json", "--threads", t, *files).stdout
            for t in ("1", "2")]
    assert runs[0] == runs[1]
    other = spdfit("fit", "-m", "spde", "--bootstrap", "200", "--json", "--seed", "7", *files).stdout
    assert json.loads(other)["bootstrap"]["seed"] == 7
    assert json.loads(other)["standard_errors"] != json.loads(runs[0])["standard_errors"]


def test_confidence_sets_the_level(spdfit, files):
    j = json.loads(spdfit("fit", "-m", "spde", "--bootstrap", "100", "--confidence", "0.5", "--json",
                          *files).stdout)
    wide = json.loads(spdfit("fit", "-m", "spde", "--bootstrap", "100", "--json", *files).stdout)
    assert j["interval"]["level"] == 0.5
    width = np.array(j["interval"]["upper"]) - np.array(j["interval"]["lower"])
    assert np.all(width < np.array(wide["interval"]["upper"]) - np.array(wide["interval"]["lower"]))


def test_interval_types_from_the_same_replicates(spdfit, files):
    runs = {kind: json.loads(spdfit("fit", "-m", "spd-tls", "--bootstrap", "150", "--interval", kind, "--json",
                                    *files).stdout) for kind in ("percentile", "basic", "normal")}
    default = json.loads(spdfit("fit", "-m", "spd-tls", "--bootstrap", "150", "--json", *files).stdout)
    # the default, auto: percentile here, where X and its replicates are well inside the cone
    assert default["interval"] == runs["percentile"]["interval"] and default["interval"]["type"] == "percentile"
    X = np.array(runs["basic"]["X"])
    q_lo, q_hi = (np.array(runs["percentile"]["interval"][k]) for k in ("lower", "upper"))
    # basic: the percentile interval reflected about the estimate
    assert runs["basic"]["interval"]["type"] == "basic"
    np.testing.assert_allclose(runs["basic"]["interval"]["lower"], 2 * X - q_hi, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(runs["basic"]["interval"]["upper"], 2 * X - q_lo, rtol=1e-12, atol=1e-14)
    # normal: X - bias -+ z se with z = Phi^-1(0.975) (scipy's normal quantile: 1.959963984540054)
    z = 1.959963984540054
    se, bias = np.array(runs["normal"]["standard_errors"]), np.array(runs["normal"]["bias"])
    assert runs["normal"]["interval"]["type"] == "normal"
    np.testing.assert_allclose(runs["normal"]["interval"]["lower"], X - bias - z * se, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(runs["normal"]["interval"]["upper"], X - bias + z * se, rtol=1e-12, atol=1e-14)
    # The same replicates: standard errors, bias and the eigenvalues' (percentile) intervals unchanged.
    for kind in ("basic", "normal"):
        assert runs[kind]["standard_errors"] == default["standard_errors"]
        assert runs[kind]["bootstrap"]["eigenvalues"] == default["bootstrap"]["eigenvalues"]
    report = spdfit("fit", "-m", "spd-tls", "--bootstrap", "50", "--interval", "basic", "--report", *files)
    assert report.returncode == 0 and "95% basic intervals of every entry" in report.stdout
    assert "[95% percentile interval]" in report.stdout  # the eigenvalues' stay percentile intervals


@pytest.mark.parametrize("args, message", [
    (["--bootstrap", "-1"], "--bootstrap"),
    (["--interval", "basic"], "--interval applies to the bootstrap"),
    (["--bootstrap", "10", "--interval", "bca"], "percentile"),
    (["--bootstrap", "10", "--confidence", "1"], "fraction strictly between 0 and 1"),
    (["--bootstrap", "10", "--confidence", "95"], "fraction strictly between 0 and 1"),
    (["--seed", "3"], "--seed applies to the bootstrap"),
    (["--confidence", "0.9"], "--confidence applies to the bootstrap"),
    (["--threads", "2"], "--threads applies to --stream and --bootstrap"),
    (["--bootstrap", "10", "--json", "--report"], "excludes"),
])
def test_usage_errors(spdfit, files, args, message):
    out = spdfit("fit", "-m", "spde", *args, *files)
    assert out.returncode == 2, out.stdout
    assert message in out.stderr


def test_threads_with_bootstrap_alone_is_accepted(spdfit, files):
    out = spdfit("fit", "-m", "spde", "--bootstrap", "10", "--threads", "2", *files)
    assert out.returncode == 0, out.stderr


def test_stream_bootstrap_on_one_group_resamples_rows_in_memory(spdfit, files):
    # 200 rows are one group of 4096: the Poisson scheme would give every replicate the estimate
    # itself (standard errors of 0). The rows are resampled in memory instead, as without --stream.
    streamed = spdfit("fit", "-m", "spde", "--stream", "--bootstrap", "200", "--report", *files)
    assert streamed.returncode == 0, streamed.stderr
    assert "+- 0.000000" not in streamed.stdout
    assert ("needs about 100 groups (409600 rows) for its standard errors, but the data have 200 rows "
            "(1 group): its rows (10 KiB, within the 256 MiB allowed) were resampled one at a time in memory "
            "instead (the in-memory bootstrap)") in streamed.stderr
    j = json.loads(spdfit("fit", "-m", "spde", "--stream", "--bootstrap", "200", "--json", *files).stdout)
    whole = json.loads(spdfit("fit", "-m", "spde", "--bootstrap", "200", "--json", *files).stdout)
    assert j["bootstrap"]["scheme"] == "multinomial"
    assert j["standard_errors"] == whole["standard_errors"]
    assert np.all(np.array(j["standard_errors"]) > 0)


def test_stream_bootstrap_on_few_rows_from_standard_input_resamples_them_in_memory(spdfit, files):
    # Standard input is read once; its text (10 KiB here, within the 256 MiB budget) is kept while
    # it is streamed, and the too few rows are resampled from it as a file's would be.
    text = open(files[0]).read()
    for args in (["-", files[1]], [files[0], "-"]):
        given = text if args[0] == "-" else open(files[1]).read()
        result = spdfit("fit", "-m", "spde", "--stream", "--bootstrap", "50", "--json", *args, input=given)
        assert result.returncode == 0, result.stderr
        assert ("the streaming bootstrap resamples groups of 4096 rows and needs about 100 groups (409600 rows) for "
                "its standard errors, but the data have 200 rows (1 group): its rows (10 KiB, within the 256 MiB "
                "allowed; standard input's text kept from the streaming pass) were resampled one at a time in "
                "memory instead (the in-memory bootstrap)") in result.stderr
        streamed = json.loads(result.stdout)
        whole = json.loads(spdfit("fit", "-m", "spde", "--bootstrap", "50", "--json", *files).stdout)
        assert streamed["bootstrap"]["scheme"] == "multinomial"
        assert streamed["standard_errors"] == whole["standard_errors"]
        assert streamed["X"] == whole["X"]
