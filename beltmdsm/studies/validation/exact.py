"""The exact coexistence of a case beside the simulated one, and what explains each run.

The runs of a case (`RUNS`) find two attractors at a grid point where the periodic
response is stable and a run from rest or a continued sweep shows the omega1 peak
(`beltmdsm.studies.validation.verdicts.coexistence`, Figs. 2b and 17-21). The exact
counterpart is `beltmdsm.studies.coexistence.coexistence`: every periodic response found
(the ``T``-periodic one and the phase-locked ones of ``k T``), continued in ``Vb`` with
its stable parts and the bifurcations that bound them (docs/modelling.md#bifurcations).

`explain_coexistence` sets the two side by side, point by point: a run that shows the
peak at a simulated coexistence point is *explained* by a computed response when that
response is stable there and the run's steady window spans the response's range of
``X1'`` (`Explanation`, `range_tolerance`). Otherwise it is, by `STATUSES`, *not
settled* (the closest stable response attracts too slowly for a run to have reached
it by its steady window, the rule the runs apply to their own transient), *not locked*
(the nearby seed runs of the exact study do not lock: quasi-periodic motion, or a
longer period than `beltmdsm.analysis.locked.LOCK_LIMIT`), or *unexplained*.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from ...analysis.floquet import NoPeriodicResponse
from ...analysis.locked import minimal_periods
from ...analysis.summary import TRANSIENT_DECAYED
from ...model import Model
from ..coexistence import Coexistence, ResponseBranch
from ..responses import shoot
from .verdicts import Run

__all__ = ["SEED_SOURCES", "STATUSES", "Explanation", "range_tolerance", "explain_coexistence"]

#: The seeds of `beltmdsm.studies.coexistence.coexistence` that stand for each run that
#: can show a second attractor: its runs from rest, and its ladders continued up and
#: down on the period map (a continued sweep's counterpart).
SEED_SOURCES = {"rest": "run from rest", "up": "continued up", "down": "continued down"}
#: What a run at a simulated coexistence point is found to be (module docstring).
STATUSES = ("explained", "not_settled", "not_locked", "unexplained")
Status = Literal["explained", "not_settled", "not_locked", "unexplained"]


@dataclass(frozen=True)
class Explanation:
    """What explains one run at one simulated coexistence point.

    Attributes
    ----------
    Vb : float
        The grid point.
    run : {"rest", "up", "down"}
        The run that shows the omega1 peak there (a key of `RUNS`).
    status : {"explained", "not_settled", "not_locked", "unexplained"}
        `STATUSES`.
    response : str or None
        The computed response the run is on (`beltmdsm.studies.coexistence.ResponseBranch.name`),
        or None: unexplained.
    closest : str or None
        The stable computed response whose range of ``X1'`` is closest to the run's
        (None where none is stable at ``Vb`` besides those that failed to solve).
    deviation : float or None
        The largest difference of the run's and that response's smallest and largest
        ``X1'``, over the response's amplitude (half its range).
    tolerance : float
        `range_tolerance` of the runs.
    reason : str
        Why the run is unexplained ("" where it is explained).
    """

    Vb: float
    run: str
    status: Status
    response: str | None
    closest: str | None
    deviation: float | None
    tolerance: float
    reason: str

    @property
    def explained(self) -> bool:
        """Whether a computed response explains the run."""
        return self.status == "explained"


def range_tolerance(model: Model, dt: float) -> float:
    """How closely a run on a response spans its range of ``X1'`` (relative to the amplitude).

    A run samples ``X1'`` every ``dt``; its extremes miss the response's by the
    distance of the nearest sample to the extreme. For a harmonic of amplitude ``A``
    at the excitation frequency ``Omega`` a sample half a step from the extreme falls
    short by ``A (1 - cos(Omega dt / 2)) <= A (Omega dt)^2 / 8``; the bound is doubled
    for the harmonics of the response (``(Omega dt)^2 / 4``, 1.6e-3 at the base set and
    ``dt = 0.02`` s). The integration error of the runs (``rtol = 1e-7``) and the decay
    of a settled transient are far below it.

    Parameters
    ----------
    model : Model
        Its highest excitation frequency is used (``Omega_t``, ``Omega_n``).
    dt : float
        The runs' sampling step [s].
    """
    p = model.params
    omega = max(p["Omega_t"], p["Omega_n"])
    return float((omega * dt) ** 2 / 4)


def _states_near(branch: ResponseBranch, value: float) -> list[np.ndarray]:
    """Guesses for the stable responses of ``branch`` at ``value``: the phase-0 state
    interpolated between each pair of consecutive stable points that brackets it."""
    points = branch.branch.points
    guesses = []
    for a, b in zip(points[:-1], points[1:]):
        if a.stable and b.stable and min(a.value, b.value) <= value <= max(a.value, b.value):
            w = 0.0 if a.value == b.value else (value - a.value) / (b.value - a.value)
            guesses.append((1 - w) * a.state + w * b.state)
    return guesses


def _stable_at(branch: ResponseBranch, value: float) -> bool:
    return any(s.range[0] <= value <= s.range[1] for s in branch.stable)


def _responses_at(branch: ResponseBranch, model: Model) -> list[tuple[tuple, float, float]]:
    """The stable responses of ``branch`` at ``model``'s ``Vb``: ``(range of X1', max |mu|,
    k T)`` of each.

    Each is solved by Newton's method on the ``k``-fold map from the branch
    interpolated there, and kept where it is stable and of minimal period ``k``.
    """
    k = branch.branch.periods
    out = []
    for guess in _states_near(branch, float(model["Vb"])):
        try:
            pmap, point = shoot(model, k, guess)
        except NoPeriodicResponse:
            continue
        mu = float(
            np.max(
                np.abs(
                    np.concatenate(
                        [np.linalg.eigvals(point.image.jacobian), pmap.fixed_multipliers()]
                    )
                )
            )
        )
        if mu < 1.0 and minimal_periods(point.image, k) == k:
            out.append((point.image.velocity_range(), mu, k * pmap.period))
    return out


def _unlocked_reason(exact: Coexistence, value: float, run: str, seed_step: float) -> str | None:
    """The reason "not locked" where a seed of ``run``'s kind near ``value`` does not lock."""
    near = [
        u
        for u in exact.unlocked
        if abs(u.value - value) <= seed_step * (1 + 1e-9)
        and u.evidence.source.startswith(SEED_SOURCES[run])
    ]
    if not near:
        return None
    u = min(near, key=lambda u: abs(u.value - value))
    e = u.evidence
    shape = "on a closed curve" if e.closed_curve else "not on a closed curve"
    return (
        f"not locked within {e.limit} periods: the seed '{e.source}' at Vb = {u.value:g} "
        f"returns at best to {e.closest_return:.1e} (after {e.closest_periods} periods), "
        f"its samples {shape}, rotation number {e.rotation_number:.3f}"
    )


def explain_coexistence(
    points: Sequence[float],
    found_by: Mapping[float, Sequence[str]],
    runs: Mapping[str, Run],
    vb: Sequence[float],
    exact: Coexistence,
    dt: float,
    window_start: float,
    seed_step: float,
) -> list[Explanation]:
    """Each run at each simulated coexistence point, explained by a computed response or not.

    Parameters
    ----------
    points : sequence of float
        The simulated coexistence points (`beltmdsm.studies.validation.verdicts.Coexistence`).
    found_by : mapping of float to sequence of str
        The runs that show the peak at each point.
    runs : mapping of str to Run
        The runs of the case on the grid ``vb``.
    vb : sequence of float
        The case's grid.
    exact : beltmdsm.studies.coexistence.Coexistence
        The exact coexistence in ``Vb`` over a range that holds ``points``.
    dt : float
        The runs' sampling step [s] (`range_tolerance`).
    window_start : float
        The start of the runs' steady window [s]: a response whose largest multiplier
        ``mu`` (of ``k T``) leaves ``|mu|^(window_start / (k T))`` above
        `beltmdsm.analysis.summary.TRANSIENT_DECAYED` attracts too slowly for a run to
        have settled on it (the rule the runs apply to their own transient).
    seed_step : float
        The spacing of ``exact``'s seeds: a seed this close to a point stands for it.

    Returns
    -------
    list of Explanation
        In the order of ``points``, then of the runs.
    """
    grid = [float(v) for v in vb]
    out = []
    for value in points:
        i = grid.index(float(value))
        model = exact.model.replace(Vb=float(value))
        tolerance = range_tolerance(model, dt)
        stable = [
            (r.name, *at)
            for r in exact.responses
            if _stable_at(r, value)
            for at in _responses_at(r, model)
        ]
        for run in found_by[value]:
            lo, hi = runs[run].velocity_range[i]
            best = None
            for name, (a, b), mu, period in stable:
                deviation = max(abs(lo - a), abs(hi - b)) / (0.5 * (b - a))
                if best is None or deviation < best[1]:
                    best = (name, deviation, mu, period)
            closest, deviation = (best[0], best[1]) if best is not None else (None, None)
            if deviation is not None and deviation <= tolerance:
                out.append(
                    Explanation(value, run, "explained", closest, closest, deviation, tolerance, "")
                )
                continue
            status, reason = "unexplained", _unlocked_reason(exact, value, run, seed_step)
            if reason is not None:
                status = "not_locked"
            elif best is not None and math.log(best[2]) * window_start / best[3] > math.log(
                TRANSIENT_DECAYED
            ):
                status = "not_settled"
                left = best[2] ** (window_start / best[3])
                reason = (
                    f"not settled: the closest stable response, {closest} ({deviation:.1e} of "
                    f"its amplitude off), attracts with |mu| = {best[2]:.4f} per "
                    f"{best[3]:.4g} s, so a run reaches it only to {left:.1e} of its "
                    f"distance by the window's start ({window_start:g} s)"
                )
            elif closest is not None:
                reason = (
                    f"the run's X1' spans [{lo:.4g}, {hi:.4g}] m/s, no stable computed "
                    f"response's (closest: {closest}, {deviation:.1e} of its amplitude off)"
                )
            else:
                reason = "no stable computed response at this Vb"
            out.append(Explanation(value, run, status, None, closest, deviation, tolerance, reason))
    return out
