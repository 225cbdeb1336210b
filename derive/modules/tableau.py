"""The DOP853 tableau of the runtime's integrator: the spec of generated/tableau.py."""

from __future__ import annotations

from .. import dop853
from ..codegen import ModuleSpec

__all__ = ["build"]


def build() -> ModuleSpec:
    """The Dormand-Prince 8(5,3) tableau of the runtime's integrator, as data.

    Hairer's published constants (`beltmdsm.derive.dop853`), written into generated/ so that
    the runtime's integrator (beltmdsm/integrate/_dop853.py) starts without importing
    ``scipy.integrate``, which costs half a second of every run's start.
    """
    constants = (
        ("N_STAGES", dop853.N_STAGES, "Stages of a step (the 8th-order solution)."),
        (
            "N_STAGES_EXTENDED",
            dop853.N_STAGES_EXTENDED,
            "Stages with those of the dense output.",
        ),
        ("INTERPOLATOR_POWER", dop853.INTERPOLATOR_POWER, "Rows of a step's dense output."),
        ("A", dop853.A, "The Runge-Kutta matrix, extended stages included."),
        ("B", dop853.B, "The weights of the 8th-order solution."),
        ("C", dop853.C, "The nodes, extended stages included."),
        ("E3", dop853.E3, "The 3rd-order error estimate's weights."),
        ("E5", dop853.E5, "The 5th-order error estimate's weights."),
        ("D", dop853.D, "The dense output's coefficients."),
    )
    return ModuleSpec(
        "tableau",
        """The Dormand-Prince 8(5,3) tableau (Hairer, Norsett and Wanner), as dop853.f prints it.

Typed in derive/dop853.py and written here, so that the runtime's integrator
(beltmdsm/integrate/_dop853.py) starts without importing ``scipy.integrate``.
""",
        (),
        constants,
        mp=False,
    )
