"""The paper's 2-DOF model with the Kelvin-Voigt contact and Coulomb friction, typed by
hand to the model contract (issue 39): the runtime's check of a unilateral contact.

Per unit mass (docs/modelling.md, Eq. (4) with ``contact="kelvin_voigt"``):

    X1'' + 2 beta1 omega1 X1' + omega1^2 X1 = alpha_t Omega_t^2 sin(Omega_t t + phase_t) + f,
    X2'' = g - alpha_n Omega_n^2 sin(Omega_n t + phase_n) - Fn,

Fn = omega2^2 max(X2, 0) + 2 beta2 omega2 X2' in contact (X2 the penetration; tension
allowed), 0 in flight; f = -mu_s Fn sgn(v_r), v_r = X1' - Vb, in slip; in stick the
holding force H = 2 beta1 omega1 X1' + omega1^2 X1 - alpha_t Omega_t^2 sin(...) holds
while |H| <= mu_s Fn. The gap is -X2: take-off where X2 falls through 0, landing where
it rises through 0.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

NAME = "paper_kelvin_voigt"
COORDINATES = ("X1", "X2")
STATES = ("X1", "X2", "X1_dot", "X2_dot")
UNILATERAL = True
FRICTION_LAWS = ("coulomb",)
PARAMETERS = {
    "coulomb": (
        "beta1",
        "omega1",
        "beta2",
        "omega2",
        "mu_s",
        "g",
        "Vb",
        "alpha_t",
        "Omega_t",
        "phase_t",
        "alpha_n",
        "Omega_n",
        "phase_n",
    )
}
DEFAULTS = {
    "beta1": 0.1,
    "omega1": 1.0,
    "beta2": 0.15,
    "omega2": 3.0,
    "mu_s": 0.4,
    "g": 9.81,
    "Vb": 4.0,
    "alpha_t": 2.0,
    "Omega_t": 4.0,
    "phase_t": 0.0,
    "alpha_n": 2.0,
    "Omega_n": 4.0,
    "phase_n": 0.0,
}
EXCITATION = (("X1", "alpha_t", "Omega_t", "phase_t"), ("X2", "alpha_n", "Omega_n", "phase_n"))
SURFACES = ("slip_velocity", "stick_forward", "stick_back", "gap")


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
    if friction != "coulomb":
        raise ValueError(f"friction={friction!r}: not one of {FRICTION_LAWS}")

    def f_t(t, p):
        return p[7] * p[8] ** 2 * math.sin(p[8] * t + p[9])

    def f_t_rate(t, p):
        return p[7] * p[8] ** 3 * math.cos(p[8] * t + p[9])

    def f_n(t, p):
        return -p[10] * p[11] ** 2 * math.sin(p[11] * t + p[12])

    def normal_force(t, y, p):
        return p[3] ** 2 * max(y[1], 0.0) + 2.0 * p[2] * p[3] * y[3]

    def holding_force(t, y, p):
        return 2.0 * p[0] * p[1] * y[2] + p[1] ** 2 * y[0] - f_t(t, p)

    def stick_limit(t, y, p):
        return p[4] * normal_force(t, y, p)

    def friction_force(t, y, p, mode):
        if mode == 2:
            return 0.0
        if mode == 0:
            return holding_force(t, y, p)
        return -mode * p[4] * normal_force(t, y, p)

    def field(t, y, p, mode):
        normal = p[5] + f_n(t, p) - (0.0 if mode == 2 else normal_force(t, y, p))
        if mode == 0:
            return np.array([y[2], y[3], 0.0, normal])
        ax = -holding_force(t, y, p) + friction_force(t, y, p, mode)
        return np.array([y[2], y[3], ax, normal])

    def jacobian(t, y, p, mode):
        J = np.zeros((4, 4))
        J[0, 2] = J[1, 3] = 1.0
        k2 = p[3] ** 2 if y[1] > 0.0 else 0.0
        c2 = 2.0 * p[2] * p[3]
        if mode != 2:
            J[3, 1], J[3, 3] = -k2, -c2
        if mode != 0:
            J[2, 0], J[2, 2] = -(p[1] ** 2), -2.0 * p[0] * p[1]
        if mode in (-1, 1):
            J[2, 1], J[2, 3] = -mode * p[4] * k2, -mode * p[4] * c2
        return J

    def slip_velocity(t, y, p):
        return y[2] - p[6]

    def slip_gradient(t, y, p):
        return np.array([0.0, 0.0, 1.0, 0.0])

    def slip_acceleration(t, y, p, mode):
        return field(t, y, p, mode)[2]

    def gap(t, y, p):
        return -y[1]

    def saltation(t, y, p, before, after):
        f0, f1 = field(t, y, p, before), field(t, y, p, after)
        if before == 2 or after == 2:
            n, rate = np.array([0.0, 1.0, 0.0, 0.0]), y[3]  # X2 = 0
        elif before == 0:
            s = 1.0 if holding_force(t, y, p) >= 0.0 else -1.0
            k2 = p[3] ** 2 if y[1] > 0.0 else 0.0
            n = s * np.array([p[1] ** 2, 0.0, 2 * p[0] * p[1], 0.0])
            n -= p[4] * np.array([0.0, k2, 0.0, 2 * p[2] * p[3]])
            rate = n @ f0 - s * f_t_rate(t, p)
        else:
            n = np.array([0.0, 0.0, 1.0, 0.0])
            rate = n @ f0
        return np.eye(4) + np.outer(f1 - f0, n) / rate

    def surfaces(t, y, p):
        v, L, H = slip_velocity(t, y, p), stick_limit(t, y, p), holding_force(t, y, p)
        return np.array([v, L + H, L - H, gap(t, y, p)])

    def surface_rates(t, y, p, mode):
        # d/dt along the mode's field (X1'' = a1, X2'' = a2):
        # H' = 2 beta1 omega1 a1 + omega1^2 X1' - f_t', L' = mu_s (omega2^2 [X2 > 0] X2'
        # + 2 beta2 omega2 a2), gap' = -X2'
        _, _, a1, a2 = field(t, y, p, mode)
        dH = 2.0 * p[0] * p[1] * a1 + p[1] ** 2 * y[2] - f_t_rate(t, p)
        k2 = p[3] ** 2 if y[1] > 0.0 else 0.0
        dL = p[4] * (k2 * y[3] + 2.0 * p[2] * p[3] * a2)
        return np.array([a1, dL + dH, dL - dH, -y[3]])

    def equilibrium(p):
        return np.array([p[4] * p[5] / p[1] ** 2, p[5] / p[3] ** 2, 0.0, 0.0])

    def characteristic(p):
        a = np.array([1.0, 2 * p[0] * p[1], p[1] ** 2])
        b = np.array([1.0, 2 * p[2] * p[3], p[3] ** 2])
        return np.convolve(a, b)

    def hurwitz(p):
        _, a1, a2, a3, a4 = characteristic(p)
        H2 = a1 * a2 - a3
        H3 = a3 * H2 - a1 * a1 * a4
        return np.array([a1, H2, H3, a4 * H3])

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
