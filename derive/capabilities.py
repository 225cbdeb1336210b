"""Capabilities: the structural facts the analyses rely on, decided by SymPy per choice of laws.

The runtime's fast paths assume properties of the model that hold for the paper's laws
and fail for others; each is decided here from the registry's expressions, never
assumed, and the code generator writes the table to ``generated/capabilities.py``:

* ``slip_friction_state_independent``: within a slip mode the friction force does
  not depend on the tangential state ``(X1, X1')`` (`beltmdsm.derive.hybrid.field_of_mode`).
  Then the tangential motion between switches is a linear oscillator driven by the
  contact force, which the superposition integrator and the closed-form Floquet
  path solve in closed form;
* ``one_way_coupling``: the normal equation is free of ``X1`` and ``X1'``
  (`beltmdsm.derive.dynamics.normal_rhs`), so one normal motion serves every tangential
  motion: the cached normal orbit, the block-triangular monodromy matrix and the
  contraction argument (`beltmdsm.derive.contraction`) rely on it;
* ``friction_monotone``: the signed friction coefficient ``sgn(Vr) mu(|Vr|)`` is
  non-decreasing in ``Vr`` (``mu' >= 0`` and ``mu(0) >= 0``), which the contraction
  claim needs; where it fails the reason names the range of ``Vr``
  (`beltmdsm.derive.contraction_sign.monotonicity`);
* ``closed_form_average``: the friction law's average over a harmonic fast motion is
  a closed form (`beltmdsm.derive.averaging.closed_form`), which the MDSM's closed forms
  (the critical belt speed of `beltmdsm.generated.stability`) need; without it the averages
  are quadratures.
"""

from __future__ import annotations

import itertools

from . import averaging, dynamics, hybrid, laws
from .contraction_sign import monotonicity
from .model import X1, Y1

__all__ = [
    "FACTS",
    "slip_friction_state_independent",
    "one_way_coupling",
    "friction_monotone",
    "closed_form_average",
    "capabilities",
]

#: Each fact and what relies on it (one line each).
FACTS = {
    "slip_friction_state_independent": "within a slip mode the friction force does not "
    "depend on X1, X1': the superposition integrator and the closed-form Floquet path",
    "one_way_coupling": "the normal equation is free of X1, X1': the cached normal orbit, "
    "the block-triangular monodromy and the contraction argument",
    "friction_monotone": "sgn(Vr) mu(|Vr|) is non-decreasing in Vr: the contraction claim "
    "(no self-excited vibration when the contact cannot pull)",
    "closed_form_average": "the friction law's average over a harmonic fast motion is a "
    "closed form: the MDSM's closed-form boundaries (beltmdsm.generated.stability)",
}


def slip_friction_state_independent(friction: str, contact: str) -> tuple[bool, str]:
    """Whether the slip modes' friction is free of ``X1``, ``X1'`` (SymPy's free symbols)."""
    found = set()
    for mode in ("slip_back", "slip_forward"):
        field = hybrid.field_of_mode(mode, contact, friction)
        friction_term = field[1] - dynamics.free_acceleration()
        found |= friction_term.free_symbols & {X1, Y1}
    if found:
        names = ", ".join("X1'" if s == Y1 else "X1" for s in sorted(found, key=str))
        return False, (
            f"friction={friction!r}: the slip-mode friction mu(|Vr|) F depends on {names} "
            "through Vr = X1' - Vb"
        )
    return True, f"friction={friction!r}: the slip-mode friction is free of X1 and X1'"


def one_way_coupling(contact: str, tension: str) -> tuple[bool, str]:
    """Whether the normal equation of Eq. (4) is free of ``X1``, ``X1'``."""
    found = dynamics.normal_rhs(contact, tension).free_symbols & {X1, Y1}
    if found:
        return False, (
            f"contact={contact!r}, tension={tension!r}: the normal equation contains "
            f"{sorted(map(str, found))}"
        )
    return True, (
        f"contact={contact!r}, tension={tension!r}: the normal equation is free of X1 and X1'"
    )


def friction_monotone(friction: str) -> tuple[bool, str]:
    """Whether ``sgn(Vr) mu(|Vr|)`` is non-decreasing, with the failing range of ``Vr``."""
    m = monotonicity(friction)
    return m.holds, m.reason


def closed_form_average(friction: str) -> tuple[bool, str]:
    """Whether the law's average over a harmonic fast motion is a closed form (Risch), with
    the weighted averages of the consistent MDSM that ran past their budget
    (`beltmdsm.derive.averaging.fallbacks`; ``python -m derive`` derives them first)."""
    holds, why = averaging.closed_form(friction)
    return holds, "; ".join((why, *averaging.fallbacks(friction)))


_DECIDE = {
    "slip_friction_state_independent": lambda f, c, tn: slip_friction_state_independent(f, c),
    "one_way_coupling": lambda f, c, tn: one_way_coupling(c, tn),
    "friction_monotone": lambda f, c, tn: friction_monotone(f),
    "closed_form_average": lambda f, c, tn: closed_form_average(f),
}


def capabilities() -> dict:
    """``{(friction, contact, tension): {fact: (holds, reason)}}`` for every combination."""
    out = {}
    for key in itertools.product(*(laws.choices(o) for o in laws.OPTIONS)):
        decided = {name: _DECIDE[name](*key) for name in FACTS}
        out[key] = {name: (bool(holds), str(why)) for name, (holds, why) in decided.items()}
    return out
