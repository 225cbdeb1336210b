"""Eq. (4) as a hybrid system: the spec of generated/hybrid.py."""

from __future__ import annotations

import itertools

from .. import hybrid as hy
from .. import laws
from ..codegen import FunctionSpec, ModuleSpec
from ..model import t
from ._shared import (
    CONTACT,
    LAWS_FC,
    STATE_DOCS,
    _per,
)

__all__ = ["build"]


def build() -> ModuleSpec:
    """Eq. (4) as a hybrid system: mode fields, switching surfaces, saltation matrices."""
    state_t = (t,) + hy.STATE
    mode_doc = {
        **STATE_DOCS,
        "mode": "mode code (MODE_CODES): -1 slip_back, 0 stick, "
        "+1 slip_forward, 2 flight, 3 separated",
    }
    surfaces_doc = (
        "h : tuple of ndarray\n    One value per switching surface, in the order of SURFACES."
    )
    salt = {}
    for f, c in itertools.product(laws.choices("friction"), laws.choices("contact")):
        for before, after, surface in hy.transitions():
            salt[(f, c, before, after, surface)] = hy.saltation(before, after, surface, c, f)
    names = sorted({k for k in hy.MODE_CODES})
    salt_opts = LAWS_FC + (
        ("before", "str", "slip_back", "mode before the switch"),
        ("after", "str", "slip_forward", "mode after the switch"),
        ("surface", "str", "relative_velocity", "the surface crossed (SURFACES)"),
    )
    fns = (
        FunctionSpec(
            "vector_field",
            "Vector field (X1', Y1', X2', Y2') of one mode of Eq. (4).",
            "Eqs. (1)-(4)",
            "vector",
            "dstate : ndarray, shape (..., 4)",
            _per(lambda f, c: list(hy.vector_field(c, f)), "friction", "contact"),
            LAWS_FC,
            state_t + (hy.mode,),
            mode_doc,
            notes="Each field is smooth on the whole state space: the contact modes "
            "use the unclipped force of the contact law (with max(X2, 0)) and the "
            "friction law's coefficient at sgn Vr, stick holds X1' = Vb, flight and "
            "separated are free of contact.",
            bind=True,
        ),
        FunctionSpec(
            "mode_jacobian",
            "Jacobian d(X1', Y1', X2', Y2')/d(X1, Y1, X2, Y2) of one mode's field.",
            "Eqs. (1)-(4)",
            "matrix",
            "J : ndarray, shape (..., 4, 4)",
            _per(lambda f, c: hy.mode_jacobian(c, f), "friction", "contact"),
            LAWS_FC,
            state_t + (hy.mode,),
            mode_doc,
            notes="The variational equation Phi' = J Phi of a run within one mode; across "
            "a switch the variation jumps by `saltation`. For a general Floquet "
            "analysis along an event-driven run (every friction law).",
            bind=True,
        ),
        FunctionSpec(
            "response_field",
            "Normal motion and the tangential response to its contact force.",
            "Eqs. (1)-(4)",
            "vector",
            "dstate : ndarray, shape (..., 4)\n    Derivative of (z, z', X2, X2').",
            _per(lambda c: list(hy.response_field(c)[0]), "contact"),
            CONTACT,
            (t,) + hy.response_field(laws.default("contact"))[1] + hy.STATE[2:] + (hy.mode,),
            {
                **mode_doc,
                "z": "tangential response to the contact force [m]",
                "v": "its velocity [m/s]",
            },
            notes="z'' + 2 beta1 omega1 z' + omega1^2 z = F(mode) from rest, beside "
            "the normal equation: the normal motion does not depend on the "
            "tangential one, so the superposition integrator integrates this "
            "once. Friction laws whose slip-mode friction depends on the tangential "
            "state cannot use it (beltmdsm.generated.capabilities).",
            bind=True,
        ),
        FunctionSpec(
            "surfaces",
            "Switching functions h(t, x) of the hybrid system.",
            "Eqs. (1)-(4)",
            "tuple",
            surfaces_doc,
            _per(lambda f, c: [hy.surfaces(c, f)[n] for n in hy.SURFACES], "friction", "contact"),
            LAWS_FC,
            state_t,
            STATE_DOCS,
            notes="relative_velocity Y1 - Vb; stick_forward, stick_back "
            "mu(0) F -+ a_free (the stick cone of the friction law); penetration X2; "
            "contact_force: the sign of F (F over its factors positive in contact).",
            bind=True,
        ),
        FunctionSpec(
            "surface_scales",
            "Rounding scale of each switching function.",
            "Eqs. (1)-(4)",
            "tuple",
            surfaces_doc,
            _per(
                lambda f, c: [hy.surface_scales(c, f)[n] for n in hy.SURFACES],
                "friction",
                "contact",
            ),
            LAWS_FC,
            state_t,
            STATE_DOCS,
            notes="The sum of the absolute values of the terms of h: a computed h "
            "is within a few ulps of it, so a sign decision at a tie uses a "
            "tolerance proportional to it.",
            bind=True,
        ),
        FunctionSpec(
            "surface_rates",
            "Rates dh/dt of the switching functions along a mode.",
            "Eqs. (1)-(4)",
            "tuple",
            surfaces_doc,
            _per(
                lambda f, c: [hy.surface_rates(c, f)[n] for n in hy.SURFACES],
                "friction",
                "contact",
            ),
            LAWS_FC,
            state_t + (hy.mode,),
            mode_doc,
            notes="dh/dt = partial h / partial t + grad h . f(mode): which side of a "
            "surface the field of a mode points to (Filippov's rule), and the "
            "denominator of the saltation matrix.",
            bind=True,
        ),
        FunctionSpec(
            "saltation",
            "Saltation matrix of a switch: the jump of the variational solution.",
            "Eqs. (1)-(4)",
            "matrix",
            "S : ndarray, shape (..., 4, 4)",
            salt,
            salt_opts,
            state_t,
            STATE_DOCS,
            notes="S = I + (f+ - f-) n^T / (dh/dt)-, n = grad h, evaluated at the "
            "state on the surface. It diverges as (dh/dt)- -> 0 (grazing). "
            "Valid (before, after, surface) triples: TRANSITIONS.",
            bind=True,
        ),
    )
    guards = {tl: {m: tuple(g) for m, g in sorted(gs.items())} for tl, gs in hy.GUARDS.items()}
    constants = (
        (
            "MODE_CODES",
            dict(sorted(hy.MODE_CODES.items(), key=lambda kv: kv[1])),
            "Integer code of each mode; the slip codes are sgn(Vr) of Eq. (3).",
        ),
        ("FIELDS", {m: hy.FIELDS[m] for m in names}, "The vector field of each mode."),
        ("SURFACES", hy.SURFACES, "The switching surfaces, in the order of `surfaces`."),
        ("DECIDE_SLIP", hy.DECIDE_SLIP, "Guard target: Filippov's rule at Vr = 0."),
        ("DECIDE_CONTACT", hy.DECIDE_CONTACT, "Guard target: entering contact."),
        (
            "GUARDS",
            guards,
            "Per tension law: mode -> ((surface, crossing direction, target), ...).",
        ),
        ("TRANSITIONS", hy.transitions(), "Every (before, after, surface) of `saltation`."),
    )
    return ModuleSpec(
        "hybrid",
        """Eq. (4) as a hybrid system (derive/hybrid.py).

Modes with smooth vector fields (`vector_field`, by mode code) and their Jacobians
(`mode_jacobian`), the switching surfaces between them (`surfaces`, with rounding
scales and rates along a mode), the guards of each tension law (`GUARDS`: which
surface ends which mode, crossed in which direction, and what follows) and the
saltation matrices of the switches (`saltation`), which the Floquet analysis of the
periodic response needs. Fields, surfaces and saltation matrices take the friction
and contact laws of the registry (``friction=``, ``contact=``).
""",
        fns,
        constants,
    )
