"""Steady sliding and Hopf points of belt_1dof (the hand-typed reference and the generated
module), against closed forms."""

import math

import numpy as np
import pytest
import reference_belt_1dof as belt

from beltmdsm.errors import Unsupported
from beltmdsm.oscillator import System, hopf_points, steady_sliding

#: The hand-typed reference and the generated module (the same model, the same checks).
BELTS = [pytest.param(belt, id="reference"), pytest.param("belt_1dof", id="generated")]


@pytest.mark.parametrize("belt", BELTS)
@pytest.mark.parametrize(
    "changes",
    [{}, {"omega1": 2.0, "beta1": 0.05}, {"g": 5.0, "v_s": 0.5, "mu_k": 0.1}],
)
def test_stribeck_hopf_point_is_the_closed_form(belt, changes):
    s = System(belt, friction="stribeck", **changes)
    p = s.params
    # d/dVb of the damping 2 beta1 omega1 + g mu'(Vb) = 0, mu' = -(mu_s - mu_k)/v_s e^(-Vb/v_s)
    typed = p["v_s"] * math.log(
        p["g"] * (p["mu_s"] - p["mu_k"]) / (2 * p["beta1"] * p["omega1"] * p["v_s"])
    )
    found = hopf_points(s, "Vb", 0.01, 10.0)
    assert found.size == 1
    assert found[0] == pytest.approx(typed, abs=1e-12)
    # stable above, unstable below; the eigenvalues cross at +-i omega1
    assert steady_sliding(s.replace(Vb=typed + 0.01)).stable
    below = steady_sliding(s.replace(Vb=typed - 0.01))
    assert not below.stable and below.growth_rate > 0
    at = steady_sliding(s.replace(Vb=typed))
    assert np.allclose(sorted(at.eigenvalues.imag), [-p["omega1"], p["omega1"]], rtol=1e-12)
    assert abs(at.growth_rate) < 1e-12


@pytest.mark.parametrize("belt", BELTS)
def test_equilibrium_eigenvalues_and_hurwitz_agree_with_the_closed_form(belt):
    s = System(belt, friction="stribeck", Vb=1.2)
    p = s.params
    eq = steady_sliding(s)
    mu = p["mu_k"] + (p["mu_s"] - p["mu_k"]) * math.exp(-p["Vb"] / p["v_s"])
    assert eq.state == pytest.approx([mu * p["g"] / p["omega1"] ** 2, 0.0], abs=1e-14)
    assert eq.mode == -1
    c = 2 * p["beta1"] * p["omega1"] - p["g"] * (p["mu_s"] - p["mu_k"]) / p["v_s"] * math.exp(
        -p["Vb"] / p["v_s"]
    )
    typed = np.roots([1.0, c, p["omega1"] ** 2])
    assert np.allclose(
        sorted(eq.eigenvalues, key=lambda z: z.imag), sorted(typed, key=lambda z: z.imag)
    )
    assert not eq.stable and "unstable" in repr(eq)
    assert hopf_points(System(belt, friction="coulomb"), "Vb", 0.1, 5.0).size == 0
    with pytest.raises(Unsupported, match="slip velocity vanishes"):
        steady_sliding(System(belt, Vb=0.0))
    with pytest.raises(ValueError, match="parameter='vb'"):
        hopf_points(s, "vb", 0.1, 5.0)
