"""Forced periodic responses of belt_1dof (the hand-typed reference and the generated
module): Den Hartog's non-stop motion."""

import math

import numpy as np
import pytest
import reference_belt_1dof as belt

from beltmdsm.errors import Unsupported
from beltmdsm.oscillator import System, forced_response
from beltmdsm.oscillator.hybrid import flow

#: The hand-typed reference and the generated module (the same model, the same checks).
BELTS = [pytest.param(belt, id="reference"), pytest.param("belt_1dof", id="generated")]


def tangential(model, a, W):
    """The parameters of the force a cos(W t): the reference types alpha_t cos(Omega_t t +
    phase_t), the generated module the paper's alpha_t Omega_t^2 sin(Omega_t t + phase_t)."""
    if model is belt:
        return {"alpha_t": a, "Omega_t": W}
    return {"alpha_t": a / W**2, "Omega_t": W, "phase_t": math.pi / 2}


def den_hartog_amplitude(r, U):
    """Den Hartog's non-stop amplitude over the static deflection a / omega^2.

    J. P. Den Hartog, "Forced vibrations with combined Coulomb and viscous friction",
    Trans. ASME 53 (APM-53-9), 1931, 107-115, without viscous damping. Derivation: for
    x'' + w^2 x = a cos(W t) - F sgn(x'), the non-stop motion is antisymmetric,
    x(t + pi/W) = -x(t), and on a half period with x' > 0 from the turning point
    x = -X, x' = 0 at W t0 = psi it is x = C cos(W t) - F/w^2 + A cos(w tau)
    + B sin(w tau), C = a / (w^2 - W^2), tau = t - t0. The conditions x' = 0 at both
    ends and x = +X at tau = pi/W give B = C W sin(psi) / w, sin(psi) = (F / (w W C))
    tan(pi w / (2 W)) and X = -C cos(psi); with r = W / w and U = F / a,

        X / (a / w^2) = sqrt(1 / (1 - r^2)^2 - (U tan(pi / (2 r)) / r)^2).
    """
    return math.sqrt(1 / (1 - r * r) ** 2 - (U * math.tan(math.pi / (2 * r)) / r) ** 2)


def _fd_monodromy(system, x, T, delta=1e-5):
    cols = []
    for e in np.eye(x.size):
        plus = flow(system, 0.0, x + delta * e, T).y
        minus = flow(system, 0.0, x - delta * e, T).y
        cols.append((plus - minus) / (2 * delta))
    return np.array(cols).T


@pytest.mark.parametrize("belt", BELTS)
@pytest.mark.parametrize("r, U, omega1", [(0.8, 0.3, 1.0), (2.0, 0.3, 1.0), (1.5, 0.2, 2.0)])
def test_den_hartog_non_stop_solution(belt, r, U, omega1):
    a, g = 1.0, 9.81
    s = System(
        belt,
        friction="coulomb",
        Vb=0.0,
        beta1=0.0,
        omega1=omega1,
        mu_s=U * a / g,
        **tangential(belt, a, r * omega1),
    )
    resp = forced_response(s)
    assert resp.period == pytest.approx(2 * math.pi / (r * omega1), rel=1e-15)
    # continuous sliding: two reversals a period, no stick
    assert [(b, c) for _, b, c in resp.switches] in ([(1, -1), (-1, 1)], [(-1, 1), (1, -1)])
    assert resp.sticks == 0
    turn = flow(s, 0.0, resp.state, resp.period, stop=lambda sw, n: True)
    X = abs(turn.y[0])
    assert X == pytest.approx(den_hartog_amplitude(r, U) * a / omega1**2, rel=1e-9)
    assert abs(turn.y[1]) < 1e-9
    # half a period later, the mirror image (antisymmetry)
    half = flow(s, 0.0, resp.state, resp.period / 2)
    assert half.y == pytest.approx(-resp.state, abs=1e-9)
    # multipliers against central differences of the period map (no saltation there)
    M_fd = _fd_monodromy(s, resp.state, resp.period)
    assert np.allclose(resp.monodromy, M_fd, atol=1e-6)
    assert sorted(abs(np.linalg.eigvals(M_fd))) == pytest.approx(
        sorted(abs(resp.multipliers)), abs=1e-6
    )


@pytest.mark.parametrize("belt", BELTS)
def test_unforced_model_is_refused(belt):
    with pytest.raises(Unsupported, match="every excitation amplitude is 0"):
        forced_response(System(belt))
    with pytest.raises(ValueError, match="periods=0"):
        forced_response(System(belt, alpha_t=1.0), periods=0)
