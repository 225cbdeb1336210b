"""Parameters and lean right-hand sides of Eq. (4) for the inner ODE loop.

The generated functions in ``generated.dynamics`` are the reference implementation of
Eqs. (1)-(4); they validate every argument on every call, which costs more than the
arithmetic inside a solver loop. The closures here repeat the same arithmetic on
scalars with the parameters bound once; ``tests/test_runtime_model.py`` checks them against
the generated functions on random states to 1e-13.
"""
from __future__ import annotations

import math

import numpy as np

from generated import dynamics, unforced
from generated.parameters import BASE, KNOWN

__all__ = ["CONTACTS", "resolve_parameters", "initial_state", "Lean", "SLIP_BACK",
           "SLIP_FORWARD", "STICK", "FLIGHT", "MODE_NAMES"]

CONTACTS = ("hertz_damp", "kelvin_voigt")

# Modes of the piecewise-smooth system; the slip modes are the friction direction
# sgn(Vr) of Eq. (3), so they can be used as the ``sgn`` argument of the generated code.
SLIP_BACK = -1      # Vr = X1' - Vb < 0: mass slower than the belt
SLIP_FORWARD = 1    # Vr > 0: velocity reversal
STICK = 0           # Vr = 0 held by friction, |a_free| <= mu_s Fn
FLIGHT = 2          # X2 <= 0: no contact, Fn = 0 (Eq. 1)
MODE_NAMES = {SLIP_BACK: "slip-", SLIP_FORWARD: "slip+", STICK: "stick", FLIGHT: "flight"}

_EXCITATION_DEFAULTS = {"alpha_t": "alpha", "Omega_t": "Omega", "alpha_n": "alpha",
                        "Omega_n": "Omega"}


def resolve_parameters(params=None, *, contact="hertz_damp", **overrides):
    """The paper's base set (``generated.parameters.BASE``) updated by the arguments.

    The per-direction excitation keywords (``alpha_t``, ``Omega_t``, ``phase_t``,
    ``alpha_n``, ``Omega_n``, ``phase_n``) are filled in from ``alpha``, ``Omega`` and
    zero, as Eq. (4) has it, so the returned dict is complete and can key a cache.

    Raises
    ------
    ValueError
        Naming the parameter, for an unknown name, a non-finite value or a value
        outside its domain (checked by the generated code), or an unknown contact law.
    """
    if contact not in CONTACTS:
        raise ValueError(f"contact must be one of {CONTACTS}; got {contact!r}")
    merged = dict(BASE)
    for source in (params or {}, overrides):
        for name, value in source.items():
            if name not in KNOWN:
                raise ValueError(f"unknown parameter {name!r}; known: {', '.join(sorted(KNOWN))}")
            if value is None:
                continue
            try:
                value = float(value)
            except (TypeError, ValueError):
                raise ValueError(f"parameter {name!r} must be a number; got {value!r}") from None
            if not math.isfinite(value):
                raise ValueError(f"parameter {name!r} must be finite; got {value!r}")
            merged[name] = value
    for name, default in _EXCITATION_DEFAULTS.items():
        merged.setdefault(name, merged[default])
    merged.setdefault("phase_t", 0.0)
    merged.setdefault("phase_n", 0.0)
    merged.pop("Vhat", None)  # Eq. (23) only; the simulation does not use it
    # The generated code checks every domain and names the offending parameter.
    dynamics.rhs(0.0, 0.0, 0.0, 1.0, 0.0, contact=contact, **merged)
    return merged


def initial_state(p, contact="hertz_damp"):
    """Default initial state: the unforced equilibrium of Eq. (9), at rest.

    ``X1 = mu_s g / omega1^2``, ``X2 = (g / omega2*^2)^(2/3)`` (Hertz-Damp) or
    ``g / omega2^2`` (Kelvin-Voigt), zero velocities; the excitation is switched on at
    t = 0. For ``Vb > 0`` the mass starts sliding backwards relative to the belt.
    """
    return np.array([float(v) for v in unforced.equilibrium(contact=contact, **p)])


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
