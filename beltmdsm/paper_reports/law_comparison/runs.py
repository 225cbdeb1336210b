"""Where runs from rest show the ``omega1`` vibration, per friction law (`runs_from_rest`).

The ``omega1_peak_present`` of `beltmdsm.simulation.simulate`'s summaries on a grid of
``Vb``, forced or not, from each start of `STARTS` and `FORCED_STARTS`.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...excitation import initial_state
from ...intervals import runs
from ...model import Model
from ...settings import SolverSettings
from ...simulation import simulate
from ...starts.forced import PERTURBATION
from .laws import FORCED_STARTS, RUN_SETTINGS, STARTS, Law

__all__ = ["RunScan", "runs_from_rest"]


@dataclass(frozen=True)
class RunScan:
    """Runs on a grid of ``Vb`` and where they show the ``omega1`` vibration (part (c)).

    Attributes
    ----------
    law : Law
    tension : str
    forced : bool
        At the base excitation, or without it (``alpha = 0``).
    start : str
        One of `FORCED_STARTS` (forced) or of `STARTS` (unforced).
    values : ndarray
        The belt speeds [m/s].
    present : ndarray of object
        ``omega1_peak_present`` of each run's summary: True, False, or None where the
        run cannot tell (`beltmdsm.run.summary.Summary`; next to the Stribeck
        boundary the free transient decays too slowly for the window to tell,
        `beltmdsm.run.summary.free_decay_rate`).
    peak_omega1 : ndarray
        The amplitude of the ``omega1`` peak of X1' [m/s].
    min_normal_force : ndarray
        The smallest normal force of each run [m/s^2]: negative only where the contact
        pulled.
    regime : ndarray of str
    energy_ok : ndarray of bool
        Whether each run's energy balance closes.
    wall_s : float
        The scan's wall time [s].

    See Also
    --------
    beltmdsm.paper_reports.law_comparison.runs.runs_from_rest : what builds it.

    Examples
    --------
    Built by hand: the peak is present at 1 and 2 m/s, absent at 3, and the run at
    4 m/s cannot tell, so it stays out of the ranges:

    >>> import numpy as np
    >>> from beltmdsm.paper_reports.law_comparison import LAWS
    >>> scan = RunScan(LAWS["coulomb"], "allowed", True, "rest",
    ...                np.array([1.0, 2.0, 3.0, 4.0]),
    ...                np.array([True, True, False, None], dtype=object),
    ...                np.zeros(4), np.full(4, 1.0), np.array(["stick_slip"] * 4),
    ...                np.ones(4, dtype=bool), 0.1)
    >>> scan.present_ranges, scan.unresolved
    ([(1.0, 2.0)], [4.0])
    >>> scan.as_dict()["min_normal_force"], scan.as_dict()["energy_ok"]
    (1.0, True)
    """

    law: Law
    tension: str
    forced: bool
    start: str
    values: NDArray[np.float64] = field(repr=False)
    present: NDArray[np.object_] = field(repr=False)
    peak_omega1: NDArray[np.float64] = field(repr=False)
    min_normal_force: NDArray[np.float64] = field(repr=False)
    regime: NDArray[np.str_] = field(repr=False)
    energy_ok: NDArray[np.bool_] = field(repr=False)
    wall_s: float

    @property
    def present_ranges(self) -> list[tuple[float, float]]:
        """The runs of consecutive grid values where the peak is present (resolved)."""
        return runs(self.values, self.present == True)  # noqa: E712 (None stays out)

    @property
    def unresolved(self) -> list[float]:
        """The values whose run could not tell."""
        return [float(v) for v, p in zip(self.values, self.present) if p is None]

    def as_dict(self) -> dict:
        """For JSON: the ranges, the unresolved values, the wall time."""
        return {
            "law": self.law.name,
            "tension": self.tension,
            "forced": self.forced,
            "start": self.start,
            "present": [list(r) for r in self.present_ranges],
            "unresolved": self.unresolved,
            "min_normal_force": float(np.min(self.min_normal_force)),
            "energy_ok": bool(np.all(self.energy_ok)),
            "wall_s": self.wall_s,
        }


def _start_state(model: Model, start: str, settings: SolverSettings) -> NDArray[np.float64] | None:
    """The initial state of a run (`RunScan.start`)."""
    if start == "rest":
        return None
    if start == "vibrating":
        free = model.replace(alpha=0.0)
        end = simulate(free, settings=settings, y0=_start_state(free, "released", settings))
        return np.array(end.summary.final_state, dtype=float)
    y0 = initial_state(model)
    if start == "perturbed":
        y0[0] += PERTURBATION
    else:  # released
        y0[0] = 0.0
    return y0


def runs_from_rest(
    law: Law,
    tension: str,
    values: ArrayLike,
    model: Model | Mapping[str, Any] | None = None,
    *,
    forced: bool = True,
    start: str | None = None,
    settings: SolverSettings | None = None,
) -> RunScan:
    """Runs of Eq. (4) on a grid of ``Vb``, serially, and their ``omega1`` peak (part (c)).

    Parameters
    ----------
    law : Law
    tension : {"allowed", "clipped"}
    values : array_like
        The belt speeds [m/s].
    model : Model or dict, optional
        The other parameters (default: the base set).
    forced : bool
        False: without excitation (``alpha = 0``).
    start : str, optional
        One of `FORCED_STARTS` (forced; default ``"rest"``) or of `STARTS` (unforced;
        default ``"perturbed"``). A run from ``"vibrating"`` costs an unforced run more.
    settings : SolverSettings, optional
        Default `RUN_SETTINGS`.

    Returns
    -------
    RunScan

    Raises
    ------
    ValueError
        for a start that is not one of the kind of run's starts.

    See Also
    --------
    beltmdsm.simulation.simulate : each run.
    beltmdsm.paper_reports.law_comparison.laws.STARTS : where unforced runs start.

    Examples
    --------
    Without excitation, Stribeck's law B sticks and slips at 2 m/s (steady sliding is
    unstable there) and slides at 6 m/s; 100 s runs:

    >>> from beltmdsm import SolverSettings
    >>> from beltmdsm.paper_reports.law_comparison import LAWS
    >>> scan = runs_from_rest(LAWS["stribeck_B"], "allowed", [2.0, 6.0], forced=False,
    ...                       settings=SolverSettings(t_end=100.0))
    >>> scan.start, scan.regime.tolist(), scan.present_ranges
    ('perturbed', ['stick_slip', 'continuous_sliding'], [(2.0, 2.0)])
    >>> runs_from_rest(LAWS["coulomb"], "allowed", [2.0], start="released")
    Traceback (most recent call last):
    ValueError: a forced run starts from one of ('rest', 'vibrating'); got start='released'
    """
    start = start or ("rest" if forced else "perturbed")
    if forced and start not in FORCED_STARTS:
        raise ValueError(f"a forced run starts from one of {FORCED_STARTS}; got start={start!r}")
    if not forced and start not in STARTS:
        raise ValueError(f"an unforced run starts from one of {STARTS}; got start={start!r}")
    settings = settings or RUN_SETTINGS
    values = np.asarray(values, dtype=float)
    began = time.perf_counter()
    rows = []
    for vb in values:
        m = law.model(model, Vb=float(vb), tension=tension, **({} if forced else {"alpha": 0.0}))
        rows.append(simulate(m, settings=settings, y0=_start_state(m, start, settings)).summary)
    return RunScan(
        law=law,
        tension=tension,
        forced=forced,
        start=start,
        values=values,
        present=np.array([s.omega1_peak_present for s in rows], dtype=object),
        peak_omega1=np.array([s.peak_omega1 for s in rows]),
        min_normal_force=np.array([s.min_normal_force for s in rows]),
        regime=np.array([s.regime for s in rows]),
        energy_ok=np.array([s.energy_ok for s in rows], dtype=bool),
        wall_s=time.perf_counter() - began,
    )
