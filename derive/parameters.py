"""The model's own parameters: every parameter that all laws share, once, with unit and base value.

Base values are those of the paper's Fig. 2 (Sect. 3); ``Vb = 4`` is the belt speed
of Fig. 3. Names follow the paper in ASCII: ``beta2`` and ``omega2`` are the starred
Hertz-Damp quantities ``beta2*`` and ``omega2*`` of Eq. (4) (for the linear
Kelvin-Voigt contact of Fig. 16 they are the ordinary damping ratio and natural
frequency of the normal direction). ``Omega`` is the excitation frequency
``Omega_e``.

The excitation has its own amplitude, frequency and phase in each direction
(Figs. 14-15). ``alpha_t, Omega_t, phase_t`` (tangential) and ``alpha_n, Omega_n,
phase_n`` (normal) default to ``alpha``, ``Omega`` and 0, which gives Eq. (4)
exactly.

The friction and contact laws bring parameters of their own (``mu_k``, ``v_s`` of
Stribeck's law, ``n_h`` of Hunt-Crossley's): they are entries of the laws in
`beltmdsm.derive.laws`, and `beltmdsm.derive.laws.parameter_table` appends them to
`MODEL`. The units of ``omega2`` and ``beta2`` depend on the contact law (`derived_unit`):
`beltmdsm.derive.units` derives them from its force.

This module is plain Python (no SymPy): the code generator copies the full table into
``generated/parameters.py`` so the runtime layer can read it without SymPy.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Parameter", "MODEL", "DOMAINS", "base_values"]

#: The domains of the parameter table, each as ``(lower bound, whether the bound itself
#: is excluded, the text of a failure)``: the one rule that the generated argument
#: checks and the runtime's `Model` both apply (``beltmdsm.generated.parameters.within``).
DOMAINS: dict[str, tuple[float, bool, str]] = {
    "positive": (0.0, True, "> 0"),
    "nonnegative": (0.0, False, ">= 0"),
    "real": (-math.inf, True, "real"),
}


@dataclass(frozen=True)
class Parameter:
    """One model parameter.

    Attributes
    ----------
    name : str
        ASCII name used as keyword argument everywhere.
    unit : str
        SI unit. For a parameter with `derived_unit` the unit under the linear
        contact law of Fig. 16; `beltmdsm.derive.units` derives it for each contact law.
    base : float or None
        Value of the paper's base set (Fig. 2); ``None`` for an optional parameter
        that defaults to another one (see `default_from`).
    domain : {"positive", "nonnegative", "real"}
        Admissible values; generated functions raise ``ValueError`` outside it.
    description : str
        One line, citing the paper.
    default_from : str or None
        For the per-direction excitation: the parameter whose value is taken when
        this one is not given.
    law : (str, str) or None
        ``(option, choice)`` of the law that owns the parameter (``("friction",
        "stribeck")``); None for the model's own parameters.
    derived_unit : bool
        The unit depends on the contact law (its stiffness and damping).
    """

    name: str
    unit: str
    base: float | None
    domain: str
    description: str
    default_from: str | None = None
    law: tuple[str, str] | None = None
    derived_unit: bool = False


MODEL: tuple[Parameter, ...] = (
    Parameter(
        "beta1", "1", 0.1, "nonnegative", "tangential damping ratio C1/(2 M omega1), Eq. (4)"
    ),
    Parameter(
        "omega1", "rad/s", 1.0, "positive", "tangential natural frequency sqrt(K1/M), Eq. (4)"
    ),
    Parameter(
        "beta2",
        "1",
        0.15,
        "nonnegative",
        "contact damping: beta2* = C2/(2 M omega2*) of Hertz-Damp, Eq. (4)",
        derived_unit=True,
    ),
    Parameter(
        "omega2",
        "rad/s",
        0.5,
        "positive",
        "contact stiffness: omega2* = sqrt(K2/M) of Hertz-Damp, Eq. (4)",
        derived_unit=True,
    ),
    Parameter(
        "alpha",
        "m",
        2.0,
        "nonnegative",
        "excitation amplitude: force per mass alpha Omega^2, Eq. (4)",
    ),
    Parameter("Omega", "rad/s", 4.0, "nonnegative", "excitation frequency Omega_e, Eq. (4)"),
    Parameter(
        "mu_s",
        "1",
        0.4,
        "nonnegative",
        "static friction coefficient: Coulomb's of Eq. (3), the bound of stick",
    ),
    Parameter("g", "m/s^2", 9.81, "positive", "gravity pressing the mass on the belt, Eq. (4)"),
    Parameter("Vb", "m/s", 4.0, "nonnegative", "belt speed (base value: Fig. 3)"),
    Parameter(
        "alpha_t",
        "m",
        None,
        "nonnegative",
        "tangential excitation amplitude (Figs. 14-15)",
        "alpha",
    ),
    Parameter(
        "Omega_t",
        "rad/s",
        None,
        "nonnegative",
        "tangential excitation frequency (Fig. 14b)",
        "Omega",
    ),
    Parameter("phase_t", "rad", 0.0, "real", "tangential excitation phase (Fig. 15: pi/2)"),
    Parameter(
        "alpha_n", "m", None, "nonnegative", "normal excitation amplitude (Figs. 14-15)", "alpha"
    ),
    Parameter(
        "Omega_n", "rad/s", None, "nonnegative", "normal excitation frequency (Fig. 14b)", "Omega"
    ),
    Parameter("phase_n", "rad", 0.0, "real", "normal excitation phase"),
    Parameter(
        "Vhat", "m/s", None, "positive", "velocity amplitude in the effective friction, Eq. (23)"
    ),
)


def base_values(table: tuple[Parameter, ...]) -> dict[str, float]:
    """The base set of ``table``: every parameter with a value of its own.

    Per-direction excitation parameters (they default to ``alpha``, ``Omega``) and
    the phases (optional, 0) are left out, so that the base set is Eq. (4) itself.
    """
    return {
        p.name: p.base
        for p in table
        if p.base is not None and p.default_from is None and not p.name.startswith("phase")
    }
