"""The generated ``LINEAR_SLIP`` (issue 39): whether every slip mode's unforced field is
affine in the state, derived in derive/models/linearity.py, against the truth built here
with SymPy from the equations typed by hand, for every model and law; and
`beltmdsm.oscillator.hopf_branch` reading it (a module typed by hand without it is
refused, never sampled).

Affine in the state means every second derivative of the field in the state vanishes
identically (SymPy's ``simplify`` to 0). The equations, per unit mass, mode ``s = +-1``
(the sign of ``v_r``), the excitation off, friction ``-s mu(|v_r|) N``:

* ``paper``: ``X1'' = -2 beta1 omega1 Y1 - omega1^2 X1 - s mu F``, ``X2'' = g - F``, ``F =
  (omega2^2 + 2 beta2 omega2 Y2) X2^(3/2)`` (in contact, ``X2 > 0``), ``v_r = Y1 - Vb``;
* ``belt_1dof``: ``x'' = -2 beta1 omega1 x' - omega1^2 x - s mu g``, ``v_r = x' - Vb``;
* ``hoffmann``: ``m x'' = -c1 x' - (k1 + k3/2) x - k3/2 y - s mu (k_c y + F_pre)``, ``m y'' =
  -c2 y' - k3/2 x - (k2 + k3/2 + k_c) y``, ``v_r = x' - Vb``.

The laws: Coulomb ``mu = mu_s``; Stribeck ``mu_k + (mu_s - mu_k) exp(-|v_r| / v_s)``;
static/kinetic ``mu_k`` while slipping.
"""

import pytest
import reference_two_dof as two
import sympy as sp

from beltmdsm.errors import Unsupported
from beltmdsm.generated import models
from beltmdsm.oscillator import System
from beltmdsm.oscillator.hopf_branch import hopf_branch

P = {
    n: sp.Symbol(n, positive=True)
    for n in ("beta1 omega1 g Vb beta2 omega2 mu_s mu_k v_s m k1 k2 k3 k_c F_pre c1 c2".split())
}


def _mu(law, v):
    return {
        "coulomb": P["mu_s"],
        "stribeck": P["mu_k"] + (P["mu_s"] - P["mu_k"]) * sp.exp(-sp.Abs(v) / P["v_s"]),
        "static_kinetic": P["mu_k"],
    }[law]


def _fields(model, law, s):
    """(state symbols, field) of ``model`` in slip mode ``s`` under ``law``."""
    if model == "paper":
        X1, Y1, Y2 = sp.symbols("X1 Y1 Y2", real=True)
        X2 = sp.Symbol("X2", positive=True)
        F = (P["omega2"] ** 2 + 2 * P["beta2"] * P["omega2"] * Y2) * X2 ** sp.Rational(3, 2)
        mu = _mu(law, Y1 - P["Vb"])
        a1 = -2 * P["beta1"] * P["omega1"] * Y1 - P["omega1"] ** 2 * X1 - s * mu * F
        return (X1, Y1, X2, Y2), [Y1, a1, Y2, P["g"] - F]
    if model == "belt_1dof":
        x, xd = sp.symbols("x x_dot", real=True)
        mu = _mu(law, xd - P["Vb"])
        a = -2 * P["beta1"] * P["omega1"] * xd - P["omega1"] ** 2 * x - s * mu * P["g"]
        return (x, xd), [xd, a]
    x, y, xd, yd = sp.symbols("x y x_dot y_dot", real=True)
    N = P["k_c"] * y + P["F_pre"]
    mu = _mu(law, xd - P["Vb"])
    ax = (-P["c1"] * xd - (P["k1"] + P["k3"] / 2) * x - P["k3"] / 2 * y - s * mu * N) / P["m"]
    ay = (-P["c2"] * yd - P["k3"] / 2 * x - (P["k2"] + P["k3"] / 2 + P["k_c"]) * y) / P["m"]
    return (x, y, xd, yd), [xd, yd, ax, ay]


def _affine(model, law):
    """The truth: every second derivative in the state of both slip modes' fields is 0."""
    for s in (1, -1):
        state, f = _fields(model, law, s)
        for fi in f:
            for a in state:
                for b in state:
                    if sp.simplify(sp.diff(fi, a, b)) != 0:
                        return False
    return True


CASES = [(name, law) for name in models.MODELS for law in models.load(name).FRICTION_LAWS]


def test_the_cases_cover_every_model_and_both_answers():
    assert {name for name, _ in CASES} == {"paper", "belt_1dof", "hoffmann"}
    truth = [_affine(name, law) for name, law in CASES]
    assert any(truth) and not all(truth)


@pytest.mark.parametrize("name, law", CASES)
def test_linear_slip_against_the_symbolic_truth(name, law):
    assert models.load(name).LINEAR_SLIP[law] is _affine(name, law)


def test_hopf_branch_refuses_a_module_without_the_flag():
    s = System(two, Vb=1.0)
    assert not hasattr(two, "LINEAR_SLIP")
    with pytest.raises(Unsupported, match="no LINEAR_SLIP"):
        hopf_branch(s, "mu_s", 0.3, 0.1)
