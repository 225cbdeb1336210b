"""The friction laws compared, the tension laws, the belt speeds and the runs' starts.

The data of the comparison (`beltmdsm.paper_reports.law_comparison`): `Law` (a friction
law with its parameters), `LAWS`, `TENSIONS`, `VB_RANGE`, `STARTS`, `FORCED_STARTS`
and `RUN_SETTINGS`.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ...model import Model, as_model
from ...settings import SolverSettings

__all__ = ["Law", "LAWS", "TENSIONS", "VB_RANGE", "STARTS", "FORCED_STARTS", "RUN_SETTINGS"]


@dataclass(frozen=True)
class Law:
    """A friction law with its parameters: one curve of the comparison.

    Attributes
    ----------
    name : str
        The label of tables and figures.
    friction : {"coulomb", "stribeck"}
    mu_k, v_s : float or None
        Stribeck's kinetic coefficient and velocity (None for Coulomb).

    See Also
    --------
    beltmdsm.paper_reports.law_comparison.laws.LAWS : the laws compared.
    beltmdsm.paper_reports.law_comparison.comparison.compare : the comparison.

    Examples
    --------
    A law gives its model, with the other parameters passed on:

    >>> law = Law("stribeck B", "stribeck", mu_k=0.1, v_s=3.0)
    >>> law.label()
    'stribeck B (mu_k = 0.1, v_s = 3 m/s)'
    >>> law.model(Vb=2.0)
    Model(Vb=2.0, mu_k=0.1, v_s=3.0, friction='stribeck')
    >>> Law("coulomb").model().friction
    'coulomb'
    """

    name: str
    friction: str = "coulomb"
    mu_k: float | None = None
    v_s: float | None = None

    def model(self, model: Model | Mapping[str, Any] | None = None, **kw: Any) -> Model:
        """The `Model` of this law: ``model`` (default the base set) with the law's
        options and parameters, and ``kw`` (``Vb=``, ``tension=``, ``alpha=``)."""
        law: dict[str, Any] = {"friction": self.friction}
        if self.friction == "stribeck":
            law.update(mu_k=self.mu_k, v_s=self.v_s)
        return as_model(model, **law, **kw)

    def label(self) -> str:
        """``"coulomb"`` or ``"stribeck (mu_k = 0.25, v_s = 1)"``."""
        if self.friction == "coulomb":
            return self.name
        return f"{self.name} (mu_k = {self.mu_k:g}, v_s = {self.v_s:g} m/s)"


#: The laws compared (issue 19, item 8): Coulomb's (Eq. 3), the issue's Stribeck set
#: (``mu_k = 0.25``, ``v_s = 1``) and a second one with a steeper and wider fall
#: (``mu_k = 0.1``, ``v_s = 3``: steady sliding unstable up to 4.77 m/s, beyond the
#: lower edge of Coulomb's Floquet band and the clipped response's grazing point),
#: all at the base set (``mu_s = 0.4``).
LAWS: dict[str, Law] = {
    "coulomb": Law("coulomb"),
    "stribeck_A": Law("stribeck A", "stribeck", mu_k=0.25, v_s=1.0),
    "stribeck_B": Law("stribeck B", "stribeck", mu_k=0.1, v_s=3.0),
}
#: The tension laws (docs/modelling.md#tension).
TENSIONS: tuple[str, ...] = ("allowed", "clipped")
#: The belt speeds studied [m/s].
VB_RANGE: tuple[float, float] = (0.2, 12.0)
#: Where an unforced run starts (`runs_from_rest`): ``"perturbed"`` the equilibrium of
#: Eq. (9) at rest with ``X1`` moved by `beltmdsm.starts.forced.PERTURBATION` (the
#: exact equilibrium is left only by rounding), ``"released"`` at rest with ``X1 = 0``
#: (the spring relaxed: a large disturbance, which finds a stick-slip cycle where it
#: coexists with stable sliding).
STARTS: tuple[str, ...] = ("perturbed", "released")
#: Where a forced run starts (`runs_from_rest`): ``"rest"`` the package's default (the
#: unforced equilibrium at rest, the excitation switched on at t = 0), ``"vibrating"``
#: the final state of the unforced run from ``"released"`` at the same belt speed (on
#: the stick-slip cycle where one exists), the excitation switched on there: whether the
#: excitation quenches a friction-induced vibration that is already there.
FORCED_STARTS: tuple[str, ...] = ("rest", "vibrating")
#: The runs' settings: the fast configuration of the notebooks (DOP853 on the events
#: solver at rtol = atol = 1e-7), 1000 s as in the paper's figures.
RUN_SETTINGS = SolverSettings(rtol=1e-7, atol=1e-7, t_end=1000.0)
