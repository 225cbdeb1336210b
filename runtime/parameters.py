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
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from generated import unforced
from generated.parameters import BASE, DOMAINS, KNOWN

__all__ = [
    "CONTACTS",
    "METHODS",
    "MAX_SAMPLES",
    "resolve_parameters",
    "initial_state",
    "is_real",
    "excitation_period",
]

CONTACTS = ("hertz_damp", "kelvin_voigt")
#: Annotation types of a run's options: the contact laws (`CONTACTS`), the tension
#: laws (`runtime.model.TENSIONS`; tests/test_typing.py keeps both equal to these) and
#: the backends of the bound kernels (where None is accepted, it means numba if installed).
Contact = Literal["hertz_damp", "kelvin_voigt"]
Tension = Literal["allowed", "clipped"]
Backend = Literal["python", "numba"]
#: The integration methods of the integrators (`runtime._dop853`), by name (the name
#: keys the sweep cache); `runtime.simulate.SolverSettings` accepts these.
METHODS = ("DOP853",)
#: Most samples in a run's time series (``t_end / dt``, `SolverSettings`): each
#: costs 7 floats in the returned arrays, so this caps them near 0.6 GB, and an
#: absurd request fails before anything is allocated.
MAX_SAMPLES = 10**7

#: The domains of the parameter table (``generated.parameters.DOMAINS``) as tests.
_DOMAIN_TESTS = {
    "positive": (lambda x: x > 0, "> 0"),
    "nonnegative": (lambda x: x >= 0, ">= 0"),
    "real": (lambda x: True, "real"),
}

_EXCITATION_DEFAULTS = {
    "alpha_t": "alpha",
    "Omega_t": "Omega",
    "alpha_n": "alpha",
    "Omega_n": "Omega",
}


def is_real(value: object) -> bool:
    """True for a real number (int, float, numpy scalar), False for a bool or anything else."""
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def resolve_parameters(
    params: Mapping[str, float | None] | None = None,
    *,
    contact: Contact = "hertz_damp",
    **overrides: float | None,
) -> dict[str, float]:
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
    for name, value in merged.items():
        test, text = _DOMAIN_TESTS[DOMAINS[name]]
        if not test(value):
            raise ValueError(f"parameter {name!r} must be {text}; got {value!r}")
    return merged


def initial_state(p: Mapping[str, float], contact: Contact = "hertz_damp") -> NDArray[np.float64]:
    """Default initial state: the unforced equilibrium of Eq. (9), at rest.

    ``X1 = mu_s g / omega1^2``, ``X2 = (g / omega2*^2)^(2/3)`` (Hertz-Damp) or
    ``g / omega2^2`` (Kelvin-Voigt), zero velocities; the excitation is switched on at
    t = 0. For ``Vb > 0`` the mass starts sliding backwards relative to the belt.
    """
    return np.array([float(v) for v in unforced.equilibrium(contact=contact, **p)])


#: (`excitation_period`): a common period of more than 1000 periods of the faster
#: excitation is longer than any run of the paper.
_MAX_DENOMINATOR = 1000


def excitation_period(p: Mapping[str, float]) -> float:
    """The common period ``T`` [s] of the excitation of Eq. (4): ``2 pi / gcd``.

    The tangential force ``alpha_t Omega_t^2 sin(Omega_t t + phase_t)`` and the normal
    one (``_n``) repeat together after ``T = 2 pi a / Omega_t = 2 pi b / Omega_n``
    where ``Omega_t / Omega_n = a / b`` in lowest terms. A direction whose force is
    zero (``alpha = 0`` or ``Omega = 0``) is absent and does not enter.

    Parameters
    ----------
    p : dict
        complete parameters (`runtime.parameters.resolve_parameters`)

    Returns
    -------
    float

    Raises
    ------
    ValueError
        Without excitation (no force in either direction: no phase to take), or for
        frequencies ``Omega_t``, ``Omega_n`` whose ratio is not a fraction with a
        denominator up to 1000 within 1e-12 (incommensurate: no common period).

    Examples
    --------
    >>> round(excitation_period({"alpha_t": 2, "Omega_t": 6, "alpha_n": 2, "Omega_n": 4}), 6)
    3.141593
    """
    from fractions import Fraction

    active = [p[f"Omega_{d}"] for d in ("t", "n") if p[f"alpha_{d}"] != 0 and p[f"Omega_{d}"] != 0]
    if not active:
        raise ValueError(
            "no excitation (alpha_t Omega_t = alpha_n Omega_n = 0): there is no "
            "excitation period to take the phase from; continuation needs "
            "Omega > 0 and alpha > 0"
        )
    if len(active) == 1 or active[0] == active[1]:
        return 2 * math.pi / active[0]
    w_t, w_n = active
    ratio = Fraction(w_t / w_n).limit_denominator(_MAX_DENOMINATOR)
    # rounding of the given frequencies only: their ratio must be the fraction
    if abs(ratio.numerator / ratio.denominator - w_t / w_n) > 1e-12 * (w_t / w_n):
        raise ValueError(
            f"Omega_t = {w_t!r} and Omega_n = {w_n!r} are incommensurate (their "
            f"ratio is no fraction a/b with b <= {_MAX_DENOMINATOR}): the "
            "excitation has no common period"
        )
    return 2 * math.pi * ratio.numerator / w_t
