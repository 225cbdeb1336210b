"""The DOP853 tableau of the runtime's integrator: the spec of generated/tableau.py."""

from __future__ import annotations

from ..codegen import ModuleSpec

__all__ = ["build"]


def build() -> ModuleSpec:
    """The Dormand-Prince 8(5,3) tableau of the runtime's integrator, as data.

    Copied from ``scipy.integrate`` when generated/ is written, so that the runtime's
    integrator (beltmdsm/integrate/_dop853.py) starts without importing
    ``scipy.integrate``, which costs half a second of every run's start.
    """
    from scipy.integrate._ivp import dop853_coefficients as c

    def data(a):
        return tuple(data(row) for row in a) if a.ndim > 1 else tuple(float(x) for x in a)

    constants = (
        ("N_STAGES", int(c.N_STAGES), "Stages of a step (the 8th-order solution)."),
        (
            "N_STAGES_EXTENDED",
            int(c.N_STAGES_EXTENDED),
            "Stages with those of the dense output.",
        ),
        ("INTERPOLATOR_POWER", int(c.INTERPOLATOR_POWER), "Rows of a step's dense output."),
        ("A", data(c.A), "The Runge-Kutta matrix, extended stages included."),
        ("B", data(c.B), "The weights of the 8th-order solution."),
        ("C", data(c.C), "The nodes, extended stages included."),
        ("E3", data(c.E3), "The 3rd-order error estimate's weights."),
        ("E5", data(c.E5), "The 5th-order error estimate's weights."),
        ("D", data(c.D), "The dense output's coefficients."),
    )
    return ModuleSpec(
        "tableau",
        """The Dormand-Prince 8(5,3) tableau (Hairer, Norsett and Wanner) of ``scipy.integrate``.

Copied when generated/ is written, so that the runtime's integrator
(beltmdsm/integrate/_dop853.py) starts without importing ``scipy.integrate``.
""",
        (),
        constants,
        mp=False,
    )
