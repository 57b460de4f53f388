"""experiment thesis|paper-hexapod|paper-2x2 --methods a,b,...: the chosen methods' numbers are
those of the default run with the same seed (each trial's data do not depend on the methods run),
unknown or repeated names are usage errors (exit 2)."""
import json

import pytest

RUNS = {
    "thesis": ["experiment", "thesis", "--noise-var", "0.86", "--trials", "50"],
    "paper-hexapod": ["experiment", "paper-hexapod", "--trials", "20"],
    "paper-2x2": ["experiment", "paper-2x2", "--std-a", "0.5", "--trials", "200"],
}


def run_json(spdfit, args):
    result = spdfit("--quiet", *args, "--json")
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)["methods"]


@pytest.mark.parametrize("experiment", sorted(RUNS))
def test_a_subset_of_methods_gives_the_default_runs_numbers(spdfit, experiment):
    everything = run_json(spdfit, RUNS[experiment] + ["--methods", "ls,procrustes,tls,tls-sym,tls-psd,spde"])
    subset = run_json(spdfit, RUNS[experiment] + ["--methods", "spde,tls-sym"])
    assert sorted(subset) == ["spde", "tls-sym"]  # {method: statistics}
    for name in subset:
        assert subset[name] == everything[name]


@pytest.mark.parametrize("methods, message", [("spde,bogus", "bogus is not one of ls, procrustes"), ("spde,spde", "listed twice")])
def test_bad_method_lists_are_usage_errors(spdfit, methods, message):
    result = spdfit(*RUNS["paper-2x2"], "--methods", methods)
    assert result.returncode == 2
    assert message in result.stderr
