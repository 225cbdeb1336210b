"""Parameters, initial state and modes of a simulation of Eq. (4).

`resolve_parameters` completes and checks a parameter set once (the generated code
checks every domain and names the offending parameter); `initial_state` is the
unforced equilibrium of Eq. (9). The modes of the hybrid system come from
`generated.hybrid` (`runtime.switching.Mode`); the names below are kept for the
code that uses them.
"""
from __future__ import annotations

import math

import numpy as np

from generated import dynamics, hybrid, unforced
from generated.parameters import BASE, KNOWN

from .switching import MODE_NAMES, Mode

__all__ = ["CONTACTS", "TENSIONS", "resolve_parameters", "initial_state", "Mode",
           "MODE_NAMES", "SLIP_BACK", "SLIP_FORWARD", "STICK", "FLIGHT", "SEPARATED"]

CONTACTS = ("hertz_damp", "kelvin_voigt")
TENSIONS = tuple(hybrid.GUARDS)

SLIP_BACK, SLIP_FORWARD, STICK = Mode.SLIP_BACK, Mode.SLIP_FORWARD, Mode.STICK
FLIGHT, SEPARATED = Mode.FLIGHT, Mode.SEPARATED

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
