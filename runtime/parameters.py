"""Model parameters of a run: the base set completed and checked, the initial state, limits.

`resolve_parameters` turns what a caller gives (a dict, keywords, command-line
flags) into the complete, checked parameter dict that every run and every cache key
uses; `initial_state` is the default start of a run. Both are re-exported by
`runtime.model`, where they used to live.
"""
from __future__ import annotations

import math
import numbers
from collections.abc import Mapping

import numpy as np

from generated import dynamics, unforced
from generated.parameters import BASE, KNOWN

__all__ = ["CONTACTS", "METHODS", "MAX_SAMPLES", "resolve_parameters",
           "initial_state", "is_real"]

CONTACTS = ("hertz_damp", "kelvin_voigt")
#: The integration methods of the integrators (`runtime._dop853`), by name (the name
#: keys the sweep cache); `runtime.simulate.SolverSettings` accepts these.
METHODS = ("DOP853",)
#: Most samples in a run's time series (``t_end / dt``, `SolverSettings`): each
#: costs 7 floats in the returned arrays, so this caps them near 0.6 GB, and an
#: absurd request fails before anything is allocated.
MAX_SAMPLES = 10**7

_EXCITATION_DEFAULTS = {"alpha_t": "alpha", "Omega_t": "Omega", "alpha_n": "alpha",
                        "Omega_n": "Omega"}


def is_real(value):
    """True for a real number (int, float, numpy scalar), False for a bool or anything else."""
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def resolve_parameters(params=None, *, contact="hertz_damp", **overrides):
    """The paper's base set (``generated.parameters.BASE``) updated by the arguments.

    The per-direction excitation keywords (``alpha_t``, ``Omega_t``, ``phase_t``,
    ``alpha_n``, ``Omega_n``, ``phase_n``) are filled in from ``alpha``, ``Omega`` and
    zero, as Eq. (4) has it, so the returned dict is complete and can key a cache.
    ``None`` leaves a parameter at its default.

    Raises
    ------
    ValueError
        Naming the parameter, for an unknown name, a value that is not a real number
        (a bool, a string, an array), NaN or infinite, or a value outside its domain
        (checked by the generated code); or naming the contact law if it is unknown.
    """
    if contact not in CONTACTS:
        raise ValueError(f"contact must be one of {CONTACTS}; got {contact!r}")
    if params is not None and not isinstance(params, Mapping):
        raise ValueError(f"params must be a dict of parameters; got {type(params).__name__}")
    merged = dict(BASE)
    for source in (params or {}, overrides):
        for name, value in source.items():
            if name not in KNOWN:
                raise ValueError(f"unknown parameter {name!r}; known: {', '.join(sorted(KNOWN))}")
            if value is None:
                continue
            # float(True) is 1.0: a flag passed where a number belongs is a mistake
            if isinstance(value, (bool, np.bool_)):
                raise ValueError(f"parameter {name!r} must be a number; got {value!r}")
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
