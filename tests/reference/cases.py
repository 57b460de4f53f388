"""Seeded data sets shared by the reference self-tests and the CLI comparison.

All are well conditioned with rank(A) = rank(B) = n, so every method's formula applies
(unless thesis_reference.degeneracy says otherwise for a particular case).
"""
import numpy as np

import thesis_reference as ref


def _thesis(m, nm, seed):
    return lambda: ref.thesis_generator(m, 6, nm, np.random.default_rng(seed))[:2]


def _paper_2x2(seed, std_a=0.5):
    return lambda: ref.paper_example(np.random.default_rng(seed), std_a=std_a)[:2]


def _scalar(seed, m=20, x=2.5):
    """n = 1: a x ~= b with noise in both a and b (paper section II, one parameter)."""
    def make():
        rng = np.random.default_rng(seed)
        a = 1.0 + rng.random((m, 1))
        return a + 0.1 * rng.standard_normal((m, 1)), x * a + 0.1 * rng.standard_normal((m, 1))
    return make


CASES = {}
for _nm in (1.0, 3.2, 3.9):  # thesis experiments 1, 2, 3
    for _seed in (1, 2, 3):
        CASES[f"thesis-m12-nm{_nm}-s{_seed}"] = _thesis(12, _nm, _seed)
CASES["thesis-m100-nm1.0"] = _thesis(100, 1.0, 11)
CASES["thesis-m100-nm3.9"] = _thesis(100, 3.9, 12)
CASES["thesis-square-m6"] = _thesis(6, 1.0, 21)  # m = n (paper Remark III.5)
CASES["paper-2x2-s1"] = _paper_2x2(31)
CASES["paper-2x2-s2"] = _paper_2x2(32)
# Larger noise in A (the paper goes up to STD{v_a} = 1.9): seeds picked so that A'B+B'A,
# the Procrustes estimate and X_TLS are all indefinite, exercising Higham's clipping.
CASES["paper-2x2-indef-s42"] = _paper_2x2(42, std_a=1.5)
CASES["paper-2x2-indef-s80"] = _paper_2x2(80, std_a=1.5)
CASES["scalar-n1-s1"] = _scalar(41)
CASES["scalar-n1-s2"] = _scalar(42, m=3)


def make_case(name):
    """Return (A, B) for a case id."""
    return CASES[name]()
