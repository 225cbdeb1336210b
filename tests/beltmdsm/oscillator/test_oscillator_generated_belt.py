"""The generated ``belt_1dof`` (derive/models/entries.py) against the module typed by hand
(reference_belt_1dof.py), kernel by kernel at random states, times and parameters.

The two write the excitation differently: the generated module as the paper does, a
tangential force alpha_t Omega_t^2 sin(Omega_t t + phase_t) and a load g - alpha_n
Omega_n^2 sin(Omega_n t + phase_n); the reference as alpha_t cos(Omega_t t + phase_t)
and g (1 + alpha_n cos(Omega_n t + phase_n)). `to_reference` maps the first's
parameters to the second's (sin x = cos(x - pi/2)).
"""

import math

import numpy as np
import pytest
import reference_belt_1dof as ref

from beltmdsm.generated.models import belt_1dof as gen


def to_reference(q):
    """The reference's parameters of the generated module's ``q``."""
    return {
        **q,
        "alpha_t": q["alpha_t"] * q["Omega_t"] ** 2,
        "phase_t": q["phase_t"] - math.pi / 2,
        "alpha_n": q["alpha_n"] * q["Omega_n"] ** 2 / q["g"],
        "phase_n": q["phase_n"] + math.pi / 2,
    }


def _draw(rng, law):
    q = {n: gen.DEFAULTS[n] * math.exp(rng.uniform(-0.5, 0.5)) for n in gen.PARAMETERS[law]}
    q["alpha_t"] = rng.uniform(0.0, 0.5)
    q["alpha_n"] = rng.uniform(0.0, 0.3) * q["g"] / q["Omega_n"] ** 2  # the load stays > 0
    q["phase_t"], q["phase_n"] = rng.uniform(-3, 3, 2)
    return q


@pytest.mark.parametrize("law", gen.FRICTION_LAWS)
def test_generated_kernels_agree_with_the_hand_typed_module(law):
    assert ref.FRICTION_LAWS == tuple(sorted(gen.FRICTION_LAWS, key=ref.FRICTION_LAWS.index))
    assert (gen.STATES, gen.COORDINATES, gen.UNILATERAL) == (ref.STATES, ref.COORDINATES, False)
    kg, kr = gen.kernels(law), ref.kernels(law)
    rng = np.random.default_rng(39)
    worst = 0.0
    for _ in range(40):
        q = _draw(rng, law)
        r = to_reference(q)
        pg = np.array([q[n] for n in gen.PARAMETERS[law]])
        pr = np.array([r[n] for n in ref.PARAMETERS[law]])
        t = rng.uniform(0.0, 1.0)
        y = np.array([rng.normal(), q["Vb"] + rng.normal()])
        # the error model: rounding of the largest term of the equation of motion (the
        # phase shift pi/2 rounds the excitation's argument to an ulp of it too)
        scale = max(
            q["omega1"] ** 2 * abs(y[0]),
            2 * q["beta1"] * q["omega1"] * abs(y[1]),
            q["mu_s"] * q["g"] * 1.3,
            q["alpha_t"] * q["Omega_t"] ** 2,
        )

        def agree(a, b, scale=scale):
            nonlocal worst
            a, b = np.asarray(a, float), np.asarray(b, float)
            err = np.max(np.abs(a - b)) / scale
            assert np.isfinite(err)
            worst = max(worst, err)

        for mode in (-1, 0, 1):
            agree(kg.field(t, y, pg, mode), kr.field(t, y, pr, mode))
            agree(kg.jacobian(t, y, pg, mode), kr.jacobian(t, y, pr, mode), 1 + scale)
            agree(kg.slip_acceleration(t, y, pg, mode), kr.slip_acceleration(t, y, pr, mode))
            agree(kg.friction_force(t, y, pg, mode), kr.friction_force(t, y, pr, mode))
        for name in ("normal_force", "holding_force", "stick_limit", "slip_velocity"):
            agree(getattr(kg, name)(t, y, pg), getattr(kr, name)(t, y, pr))
        agree(kg.slip_gradient(t, y, pg), kr.slip_gradient(t, y, pr), 1.0)
        agree(kg.equilibrium(pg), kr.equilibrium(pr))
        agree(kg.characteristic(pg), kr.characteristic(pr), 1 + scale)
        agree(kg.hurwitz(pg), kr.hurwitz(pr), (1 + scale) ** 2)
        # the saltation matrices, I + (f+ - f-) n^T / rate, relative to their entries'
        # condition scale / rate: slip's end anywhere (its surface v_r = 0 is the state's),
        # stick's end on its surface, x' = Vb and |H| = mu_s N
        for before, after in ((-1, 0), (1, 0), (-1, 1), (1, -1)):
            S = kr.saltation(t, y, pr, before, after)
            rate = abs(kr.slip_acceleration(t, y, pr, before))
            agree(kg.saltation(t, y, pg, before, after), S, np.abs(S).max() * scale / rate)
        for side, after in ((1, -1), (-1, 1)):
            z = np.array([0.0, q["Vb"]])
            h = side * kr.stick_limit(t, z, pr) - kr.holding_force(t, z, pr)
            z[0] = h / q["omega1"] ** 2
            assert abs(kg.holding_force(t, z, pg)) == pytest.approx(kg.stick_limit(t, z, pg))
            S = kr.saltation(t, z, pr, 0, after)
            # its rate (of |H| - mu_s N along the stick) from S[1, 0] = f+_1 omega1^2 / rate;
            # S = I where the friction is continuous there (coulomb: f+ = f-)
            jump = kr.field(t, z, pr, after)[1] * q["omega1"] ** 2
            rate = abs(jump / S[1, 0]) if S[1, 0] else scale
            agree(kg.saltation(t, z, pg, 0, after), S, np.abs(S).max() * scale / rate)
    assert kg.gap is None
    assert worst < 2e-14, worst
