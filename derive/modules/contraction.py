"""The energy of a difference of two motions: the spec of generated/contraction.py."""

from __future__ import annotations

from .. import contraction_energy as ctr
from ..codegen import FunctionSpec, ModuleSpec

__all__ = ["build"]


def build() -> ModuleSpec:
    """The energy of the difference of two tangential motions (derive/contraction.py)."""
    docs = {
        "e": "difference of the tangential displacements X1 of two runs [m]",
        "e_dot": "difference of their velocities X1' [m/s]",
    }
    functions = (
        FunctionSpec(
            "difference_energy",
            "Energy E_d(e, e') of the difference of two tangential motions.",
            "Eq. (4) (derive/contraction.py)",
            "value",
            "E_d : ndarray\n    The tangential part of the mechanical energy at (e, e').",
            {(): ctr.difference_energy()},
            (),
            (ctr.e, ctr.ep),
            docs,
            notes="Two runs under one normal motion: dE_d/dt = -c1 e'^2 - (f_a - f_b) F e' "
            "(`difference_damping`), the evidence of the contraction claim.",
            examples=(
                "(e'^2 + omega1^2 e^2) / 2 = (4 + 1) / 2 at e = 1, e' = 2:\n"
                "\n"
                ">>> from beltmdsm.generated import contraction\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> float(contraction.difference_energy(1.0, 2.0, **BASE))\n"
                "2.5"
            ),
        ),
        FunctionSpec(
            "difference_damping",
            "The dashpot's coefficient c1 in dE_d/dt = -c1 e'^2 + the friction's part.",
            "Eq. (4) (derive/contraction.py)",
            "value",
            "c1 : ndarray\n    -d a_free / d X1'.",
            {(): ctr.power_split().c1},
            examples=(
                "The dashpot's 2 beta1 omega1:\n"
                "\n"
                ">>> from beltmdsm.generated import contraction\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> round(float(contraction.difference_damping(**BASE)), 4)\n"
                "0.2"
            ),
        ),
    )
    return ModuleSpec(
        "contraction",
        """The energy of the difference of two tangential motions under one normal motion.

derive/contraction.py proves with SymPy that it never rises while the contact cannot
pull; these functions let a simulation show it
(beltmdsm/paper_reports/contraction_evidence.py).
""",
        functions,
    )
