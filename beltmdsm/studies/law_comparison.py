"""Friction that falls with speed: the research answer of issue 19, item 8.

With Stribeck friction, ``mu(Vr) = mu_k + (mu_s - mu_k) exp(-|Vr|/v_s)``, beside Coulomb's,
unforced and at the base excitation, under both tension laws (``allowed``: Eq. (1) as
printed, the contact can pull; ``clipped``: ``max(F, 0)``), this module computes

(a) where steady sliding is unstable (`steady_sliding`): the closed form
    `beltmdsm.generated.unforced.critical_belt_speed` (SymPy's root of the tangential damping
    ``2 beta1 omega1 + g dmu/d|Vr|`` of the linearisation at ``|Vr| = Vb``) beside the
    sign change of the largest real part of `beltmdsm.generated.unforced.eigenvalues`, and the
    eigenvalues of the whole Jacobian against those of its tangential and normal blocks
    (the normal coupling does not move them: the normal equation is free of the
    tangential state, ``one_way_coupling`` of `beltmdsm.generated.capabilities`);
(b) where the ``T``-periodic forced response is unstable (`forced_stability`: the Floquet
    band of `beltmdsm.continuation.band.floquet_band` over ``Vb``, its labelled edges and the
    growth rate ``log max|mu| / T`` at every evaluated value);
(c) where runs from rest show the ``omega1`` vibration (`runs_from_rest`: the
    ``omega1_peak_present`` of `beltmdsm.simulation.simulate`'s summaries on a grid);
(d) the answer (`answer`): whether a self-excited vibration exists without tension once
    friction falls with speed, and where the excitation stabilises or destabilises
    steady sliding (the question of Thomsen and of Michaux et al. that the paper's
    introduction cites);
(e) the growth rates of (a) and (b) against ``Vb`` for the figure of
    notebooks/stribeck_research.ipynb.

`compare` does all of it for the laws of `LAWS` and both tension laws, timing each
expensive call; docs/stribeck.md reports the numbers. No physics is typed here: every
formula comes from generated/ (tests/beltmdsm/test_physics_in_derive_only.py), and the
tests (tests/beltmdsm/studies/test_law_comparison.py) check each reported number against
an independent reference.
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from beltmdsm.generated import unforced

from ..continuation.band import Band, floquet_band
from ..intervals import clip, difference, format_intervals, runs, union
from ..model import Model, as_model, initial_state
from ..periodic.floquet import PERTURBATION
from ..periodic.periodmap import engine_of
from ..settings import SolverSettings
from ..simulation import simulate

__all__ = [
    "Law",
    "LAWS",
    "TENSIONS",
    "VB_RANGE",
    "STARTS",
    "FORCED_STARTS",
    "RUN_SETTINGS",
    "SteadySliding",
    "ForcedStability",
    "RunScan",
    "Answer",
    "LawComparison",
    "steady_sliding",
    "forced_stability",
    "runs_from_rest",
    "answer",
    "compare",
]


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
#: Eq. (9) at rest with ``X1`` moved by `PERTURBATION` (the exact equilibrium is left only
#: by rounding), ``"released"`` at rest with ``X1 = 0`` (the spring relaxed: a large
#: disturbance, which finds a stick-slip cycle where it coexists with stable sliding).
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


# --------------------------------------------------------------------------- (a)


@dataclass(frozen=True)
class SteadySliding:
    """Where steady sliding (the unforced equilibrium, Eq. 9) is unstable (`steady_sliding`).

    The linearisation at ``Fn = g > 0`` is the same under both tension laws
    (docs/modelling.md#tension), so this has no tension law.

    Attributes
    ----------
    law : Law
    critical_speed : float
        `beltmdsm.generated.unforced.critical_belt_speed`: steady sliding is unstable for
        ``Vb`` below it; NaN where no belt speed is (Coulomb's law, ``mu_k >= mu_s``, or a
        fall too weak to beat ``2 beta1 omega1`` even at ``Vb = 0``).
    unstable : list of (lo, hi)
        ``[(0, critical_speed)]``, or empty.
    eigenvalue_speed : float
        Where the largest real part of `beltmdsm.generated.unforced.eigenvalues` changes sign in
        ``Vb`` (Brent's method from the grid's sign change); NaN without a sign change.
    vb : ndarray
        The grid [m/s].
    growth_rate : ndarray
        The largest real part of the eigenvalues on the grid [1/s].
    damping : ndarray
        The tangential damping of the linearisation, minus the ``(X1', X1')`` entry of
        `beltmdsm.generated.unforced.jacobian_at_equilibrium` (``2 beta1 omega1 + g dmu/d|Vr|`` at
        ``|Vr| = Vb``) [1/s].
    block_gap : float
        The largest distance between the eigenvalues of the whole Jacobian and those of
        its tangential and normal 2 x 2 blocks over the grid (``numpy.linalg.eigvals``):
        rounding, because the normal coupling does not change them.
    closed_form_gap : float
        The largest distance between `beltmdsm.generated.unforced.eigenvalues` and
        ``numpy.linalg.eigvals`` of the Jacobian over the grid.
    wall_s : float
    """

    law: Law
    critical_speed: float
    unstable: list[tuple[float, float]]
    eigenvalue_speed: float
    vb: NDArray[np.float64] = field(repr=False)
    growth_rate: NDArray[np.float64] = field(repr=False)
    damping: NDArray[np.float64] = field(repr=False)
    block_gap: float
    closed_form_gap: float
    wall_s: float

    def as_dict(self) -> dict:
        """For JSON: the numbers, the arrays as lists."""
        return {
            "law": self.law.name,
            "critical_speed": _finite_or_none(self.critical_speed),
            "unstable": [list(r) for r in self.unstable],
            "eigenvalue_speed": _finite_or_none(self.eigenvalue_speed),
            "block_gap": self.block_gap,
            "closed_form_gap": self.closed_form_gap,
            "wall_s": self.wall_s,
        }


def _finite_or_none(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


def _largest_real_part(model: Model, vb: ArrayLike) -> NDArray[np.float64]:
    args = model.arguments(unforced.eigenvalues)
    lam = unforced.eigenvalues(**{**args, "Vb": np.asarray(vb, dtype=float)})
    return np.max(np.real(lam), axis=-1)


def steady_sliding(
    law: Law,
    model: Model | Mapping[str, Any] | None = None,
    *,
    vb: ArrayLike | None = None,
) -> SteadySliding:
    """Where steady sliding is unstable, unforced: closed form and eigenvalues (item 8a).

    Parameters
    ----------
    law : Law
    model : Model or dict, optional
        The other parameters (default: the base set); the excitation does not enter.
    vb : array_like, optional
        The grid of belt speeds (default 600 values over `VB_RANGE`).

    Returns
    -------
    SteadySliding
    """
    start = time.perf_counter()
    m = law.model(model)
    vb = np.linspace(*VB_RANGE, 600) if vb is None else np.asarray(vb, dtype=float)
    vc = float(unforced.critical_belt_speed(**m.arguments(unforced.critical_belt_speed)))
    if math.isnan(vc):
        unstable = []
    else:
        unstable = [(0.0, vc)]
    growth = _largest_real_part(m, vb)
    # the sign change of the eigenvalues' largest real part, refined by Brent's method
    changes = np.flatnonzero(np.sign(growth[:-1]) * np.sign(growth[1:]) < 0)
    speed = math.nan
    if changes.size:
        i = int(changes[0])
        speed = float(
            brentq(
                lambda v: float(_largest_real_part(m, v)), vb[i], vb[i + 1], xtol=1e-14, rtol=1e-15
            )
        )
    args = m.arguments(unforced.jacobian_at_equilibrium)
    J = np.asarray(unforced.jacobian_at_equilibrium(**{**args, "Vb": vb}), dtype=float)
    damping = -J[:, 1, 1]
    full = np.sort_complex(np.linalg.eigvals(J))
    blocks = np.sort_complex(
        np.concatenate([np.linalg.eigvals(J[:, :2, :2]), np.linalg.eigvals(J[:, 2:, 2:])], axis=1)
    )
    closed = unforced.eigenvalues(**{**m.arguments(unforced.eigenvalues), "Vb": vb})
    closed = np.sort_complex(np.asarray(closed, dtype=complex))
    return SteadySliding(
        law=law,
        critical_speed=vc,
        unstable=unstable,
        eigenvalue_speed=speed,
        vb=vb,
        growth_rate=growth,
        damping=damping,
        block_gap=float(np.max(np.abs(full - blocks))),
        closed_form_gap=float(np.max(np.abs(full - closed))),
        wall_s=time.perf_counter() - start,
    )


# --------------------------------------------------------------------------- (b)


@dataclass(frozen=True)
class ForcedStability:
    """Where the ``T``-periodic forced response is unstable, by Floquet (item 8b).

    Attributes
    ----------
    law : Law
    tension : str
    band : Band
        `beltmdsm.continuation.band.floquet_band` over ``Vb``.
    engine : str
        The Floquet path the law takes (``"closed_form"`` or ``"general"``).
    vb, growth_rate : ndarray
        Every value the band evaluated, ascending, and the growth rate
        ``log max|mu| / T`` there [1/s] (NaN where the response grazes).
    n_reversals : ndarray of int
        Reversals per period of the response at each value.
    wall_s : float
        The band's wall time [s].
    """

    law: Law
    tension: str
    band: Band = field(repr=False)
    engine: str
    vb: NDArray[np.float64] = field(repr=False)
    growth_rate: NDArray[np.float64] = field(repr=False)
    n_reversals: NDArray[np.int64] = field(repr=False)
    wall_s: float

    @property
    def unstable(self) -> list[tuple[float, float]]:
        """The band's unstable ranges (unstable, or no periodic response found)."""
        return [(float(lo), float(hi)) for lo, hi in self.band.unstable]

    @property
    def edges(self) -> list[tuple[float, str]]:
        """``(value, kind)`` of each edge of the band."""
        return [(e.value, e.kind) for e in self.band.edges]

    def growth_at(self, vb: float) -> float:
        """The growth rate at an evaluated value (within 1e-9); NaN if none was evaluated."""
        i = int(np.argmin(np.abs(self.vb - vb)))
        return float(self.growth_rate[i]) if abs(self.vb[i] - vb) < 1e-9 else math.nan

    def as_dict(self) -> dict:
        """For JSON: the band's ranges and edges, the engine and the wall time."""
        return {
            "law": self.law.name,
            "tension": self.tension,
            "engine": self.engine,
            "unstable": [list(r) for r in self.unstable],
            "edges": [{"value": v, "kind": k} for v, k in self.edges],
            "no_periodic_response": [list(r) for r in self.band.no_periodic_response],
            "failed": [f.value for f in self.band.failed],
            "wall_s": self.wall_s,
        }


def forced_stability(
    law: Law,
    tension: str,
    model: Model | Mapping[str, Any] | None = None,
    *,
    lo: float = VB_RANGE[0],
    hi: float = VB_RANGE[1],
    points: int = 49,
    tol: float = 1e-3,
) -> ForcedStability:
    """The Floquet band of the forced response over ``Vb`` (item 8b).

    Parameters
    ----------
    law : Law
    tension : {"allowed", "clipped"}
    model : Model or dict, optional
        The other parameters (default: the base set, with its excitation).
    lo, hi : float
        The range of ``Vb`` [m/s].
    points, tol
        Of `beltmdsm.continuation.band.floquet_band`: grid values, and the edges' tolerance.

    Returns
    -------
    ForcedStability
    """
    m = law.model(model, tension=tension)
    start = time.perf_counter()
    band = floquet_band("Vb", lo, hi, m, points=points, tol=tol)
    wall = time.perf_counter() - start
    rows = sorted(band.grid, key=lambda r: r.value)
    return ForcedStability(
        law=law,
        tension=tension,
        band=band,
        engine=engine_of(m),
        vb=np.array([r.value for r in rows]),
        growth_rate=np.array([r.growth_rate for r in rows]),
        n_reversals=np.array([r.n_reversals for r in rows], dtype=np.int64),
        wall_s=wall,
    )


# --------------------------------------------------------------------------- (c)


@dataclass(frozen=True)
class RunScan:
    """Runs on a grid of ``Vb`` and where they show the ``omega1`` vibration (item 8c).

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
    """Runs of Eq. (4) on a grid of ``Vb``, serially, and their ``omega1`` peak (item 8c).

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


# --------------------------------------------------------------------------- (d)


@dataclass(frozen=True)
class Answer:
    """Steady sliding unforced against the forced response, for one law and tension law.

    Attributes
    ----------
    law : Law
    tension : str
    unforced_unstable : list of (lo, hi)
        Where steady sliding is unstable without excitation (`SteadySliding.unstable`),
        up to the top of the range studied.
    forced_unstable : list of (lo, hi)
        Where the forced periodic response is unstable (`ForcedStability.unstable`).
    stabilised : list of (lo, hi)
        Unstable unforced, stable forced: where the excitation stabilises sliding.
    destabilised : list of (lo, hi)
        Stable unforced, unstable forced: where it destabilises it.
    unforced_vibration : list of (lo, hi)
        Where an unforced run (any start) shows the ``omega1`` vibration.
    forced_vibration : list of (lo, hi)
        Where a forced run (from rest, or from the unforced vibration) shows it.
    quenched : list of (lo, hi)
        Where the unforced run from ``"released"`` shows the vibration and the forced run
        started on it does not: the excitation quenches it (grid runs).
    vibration_without_tension : bool
        Whether an unforced run shows the vibration while its normal force never turned
        negative: a self-excited vibration that needs no pulling contact.
    """

    law: Law
    tension: str
    unforced_unstable: list[tuple[float, float]]
    forced_unstable: list[tuple[float, float]]
    stabilised: list[tuple[float, float]]
    destabilised: list[tuple[float, float]]
    unforced_vibration: list[tuple[float, float]]
    forced_vibration: list[tuple[float, float]]
    quenched: list[tuple[float, float]]
    vibration_without_tension: bool

    def as_dict(self) -> dict:
        """For JSON: the ranges as lists."""
        out: dict[str, Any] = {"law": self.law.name, "tension": self.tension}
        for key in (
            "unforced_unstable",
            "forced_unstable",
            "stabilised",
            "destabilised",
            "unforced_vibration",
            "forced_vibration",
            "quenched",
        ):
            out[key] = [list(r) for r in getattr(self, key)]
        out["vibration_without_tension"] = self.vibration_without_tension
        return out


def answer(
    steady: SteadySliding,
    forced: ForcedStability,
    unforced_runs: Sequence[RunScan],
    forced_runs: Sequence[RunScan],
    vb_range: tuple[float, float] = VB_RANGE,
) -> Answer:
    """Item 8d for one law and tension law, from (a), (b) and (c).

    ``unforced_runs`` and ``forced_runs`` are the scans of each start (`STARTS`,
    `FORCED_STARTS`), on one grid.

    The stabilised and destabilised ranges are set differences of the unstable ranges
    within ``vb_range``, where both are computed (`beltmdsm.intervals.difference`:
    pieces of positive length).
    """
    lo, hi = vb_range
    free = clip(steady.unstable, lo, hi)
    band = clip(forced.unstable, lo, hi)
    shows = [s for s in unforced_runs if any(p is True for p in s.present)]
    released = next((s for s in unforced_runs if s.start == "released"), None)
    vibrating = next((s for s in forced_runs if s.start == "vibrating"), None)
    quenched = []
    if released is not None and vibrating is not None:
        if not np.array_equal(released.values, vibrating.values):
            raise ValueError("the released and the vibrating runs must share one grid")
        quenched = runs(
            released.values,
            (released.present == True) & (vibrating.present == False),  # noqa: E712
        )
    without_tension = any(
        bool(np.all(s.min_normal_force[s.present == True] >= 0))  # noqa: E712
        for s in shows
    )
    return Answer(
        law=steady.law,
        tension=forced.tension,
        unforced_unstable=clip(steady.unstable, 0.0, hi),
        forced_unstable=band,
        stabilised=difference(free, band),
        destabilised=difference(band, free),
        unforced_vibration=union(r for s in unforced_runs for r in s.present_ranges),
        forced_vibration=union(r for s in forced_runs for r in s.present_ranges),
        quenched=quenched,
        vibration_without_tension=without_tension,
    )


# --------------------------------------------------------------------------- all


@dataclass(frozen=True)
class LawComparison:
    """Items 8a-8e for every law and tension law (`compare`).

    Attributes
    ----------
    steady : dict of str to SteadySliding
        By the key of the law (`LAWS`).
    forced : dict of (str, str) to ForcedStability
        By law and tension law.
    forced_runs : dict of (str, str, str) to RunScan
        By law, tension law and start (`FORCED_STARTS`).
    unforced_runs : dict of (str, str, str) to RunScan
        By law, tension law and start (`STARTS`).
    answers : dict of (str, str) to Answer
    wall_s : dict of str to float
        The wall time of each part: ``steady``, ``floquet``, ``forced_runs``,
        ``unforced_runs``.
    """

    steady: dict[str, SteadySliding]
    forced: dict[tuple[str, str], ForcedStability]
    forced_runs: dict[tuple[str, str, str], RunScan]
    unforced_runs: dict[tuple[str, str, str], RunScan]
    answers: dict[tuple[str, str], Answer]
    wall_s: dict[str, float]

    def table(self, law: str, digits: int = 3) -> str:
        """A Markdown table of one law: a row per tension law (docs/stribeck.md)."""
        fmt = f".{digits}f"
        head = (
            "| tension | steady sliding unstable (unforced) | Floquet unstable (forced) | "
            "edges | omega1 peak, unforced runs | omega1 peak, forced runs | "
            "stabilised by the excitation | destabilised | vibration quenched |\n"
            "|---|---|---|---|---|---|---|---|---|"
        )
        lines = [head]
        for tension in [t for t in TENSIONS if (law, t) in self.answers]:
            a, f = self.answers[(law, tension)], self.forced[(law, tension)]
            edges = ", ".join(f"{v:{fmt}} {k}" for v, k in f.edges) or "none"
            lines.append(
                f"| {tension} | {format_intervals(a.unforced_unstable, fmt)} | "
                f"{format_intervals(a.forced_unstable, fmt)} | {edges} | "
                f"{format_intervals(a.unforced_vibration, '.2f')} | "
                f"{format_intervals(a.forced_vibration, '.2f')} | "
                f"{format_intervals(a.stabilised, fmt)} | "
                f"{format_intervals(a.destabilised, fmt)} | "
                f"{format_intervals(a.quenched, '.2f')} |"
            )
        return "\n".join(lines)

    def as_dict(self) -> dict:
        """For JSON: every part's ``as_dict``, keys joined by ``/``."""
        return {
            "steady": {k: v.as_dict() for k, v in self.steady.items()},
            "forced": {"/".join(k): v.as_dict() for k, v in self.forced.items()},
            "forced_runs": {"/".join(k): v.as_dict() for k, v in self.forced_runs.items()},
            "unforced_runs": {"/".join(k): v.as_dict() for k, v in self.unforced_runs.items()},
            "answers": {"/".join(k): v.as_dict() for k, v in self.answers.items()},
            "wall_s": dict(self.wall_s),
        }


def compare(
    laws: Mapping[str, Law] | None = None,
    model: Model | Mapping[str, Any] | None = None,
    *,
    tensions: Iterable[str] = TENSIONS,
    band_points: int = 49,
    run_values: ArrayLike | None = None,
    settings: SolverSettings | None = None,
    starts: Iterable[str] = STARTS,
    forced_starts: Iterable[str] = FORCED_STARTS,
) -> LawComparison:
    """Items 8a-8d for each law and tension law, each part timed.

    Parameters
    ----------
    laws : dict of str to Law, optional
        Default `LAWS`.
    model : Model or dict, optional
        The other parameters (default: the base set).
    tensions : iterable of str
    band_points : int
        Grid values of each Floquet band (`forced_stability`).
    run_values : array_like, optional
        The belt speeds of the runs (default 0.5 to 12 m/s in steps of 0.5).
    settings : SolverSettings, optional
        Of the runs (default `RUN_SETTINGS`).
    starts : iterable of str
        The starts of the unforced runs (`STARTS`).
    forced_starts : iterable of str
        The starts of the forced runs (`FORCED_STARTS`).

    Returns
    -------
    LawComparison
    """
    laws = dict(LAWS if laws is None else laws)
    tensions, starts, forced_starts = tuple(tensions), tuple(starts), tuple(forced_starts)
    values = np.arange(1, 25) * 0.5 if run_values is None else np.asarray(run_values, float)
    wall = dict.fromkeys(("steady", "floquet", "forced_runs", "unforced_runs"), 0.0)
    steady, forced, forced_runs, unforced_runs, answers = {}, {}, {}, {}, {}
    for key, law in laws.items():
        steady[key] = steady_sliding(law, model)
        wall["steady"] += steady[key].wall_s
        for tension in tensions:
            forced[(key, tension)] = f = forced_stability(law, tension, model, points=band_points)
            wall["floquet"] += f.wall_s
            for start in forced_starts:
                forced_runs[(key, tension, start)] = r = runs_from_rest(
                    law, tension, values, model, start=start, settings=settings
                )
                wall["forced_runs"] += r.wall_s
            for start in starts:
                unforced_runs[(key, tension, start)] = u = runs_from_rest(
                    law, tension, values, model, forced=False, start=start, settings=settings
                )
                wall["unforced_runs"] += u.wall_s
            answers[(key, tension)] = answer(
                steady[key],
                f,
                [unforced_runs[(key, tension, s)] for s in starts],
                [forced_runs[(key, tension, s)] for s in forced_starts],
            )
    return LawComparison(steady, forced, forced_runs, unforced_runs, answers, wall)
