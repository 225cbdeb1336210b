"""The DOP853 tableau typed in derive/dop853.py: the published digits, the order
conditions of an 8(5,3) pair, SciPy's copy, and generated/tableau.py."""

import math

import mpmath
import numpy as np
import pytest

import beltmdsm.generated.tableau as gen
from beltmdsm.derive import dop853

A = np.array(dop853.A)
B = np.array(dop853.B)
C = np.array(dop853.C)
EPS = np.finfo(float).eps
S = dop853.N_STAGES  # the 8th-order step's stages; 13-16 are the dense output's


def _bound(terms, n):
    """Rounding bound of a float sum of products: n eps times the sum of the |terms|
    (Higham's gamma_n), plus a few ulps of the constants' own rounding."""
    return (n + 4) * EPS * terms


@pytest.mark.parametrize(
    "name, exact",
    [
        ("c2", lambda: 2 * (6 - mpmath.sqrt(6)) / 135),
        ("c3", lambda: (6 - mpmath.sqrt(6)) / 45),
        ("c4", lambda: (6 - mpmath.sqrt(6)) / 30),
        ("c5", lambda: (6 + mpmath.sqrt(6)) / 30),
        ("c6", lambda: mpmath.mpf(1) / 3),
        ("c8", lambda: mpmath.mpf(4) / 13),
        ("c9", lambda: mpmath.mpf(127) / 195),
        ("c11", lambda: mpmath.mpf(6) / 7),
        ("c16", lambda: mpmath.mpf(7) / 9),
        ("bhh3", lambda: mpmath.mpf(3) / 136),
    ],
    ids=lambda v: v if isinstance(v, str) else "",
)
def test_published_digits_are_the_closed_forms(name, exact):
    # Hairer, Norsett and Wanner, Sect. II.10: c4, c5 = (6 -+ sqrt 6)/30, c3 = 2/3 c4,
    # c2 = 2/3 c3, and rationals; the typed digits hold no typo where a closed form
    # says what they must be (to the 30 digits printed, truncated or rounded)
    with mpmath.workdps(50):
        value = mpmath.mpf(dop853.PUBLISHED[name])
        assert abs(value - exact()) < mpmath.mpf("1e-29") * abs(value)


def test_row_sums_are_the_nodes():
    # c_i = sum_j a_ij, for every stage, the dense output's included
    terms = np.abs(A).sum(axis=1)
    assert np.all(np.abs(A.sum(axis=1) - C) <= _bound(terms, A.shape[1]))


@pytest.mark.parametrize(
    "q, m", [(q, m) for q in range(1, 9) for m in range(9 - q)], ids=lambda v: str(v)
)
def test_order_eight_conditions_of_tall_bushy_trees(q, m):
    # b^T A^m c^(q-1) = (q-1)! / (q+m)! for every tree of order q + m <= 8 made of a
    # chain of m nodes under a bush of q-1 leaves (m = 0: the quadrature conditions,
    # sum b_i = 1 among them)
    Am, c = A[:S, :S], C[:S]
    value = B @ np.linalg.matrix_power(Am, m) @ c ** (q - 1)
    terms = np.abs(B) @ np.linalg.matrix_power(np.abs(Am), m) @ np.abs(c) ** (q - 1)
    exact = math.factorial(q - 1) / math.factorial(q + m)
    assert abs(value - exact) <= _bound(terms, S * (m + 1) + q)


@pytest.mark.parametrize("name, order", [("E3", 3), ("E5", 5)])
def test_error_estimates_vanish_to_their_order(name, order):
    # b - bhat of an embedded method of order p integrates c^(k-1) exactly for k <= p
    # (so sum e_i = 0), and not for k = p + 1
    e, c = np.array(getattr(dop853, name))[:S], C[:S]
    for k in range(1, order + 1):
        terms = np.abs(e) @ np.abs(c) ** (k - 1)
        assert abs(e @ c ** (k - 1)) <= _bound(terms, S + k), k
    assert abs(e @ c**order) > 1e-4


def test_the_third_order_estimate_is_hairers_b_minus_bhh():
    bhh = {1: "bhh1", 9: "bhh2", 12: "bhh3"}
    for j, (e3, b) in enumerate(zip(dop853.E3, dop853.B), start=1):
        assert e3 == (b - float(dop853.PUBLISHED[bhh[j]]) if j in bhh else b)
    assert dop853.E3[S] == 0.0 and dop853.E5[S] == 0.0


def test_generated_tableau_holds_these_values():
    for name in ("A", "B", "C", "E3", "E5", "D"):
        assert getattr(gen, name) == getattr(dop853, name), name
    assert (gen.N_STAGES, gen.N_STAGES_EXTENDED, gen.INTERPOLATOR_POWER) == (12, 16, 7)


def test_scipys_copy_is_the_same_to_the_bit():
    # SciPy's private module (no public API: skipped where it is gone or moved)
    sc = pytest.importorskip("scipy.integrate._ivp.dop853_coefficients")
    for name in ("A", "B", "C", "E3", "E5", "D"):
        ours, theirs = np.array(getattr(dop853, name)), getattr(sc, name)
        assert ours.shape == theirs.shape, name
        assert ours.tobytes() == np.ascontiguousarray(theirs, dtype=float).tobytes(), name
    assert (sc.N_STAGES, sc.N_STAGES_EXTENDED, sc.INTERPOLATOR_POWER) == (
        dop853.N_STAGES,
        dop853.N_STAGES_EXTENDED,
        dop853.INTERPOLATOR_POWER,
    )
