"""A registered model as a hybrid system: surfaces, guards, saltation matrices, Jacobians.

From the mode fields of `beltmdsm.derive.models.system`:

* **switching surfaces** ``h(t, y)``: ``slip_velocity`` ``v_r`` (slip ends, or reverses,
  where it vanishes); ``stick_forward`` ``mu_st N + lambda`` and ``stick_back``
  ``mu_st N - lambda`` (stick ends where the holding force leaves the static limit, on
  the side it leaves); ``gap`` ``-q_k`` (unilateral contacts: positive in flight);
* the surface that a switch between two modes crosses (`SWITCHES`);
* **saltation matrices** ``S = I + (f+ - f-) n^T / (dh/dt)-``, ``n = grad h``,
  ``(dh/dt)- = dh/dt + n^T f-`` (Aizerman-Gantmakher; Leine and Nijmeijer 2004);
* **mode Jacobians** ``d f / d y`` of every mode's field.
"""

from __future__ import annotations

from functools import cache

import sympy as sp

from ..model import t
from .system import System

__all__ = [
    "SWITCHES",
    "DECIDE_SLIP",
    "DECIDE_CONTACT",
    "guards",
    "surfaces",
    "switches",
    "saltation",
    "jacobian",
    "rate",
    "d",
]

#: (mode before, mode after) -> the surface crossed; flight pairs only where unilateral.
SWITCHES = {
    (1, -1): "slip_velocity",
    (-1, 1): "slip_velocity",
    (1, 0): "slip_velocity",
    (-1, 0): "slip_velocity",
    (0, 1): "stick_forward",
    (0, -1): "stick_back",
    (1, 2): "gap",
    (-1, 2): "gap",
    (0, 2): "gap",
    (2, 1): "gap",
    (2, -1): "gap",
    (2, 0): "gap",
}


#: Guard target: Filippov's rule at v_r = 0 (stick, or slip the other way).
DECIDE_SLIP = "decide_slip"
#: Guard target: entering contact (slip by the sign of v_r, or DECIDE_SLIP at v_r = 0).
DECIDE_CONTACT = "decide_contact"


def guards(s: System) -> dict[int, tuple]:
    """mode -> ((surface, crossing direction, target), ...): a mode ends where one of its
    surfaces is crossed in the stated direction (+1: h rises through 0, -1: falls)."""
    out = {
        1: (("slip_velocity", -1, DECIDE_SLIP),),
        -1: (("slip_velocity", 1, DECIDE_SLIP),),
        0: (("stick_forward", -1, 1), ("stick_back", -1, -1)),
    }
    if s.gap is None:
        return out
    out = {m: g + (("gap", 1, 2),) for m, g in out.items()}
    out[2] = (("gap", -1, DECIDE_CONTACT),)
    return out


@cache
def d(expr, x) -> sp.Expr:
    """``d expr / d x`` with powers of one base merged (derive/hybrid.py's ``_d``: a
    symbolic exponent's ``n X**n / X`` is 0/0 at ``max(X, 0) = 0``). Cached: a surface's
    gradient enters its rate in every mode and every saltation matrix across it."""
    return sp.powsimp(sp.diff(expr, x), combine="exp")


def surfaces(s: System) -> dict[str, sp.Expr]:
    """The switching functions by name (module docstring)."""
    out = {
        "slip_velocity": s.slip,
        "stick_forward": s.limit + s.holding,
        "stick_back": s.limit - s.holding,
    }
    if s.gap is not None:
        out["gap"] = s.gap
    return out


def switches(s: System) -> dict[tuple[int, int], str]:
    """The switches of this model (flight only where its contact is unilateral)."""
    return {k: v for k, v in SWITCHES.items() if s.gap is not None or 2 not in k}


def rate(s: System, h: sp.Expr, mode: int) -> sp.Expr:
    """``dh/dt`` along the field of ``mode``."""
    return d(h, t) + sum(d(h, x) * f for x, f in zip(s.state, s.fields[mode]))


def saltation(s: System, before: int, after: int) -> sp.Matrix:
    """The saltation matrix of the switch ``before -> after`` across its surface."""
    h = surfaces(s)[switches(s)[(before, after)]]
    n = sp.Matrix([[d(h, x) for x in s.state]])
    f_minus, f_plus = s.fields[before], s.fields[after]
    return sp.eye(len(s.state)) + (f_plus - f_minus) * n / rate(s, h, before)


def jacobian(s: System, mode: int) -> sp.Matrix:
    """``d f / d y`` of the field of ``mode``."""
    f = s.fields[mode]
    return sp.Matrix(len(f), len(s.state), lambda i, j: d(f[i], s.state[j]))
