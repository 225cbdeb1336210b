"""Lean right-hand sides of Eq. (4) for the inner ODE loop (parameters: `runtime.parameters`).

The generated functions in ``generated.dynamics`` are the reference implementation of
Eqs. (1)-(4); they validate every argument on every call, which costs more than the
arithmetic inside a solver loop. The closures here repeat the same arithmetic on
scalars with the parameters bound once; ``tests/test_model.py`` checks them against
the generated functions on random states to 1e-13.
"""
from __future__ import annotations

import math

import numpy as np

# Re-exported: they lived here before runtime.parameters existed.
from .parameters import CONTACTS, initial_state, resolve_parameters

__all__ = ["CONTACTS", "resolve_parameters", "initial_state", "Lean", "SLIP_BACK",
           "SLIP_FORWARD", "STICK", "FLIGHT", "MODE_NAMES"]

# Modes of the piecewise-smooth system; the slip modes are the friction direction
# sgn(Vr) of Eq. (3), so they can be used as the ``sgn`` argument of the generated code.
SLIP_BACK = -1      # Vr = X1' - Vb < 0: mass slower than the belt
SLIP_FORWARD = 1    # Vr > 0: velocity reversal
STICK = 0           # Vr = 0 held by friction, |a_free| <= mu_s Fn
FLIGHT = 2          # X2 <= 0: no contact, Fn = 0 (Eq. 1)
MODE_NAMES = {SLIP_BACK: "slip-", SLIP_FORWARD: "slip+", STICK: "stick", FLIGHT: "flight"}

class Lean:
    """Scalar closures of Eq. (4) with the parameters bound once.

    Attributes mirror the generated functions: ``normal_force(X2, Y2)`` (Eq. 1),
    ``branch(sgn)`` -> ``f(t, y)`` (= ``rhs_branch``), ``stick_rhs`` (the sticking
    mode: X1' = Vb, Y1' = 0), ``free_acceleration(t, y)`` (= ``rhs_branch(sgn=0)[1]``).
    """

    def __init__(self, p, contact="hertz_damp"):
        self.p, self.contact = p, contact
        c1, k1 = 2 * p["beta1"] * p["omega1"], p["omega1"] ** 2
        c2, k2 = 2 * p["beta2"] * p["omega2"], p["omega2"] ** 2
        at = p["alpha_t"] * p["Omega_t"] ** 2
        wt, pt = p["Omega_t"], p["phase_t"]
        an = p["alpha_n"] * p["Omega_n"] ** 2
        wn, pn = p["Omega_n"], p["phase_n"]
        g, mu, Vb = p["g"], p["mu_s"], p["Vb"]
        self.c1, self.k1, self.c2, self.k2, self.mu, self.Vb = c1, k1, c2, k2, mu, Vb
        sin, sqrt = math.sin, math.sqrt

        if contact == "hertz_damp":
            def normal_force(X2, Y2):
                return (c2 * Y2 + k2) * X2 * sqrt(X2) if X2 > 0.0 else 0.0
        else:
            def normal_force(X2, Y2):
                return c2 * Y2 + k2 * X2 if X2 > 0.0 else 0.0
        self.normal_force = normal_force

        def branch(sgn):
            ms = mu * sgn

            def f(t, y):
                X1, Y1, X2, Y2 = y
                Fn = normal_force(X2, Y2)
                return np.array([Y1, at * sin(wt * t + pt) - c1 * Y1 - k1 * X1 - ms * Fn,
                                 Y2, g - an * sin(wn * t + pn) - Fn])
            return f
        self.branch = branch

        def stick_rhs(t, y):
            return np.array([Vb, 0.0, y[3], g - an * sin(wn * t + pn) - normal_force(y[2], y[3])])
        self.stick_rhs = stick_rhs

        def free_acceleration(t, y):
            return at * sin(wt * t + pt) - c1 * y[1] - k1 * y[0]
        self.free_acceleration = free_acceleration

        def normal_rhs(t, y):
            return np.array([y[1], g - an * sin(wn * t + pn) - normal_force(y[0], y[1])])
        self.normal_rhs = normal_rhs
