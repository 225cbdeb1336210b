"""The 1-DOF belt oscillator typed by hand as a module of docs' model contract (issue 39).

The independent reference of the generic runtime (`beltmdsm.oscillator`): every formula
here is typed from the equation of motion, per unit mass,

    x'' + 2 beta1 omega1 x' + omega1^2 x = alpha_t cos(Omega_t t + phase_t) + f,
    f = -mu(|v_r|) N sgn(v_r)  (slip),   v_r = x' - Vb,
    N = g (1 + alpha_n cos(Omega_n t + phase_n)),

with the friction laws coulomb (mu = mu_s), static_kinetic (mu = mu_k while slipping,
mu_s bounds stick) and stribeck (mu = mu_k + (mu_s - mu_k) exp(-|v_r| / v_s)). In stick
(v_r = 0) the friction is the holding force H that keeps x'' = 0:
H = 2 beta1 omega1 Vb + omega1^2 x - alpha_t cos(Omega_t t + phase_t); it holds while
|H| <= mu_s N (mu(0) N for all three laws).

The derived module ``beltmdsm.generated.models.belt_1dof`` must agree with this one.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

NAME = "belt_1dof"
COORDINATES = ("x",)
STATES = ("x", "x_dot")
UNILATERAL = False
FRICTION_LAWS = ("coulomb", "static_kinetic", "stribeck")
_MODEL = (
    "omega1",
    "beta1",
    "g",
    "Vb",
    "mu_s",
    "alpha_t",
    "Omega_t",
    "phase_t",
    "alpha_n",
    "Omega_n",
    "phase_n",
)
PARAMETERS = {
    "coulomb": _MODEL,
    "static_kinetic": (*_MODEL, "mu_k"),
    "stribeck": (*_MODEL, "mu_k", "v_s"),
}
DEFAULTS = {
    "omega1": 1.0,
    "beta1": 0.1,
    "g": 9.81,
    "Vb": 1.5,
    "mu_s": 0.4,
    "alpha_t": 0.0,
    "Omega_t": 4.0,
    "phase_t": 0.0,
    "alpha_n": 0.0,
    "Omega_n": 4.0,
    "phase_n": 0.0,
    "mu_k": 0.25,
    "v_s": 1.0,
}
EXCITATION = (("x", "alpha_t", "Omega_t", "phase_t"), ("normal", "alpha_n", "Omega_n", "phase_n"))
SURFACES = ("slip_velocity", "stick_forward", "stick_back")


class Kernels(NamedTuple):
    field: object
    jacobian: object
    slip_velocity: object
    slip_gradient: object
    slip_acceleration: object
    normal_force: object
    friction_force: object
    holding_force: object
    stick_limit: object
    gap: object
    saltation: object
    equilibrium: object
    characteristic: object
    hurwitz: object
    surfaces: object
    surface_rates: object


def kernels(friction: str) -> Kernels:
    """The kernels of one friction law (p in ``PARAMETERS[friction]`` order)."""
    if friction not in FRICTION_LAWS:
        raise ValueError(f"friction={friction!r}: not one of {FRICTION_LAWS}")

    def mu(s, p):
        """The slip coefficient at the speed s = |v_r| and its derivative in s."""
        if friction == "coulomb":
            return p[4], 0.0
        if friction == "static_kinetic":
            return p[11], 0.0
        e = math.exp(-s / p[12])
        return p[11] + (p[4] - p[11]) * e, -(p[4] - p[11]) * e / p[12]

    def normal_force(t, y, p):
        return p[2] * (1.0 + p[8] * math.cos(p[9] * t + p[10]))

    def normal_rate(t, p):
        return -p[2] * p[8] * p[9] * math.sin(p[9] * t + p[10])

    def forcing(t, p):
        return p[5] * math.cos(p[6] * t + p[7])

    def forcing_rate(t, p):
        return -p[5] * p[6] * math.sin(p[6] * t + p[7])

    def slip_velocity(t, y, p):
        return y[1] - p[3]

    def slip_gradient(t, y, p):
        return np.array([0.0, 1.0])

    def friction_force(t, y, p, mode):
        if mode == 0:
            return holding_force(t, y, p)
        m, _ = mu(mode * (y[1] - p[3]), p)
        return -mode * m * normal_force(t, y, p)

    def holding_force(t, y, p):
        w, b = p[0], p[1]
        return 2.0 * b * w * y[1] + w * w * y[0] - forcing(t, p)

    def stick_limit(t, y, p):
        return p[4] * normal_force(t, y, p)

    def field(t, y, p, mode):
        if mode == 0:
            return np.array([y[1], 0.0])
        w, b = p[0], p[1]
        acc = -2.0 * b * w * y[1] - w * w * y[0] + forcing(t, p) + friction_force(t, y, p, mode)
        return np.array([y[1], acc])

    def jacobian(t, y, p, mode):
        if mode == 0:
            return np.array([[0.0, 1.0], [0.0, 0.0]])
        w, b = p[0], p[1]
        _, dm = mu(mode * (y[1] - p[3]), p)
        # d/dx' of -mode mu(mode v_r) N = -mode^2 mu' N = -mu' N
        return np.array([[0.0, 1.0], [-w * w, -2.0 * b * w - dm * normal_force(t, y, p)]])

    def slip_acceleration(t, y, p, mode):
        return field(t, y, p, mode)[1]

    def gap(t, y, p):
        raise NotImplementedError("belt_1dof is bilateral: no gap")

    def saltation(t, y, p, before, after):
        f0, f1 = field(t, y, p, before), field(t, y, p, after)
        if before == 0:
            # the stick ends where |H| reaches the limit: h = sgn(H) H - mu_s N
            w, b = p[0], p[1]
            s = 1.0 if holding_force(t, y, p) >= 0.0 else -1.0
            n = s * np.array([w * w, 2.0 * b * w])
            rate = n @ f0 - s * forcing_rate(t, p) - p[4] * normal_rate(t, p)
        else:
            # slip ends on v_r = 0 (into stick or a reversal)
            n = np.array([0.0, 1.0])
            rate = n @ f0
        return np.eye(2) + np.outer(f1 - f0, n) / rate

    def surfaces(t, y, p):
        v, L, H = slip_velocity(t, y, p), stick_limit(t, y, p), holding_force(t, y, p)
        return np.array([v, L + H, L - H])

    def surface_rates(t, y, p, mode):
        # d/dt along the mode's field: x'' = a; H' = 2 b w a + w^2 x' - forcing', L' = mu_s N'
        w, b = p[0], p[1]
        a = field(t, y, p, mode)[1]
        dH = 2.0 * b * w * a + w * w * y[1] - forcing_rate(t, p)
        dL = p[4] * normal_rate(t, p)
        return np.array([a, dL + dH, dL - dH])

    def equilibrium(p):
        # steady sliding, mode -1 (v_r = -Vb): omega1^2 x = mu(Vb) g
        m, _ = mu(p[3], p)
        return np.array([m * p[2] / p[0] ** 2, 0.0])

    def characteristic(p):
        # lambda^2 + (2 beta1 omega1 + g mu'(Vb)) lambda + omega1^2 at steady sliding
        _, dm = mu(p[3], p)
        return np.array([1.0, 2.0 * p[1] * p[0] + p[2] * dm, p[0] ** 2])

    def hurwitz(p):
        a = characteristic(p)
        return np.array([a[1], a[1] * a[2]])

    return Kernels(
        field,
        jacobian,
        slip_velocity,
        slip_gradient,
        slip_acceleration,
        normal_force,
        friction_force,
        holding_force,
        stick_limit,
        gap,
        saltation,
        equilibrium,
        characteristic,
        hurwitz,
        surfaces,
        surface_rates,
    )
