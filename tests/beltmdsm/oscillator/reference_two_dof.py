"""A 2-DOF mode-coupling oscillator typed by hand to the model contract (issue 39).

The runtime's check that nothing in it assumes one coordinate or a unilateral contact:
per unit mass, coordinates x (along the belt) and y (away from it), springs k1 (x),
k2 (y) and a coupling spring k3 along (1, -1)/sqrt 2, stiffness
K = [[k1 + k3/2, -k3/2], [-k3/2, k2 + k3/2]], viscous dampers c1, c2; a bilateral
preloaded contact, N = F_pre - k_c y (never opens), Coulomb friction mu_s N against
v_r = x' - Vb; excitation alpha_t cos(Omega_t t + phase_t) on x:

    x'' + c1 x' + K11 x + K12 y = alpha_t cos(Omega_t t + phase_t) + f,
    y'' + c2 y' + K21 x + K22 y = N - F_pre = -k_c y,

f = -mu_s N sgn(v_r) in slip, the holding force H = c1 Vb + K11 x + K12 y - alpha_t
cos(...) in stick (x'' = 0, the normal motion goes on), held while |H| <= mu_s N.
Steady sliding at mode -1 has the stiffness [[K11, K12 + mu_s k_c], [K21, K22 + k_c]]:
the friction couples the modes (Hoffmann, Fischer and Gaul 2002).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

NAME = "two_dof"
COORDINATES = ("x", "y")
STATES = ("x", "y", "x_dot", "y_dot")
UNILATERAL = False
FRICTION_LAWS = ("coulomb",)
PARAMETERS = {
    "coulomb": (
        "k1",
        "k2",
        "k3",
        "k_c",
        "F_pre",
        "c1",
        "c2",
        "Vb",
        "mu_s",
        "alpha_t",
        "Omega_t",
        "phase_t",
    )
}
DEFAULTS = {
    "k1": 1.25,
    "k2": 0.25,
    "k3": 0.5,
    "k_c": 1.0,
    "F_pre": 1.0,
    "c1": 0.05,
    "c2": 0.05,
    "Vb": 1.0,
    "mu_s": 0.4,
    "alpha_t": 0.0,
    "Omega_t": 1.0,
    "phase_t": 0.0,
}
EXCITATION = (("x", "alpha_t", "Omega_t", "phase_t"),)
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
    if friction != "coulomb":
        raise ValueError(f"friction={friction!r}: not one of {FRICTION_LAWS}")

    def stiff(p):
        k1, k2, k3 = p[0], p[1], p[2]
        return k1 + k3 / 2, -k3 / 2, -k3 / 2, k2 + k3 / 2

    def forcing(t, p):
        return p[9] * math.cos(p[10] * t + p[11])

    def forcing_rate(t, p):
        return -p[9] * p[10] * math.sin(p[10] * t + p[11])

    def normal_force(t, y, p):
        return p[4] - p[3] * y[1]

    def holding_force(t, y, p):
        K11, K12, _, _ = stiff(p)
        return p[5] * y[2] + K11 * y[0] + K12 * y[1] - forcing(t, p)

    def stick_limit(t, y, p):
        return p[8] * normal_force(t, y, p)

    def friction_force(t, y, p, mode):
        if mode == 0:
            return holding_force(t, y, p)
        return -mode * p[8] * normal_force(t, y, p)

    def field(t, y, p, mode):
        K11, K12, K21, K22 = stiff(p)
        ay = -p[6] * y[3] - K21 * y[0] - K22 * y[1] - p[3] * y[1]
        if mode == 0:
            return np.array([y[2], y[3], 0.0, ay])
        ax = -p[5] * y[2] - K11 * y[0] - K12 * y[1] + forcing(t, p) + friction_force(t, y, p, mode)
        return np.array([y[2], y[3], ax, ay])

    def jacobian(t, y, p, mode):
        K11, K12, K21, K22 = stiff(p)
        J = np.zeros((4, 4))
        J[0, 2] = J[1, 3] = 1.0
        J[3] = [-K21, -K22 - p[3], 0.0, -p[6]]
        if mode != 0:
            J[2] = [-K11, -K12 + mode * p[8] * p[3], -p[5], 0.0]
        return J

    def slip_velocity(t, y, p):
        return y[2] - p[7]

    def slip_gradient(t, y, p):
        return np.array([0.0, 0.0, 1.0, 0.0])

    def slip_acceleration(t, y, p, mode):
        return field(t, y, p, mode)[2]

    def gap(t, y, p):
        raise NotImplementedError("bilateral contact: no gap")

    def saltation(t, y, p, before, after):
        f0, f1 = field(t, y, p, before), field(t, y, p, after)
        if before == 0:
            K11, K12, _, _ = stiff(p)
            s = 1.0 if holding_force(t, y, p) >= 0.0 else -1.0
            # h = s H - mu_s N
            n = s * np.array([K11, K12, p[5], 0.0]) + p[8] * p[3] * np.array([0, 1.0, 0, 0])
            rate = n @ f0 - s * forcing_rate(t, p)
        else:
            n = np.array([0.0, 0.0, 1.0, 0.0])
            rate = n @ f0
        return np.eye(4) + np.outer(f1 - f0, n) / rate

    def surfaces(t, y, p):
        v, L, H = slip_velocity(t, y, p), stick_limit(t, y, p), holding_force(t, y, p)
        return np.array([v, L + H, L - H])

    def surface_rates(t, y, p, mode):
        # d/dt along the mode's field: H' = c1 x'' + K11 x' + K12 y' - forcing',
        # L' = -mu_s k_c y'
        K11, K12, _, _ = stiff(p)
        ax = field(t, y, p, mode)[2]
        dH = p[5] * ax + K11 * y[2] + K12 * y[3] - forcing_rate(t, p)
        dL = -p[8] * p[3] * y[3]
        return np.array([ax, dL + dH, dL - dH])

    def _effective(p):
        """Stiffness at steady sliding, mode -1 (friction +mu_s N)."""
        K11, K12, K21, K22 = stiff(p)
        return K11, K12 + p[8] * p[3], K21, K22 + p[3]

    def equilibrium(p):
        k11, k12, k21, k22 = _effective(p)
        det = k11 * k22 - k12 * k21
        rhs = p[8] * p[4]  # mu_s F_pre on x, 0 on y
        return np.array([k22 * rhs / det, -k21 * rhs / det, 0.0, 0.0])

    def characteristic(p):
        k11, k12, k21, k22 = _effective(p)
        c1, c2 = p[5], p[6]
        return np.array(
            [1.0, c1 + c2, k11 + k22 + c1 * c2, c1 * k22 + c2 * k11, k11 * k22 - k12 * k21]
        )

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
