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
            examples=(
                "Sticking (mode 0) the mass moves with the belt, X1' = Vb and X1'' = 0; in\n"
                "flight (mode 2, X2 < 0) only the spring, damper and gravity act:\n"
                "\n"
                ">>> from beltmdsm.generated import hybrid\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> hybrid.vector_field(0.0, 1.0, 4.0, 11.5, 0.0, 0, **BASE)[:2].tolist()\n"
                "[4.0, 0.0]\n"
                ">>> d = hybrid.vector_field(0.0, 1.0, 0.5, -1.0, 0.1, 2, **BASE)\n"
                ">>> d.round(4).tolist()\n"
                "[0.5, -1.1, 0.1, 9.81]"
            ),
            bind_examples=(
                "The kernel at one point gives `vector_field` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import hybrid\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.3, 1.0, 0.5, 11.5, 0.1, -1)\n"
                '>>> kernel = hybrid.bind_vector_field(**BASE, backend="python")\n'
                ">>> (np.round(np.ravel(kernel(*x)), 4) + 0.0).tolist()\n"
                "[0.5, 32.8591, 0.1, -30.3498]\n"
                ">>> ref = hybrid.vector_field(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
            examples=(
                "Sliding back (mode -1) at the unforced equilibrium it is J^0 (Eq. 11):\n"
                "\n"
                ">>> from beltmdsm.generated import hybrid, unforced\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> import numpy as np\n"
                ">>> J = hybrid.mode_jacobian(0.0, *unforced.equilibrium(**BASE), -1, **BASE)\n"
                ">>> bool(np.allclose(J, unforced.jacobian_at_equilibrium(**BASE)))\n"
                "True"
            ),
            bind_examples=(
                "The kernel at one point gives `mode_jacobian` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import hybrid\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.3, 1.0, 0.5, 11.5, 0.1, -1)\n"
                '>>> kernel = hybrid.bind_mode_jacobian(**BASE, backend="python")\n'
                ">>> (np.round(np.ravel(kernel(*x)), 4) + 0.0)[4:8].tolist()  # row 2\n"
                "[-1.0, -0.2, 0.5392, 2.3399]\n"
                ">>> ref = hybrid.mode_jacobian(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
            examples=(
                "From rest (z = z' = 0) at the equilibrium penetration, sliding back, the\n"
                "response is driven by the contact force, g:\n"
                "\n"
                ">>> from beltmdsm.generated import hybrid, unforced\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> X2 = float(unforced.equilibrium(**BASE)[2])\n"
                ">>> d = hybrid.response_field(0.0, 0.0, 0.0, X2, 0.0, -1, **BASE)\n"
                ">>> round(float(d[0]), 4), round(float(d[1]), 4)\n"
                "(0.0, 9.81)"
            ),
            bind_examples=(
                "The kernel at one point gives `response_field` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import hybrid\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.3, 0.0, 0.0, 11.5, 0.1, -1)\n"
                '>>> kernel = hybrid.bind_response_field(**BASE, backend="python")\n'
                ">>> (np.round(np.ravel(kernel(*x)), 4) + 0.0).tolist()\n"
                "[0.0, 10.3346, 0.1, -30.3498]\n"
                ">>> ref = hybrid.response_field(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
            examples=(
                "The relative velocity X1' - Vb and the penetration X2 (SURFACES order):\n"
                "\n"
                ">>> from beltmdsm.generated import hybrid\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> h = hybrid.surfaces(0.0, 1.0, 0.5, 11.5, 0.1, **BASE)\n"
                ">>> named = {k: round(float(v), 4) for k, v in zip(hybrid.SURFACES, h)}\n"
                '>>> named["relative_velocity"], named["penetration"]\n'
                "(-3.5, 11.5)"
            ),
            bind_examples=(
                "The kernel at one point gives `surfaces` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import hybrid\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.3, 1.0, 0.5, 11.5, 0.1)\n"
                '>>> kernel = hybrid.bind_surfaces(**BASE, backend="python")\n'
                ">>> (np.round(np.ravel(kernel(*x)), 4) + 0.0).tolist()\n"
                "[-3.5, -24.5914, 32.8591, 11.5, 0.53]\n"
                ">>> ref = hybrid.surfaces(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
            examples=(
                "One positive scale per surface (SURFACES order):\n"
                "\n"
                ">>> from beltmdsm.generated import hybrid\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> s = hybrid.surface_scales(0.0, 1.0, 0.5, 11.5, 0.1, **BASE)\n"
                ">>> len(s) == len(hybrid.SURFACES), all(float(v) > 0 for v in s)\n"
                "(True, True)"
            ),
            bind_examples=(
                "The kernel at one point gives `surface_scales` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import hybrid\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.3, 1.0, 0.5, 11.5, 0.1)\n"
                '>>> kernel = hybrid.bind_surface_scales(**BASE, backend="python")\n'
                ">>> (np.round(np.ravel(kernel(*x)), 4) + 0.0).tolist()\n"
                "[4.5, 48.9736, 48.9736, 11.5, 0.53]\n"
                ">>> ref = hybrid.surface_scales(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
            examples=(
                "Along mode -1 the relative velocity changes at X1'' of that mode, the\n"
                "penetration at X2':\n"
                "\n"
                ">>> from beltmdsm.generated import hybrid\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> r = hybrid.surface_rates(0.0, 1.0, 0.5, 11.5, 0.1, -1, **BASE)\n"
                ">>> f = hybrid.vector_field(0.0, 1.0, 0.5, 11.5, 0.1, -1, **BASE)\n"
                ">>> named = dict(zip(hybrid.SURFACES, r))\n"
                '>>> round(float(named["relative_velocity"]), 4) == round(float(f[1]), 4)\n'
                "True\n"
                '>>> round(float(named["penetration"]), 4)\n'
                "0.1"
            ),
            bind_examples=(
                "The kernel at one point gives `surface_rates` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import hybrid\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.3, 1.0, 0.5, 11.5, 0.1, -1)\n"
                '>>> kernel = hybrid.bind_surface_rates(**BASE, backend="python")\n'
                ">>> (np.round(np.ravel(kernel(*x)), 4) + 0.0).tolist()\n"
                "[32.8591, -110.2717, -31.6518, 0.1, -9.1049]\n"
                ">>> ref = hybrid.surface_rates(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
            examples=(
                "Slip back to slip forward at Vr = 0 (the defaults): det S is the ratio of\n"
                "the accelerations X1'' after and before the switch:\n"
                "\n"
                ">>> from beltmdsm.generated import hybrid, unforced\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> import numpy as np\n"
                ">>> x = (0.0, 1.0, 4.0, float(unforced.equilibrium(**BASE)[2]), 0.0)\n"
                ">>> S = hybrid.saltation(*x, **BASE)\n"
                ">>> a_before = hybrid.vector_field(*x, -1, **BASE)[1]\n"
                ">>> a_after = hybrid.vector_field(*x, 1, **BASE)[1]\n"
                ">>> round(float(np.linalg.det(S)), 4), round(float(a_after / a_before), 4)\n"
                "(-2.6949, -2.6949)"
            ),
            bind_examples=(
                "The kernel at one point gives `saltation` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import hybrid\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.3, 1.0, 4.0, 11.5, 0.0)\n"
                '>>> kernel = hybrid.bind_saltation(**BASE, backend="python")\n'
                ">>> (np.round(np.ravel(kernel(*x)), 4) + 0.0)[4:8].tolist()  # row 2\n"
                "[0.0, 0.7557, 0.0, 0.0]\n"
                ">>> ref = hybrid.saltation(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
