"""runtime.model: parameters, initial state; the runtime imports no SymPy and types no physics."""

import subprocess
import sys

import numpy as np
import pytest

from generated import dynamics
from runtime.model import initial_state, resolve_parameters


def test_rhs_with_sign_equals_branch_in_each_direction():
    p = resolve_parameters(Vb=4.0)
    y = initial_state(p)
    for vr, sgn in ((-1.0, -1.0), (1.0, 1.0)):
        state = y + np.array([0, p["Vb"] + vr, 0, 0])
        np.testing.assert_array_equal(
            dynamics.rhs(0.7, *state, **p), dynamics.rhs_branch(0.7, *state, sgn, **p)
        )


def test_initial_state_is_the_unforced_equilibrium_eq9():
    p = resolve_parameters()
    X1, Y1, X2, Y2 = initial_state(p)
    # X1: * and / only, 3 correctly rounded steps a side: <= 3 eps = 6.7e-16 on any CPU.
    # X2: three cube roots at <= 4 ulp and 3 roundings (13.5 eps) against libm's pow
    # (< 1 ulp) of a 2-rounding quotient to the rounded power 2/3 (~2.6 eps): <= 3.6e-15
    assert X1 == pytest.approx(p["mu_s"] * p["g"] / p["omega1"] ** 2, rel=1e-15)
    assert X2 == pytest.approx((p["g"] / p["omega2"] ** 2) ** (2 / 3), rel=1e-14)
    assert Y1 == Y2 == 0
    # at rest, sliding backwards, without excitation: no acceleration
    q = dict(p, alpha=0.0, alpha_t=0.0, alpha_n=0.0)
    np.testing.assert_allclose(dynamics.rhs(0.0, X1, Y1, X2, Y2, **q), 0.0, atol=1e-13)


def test_resolve_parameters_fills_the_excitation_of_eq4():
    p = resolve_parameters(alpha=1.5, Omega=6.0, Omega_n=4.0)
    assert (p["alpha_t"], p["alpha_n"], p["Omega_t"], p["Omega_n"]) == (1.5, 1.5, 6.0, 4.0)
    assert p["phase_t"] == p["phase_n"] == 0.0


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"Vb": -1.0}, "Vb"),
        ({"omega1": 0.0}, "omega1"),
        ({"beta1": float("nan")}, "beta1"),
        ({"mu_s": float("inf")}, "mu_s"),
        ({"Vbelt": 1.0}, "Vbelt"),
        ({"g": "x"}, "g"),
    ],
)
def test_bad_parameters_raise_valueerror_naming_them(kwargs, name):
    with pytest.raises(ValueError, match=name):
        resolve_parameters(**kwargs)


def test_bad_contact_law_is_named():
    with pytest.raises(ValueError, match="contact"):
        resolve_parameters(contact="coulomb")


def test_importing_runtime_does_not_import_sympy():
    code = (
        "import sys, runtime, runtime.simulate, runtime.superposition, runtime.spectra, "
        "runtime.modulation, runtime.sweep, runtime.cli; "
        "sys.exit(1 if any(m == 'sympy' or m.startswith('sympy.') for m in sys.modules) else 0)"
    )
    assert subprocess.run([sys.executable, "-c", code]).returncode == 0
