"""The exact coexistence of a case beside the simulated one, and what explains each run.

The runs of a case (`RUNS`) find two attractors at a grid point where the periodic
response is stable and a run from rest or a continued sweep shows the omega1 peak
(`beltmdsm.paper_reports.validation.verdicts.coexistence`, Figs. 2b and 17-21). The exact
counterpart is `beltmdsm.multistability.coexistence.coexistence`: every periodic response found
(the ``T``-periodic one and the phase-locked ones of ``k T``), continued in ``Vb`` with
its stable parts and the bifurcations that bound them (docs/modelling.md#bifurcations).

`explain_coexistence` sets the two side by side, point by point: a run that shows the
peak at a simulated coexistence point is *explained* by a computed response when that
response is stable there and the run's steady window spans the response's range of
``X1'`` (`Explanation`, `range_tolerance`). Otherwise it is, by `STATUSES`, *not
settled* (the closest stable response attracts too slowly for a run to have reached
it by its steady window, the rule the runs apply to their own transient), *not locked*
(the nearby seed runs of the exact study do not lock: quasi-periodic motion, or a
longer period than `beltmdsm.periodic.locked.LOCK_LIMIT`), or *unexplained*. A run
from rest that no computed response explains is run again with its settings and its
stroboscope examined (`beltmdsm.starts.forced.run_stroboscope`): where it locks,
its response is computed by shooting and compared like the others (a response the
exact study's seeds did not reach). Where it does not lock within the limit, the run is
classified (`beltmdsm.attractors.classification.classify`: its Lyapunov spectrum and its
return after any number of periods) and a long lock it finds (59T at the base set's
Vb = 3.5) is computed and compared the same way; otherwise it is *not locked* with the
classification's evidence (quasi-periodic, chaotic, or what could not be told). The
continued sweeps cannot be rerun at one point: for them the seed of the exact study
that stands for them (its ladders) is classified from its last state the same way.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from ...attractors.classification import classify
from ...errors import NoPeriodicResponse
from ...model import Model
from ...multistability.coexistence import Coexistence, ResponseBranch
from ...periodic.engines import period_map
from ...periodic.locked import LOCK_LIMIT, NotLocked, minimal_periods
from ...run.summary import TRANSIENT_DECAYED
from ...settings import SolverSettings
from ...starts.forced import run_stroboscope, shoot
from .verdicts import Run

__all__ = ["SEED_SOURCES", "STATUSES", "Explanation", "range_tolerance", "explain_coexistence"]

#: The seeds of `beltmdsm.multistability.coexistence.coexistence` that stand for each run that
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
        The computed response the run is on
        (`beltmdsm.multistability.coexistence.ResponseBranch.name`), or None: unexplained.
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

    See Also
    --------
    beltmdsm.paper_reports.validation.exact.explain_coexistence : what builds them.

    Examples
    --------
    Built by hand:

    >>> e = Explanation(5.4, "up", "explained", "T", "T", 1e-3, 1.6e-3, "")
    >>> e.explained, Explanation(5.4, "rest", "unexplained", None, None, None, 1.6e-3,
    ...                          "no stable computed response at this Vb").explained
    (True, False)
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

    Returns
    -------
    float
        ``(Omega dt)^2 / 4``

    See Also
    --------
    beltmdsm.paper_reports.validation.exact.explain_coexistence : where it is used.

    Examples
    --------
    At the base set (``Omega = 4`` rad/s) and ``dt = 0.02`` s, ``(0.08)^2 / 4``:

    >>> from beltmdsm import Model
    >>> round(range_tolerance(Model(), 0.02), 10)
    0.0016
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
        mu = _largest_multiplier(pmap, point)
        if mu < 1.0 and minimal_periods(point.image, k) == k:
            out.append((point.image.velocity_range(), mu, k * pmap.period))
    return out


def _not_locked_text(evidence: NotLocked, where: str) -> str:
    e = evidence
    shape = "on a closed curve" if e.closed_curve else "not on a closed curve"
    return (
        f"not locked within {e.limit} periods: {where} returns at best to "
        f"{e.closest_return:.1e} (after {e.closest_periods} periods), its samples {shape}, "
        f"rotation number {e.rotation_number:.3f}"
    )


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
    return _not_locked_text(u.evidence, f"the seed '{u.evidence.source}' at Vb = {u.value:g}")


def _seed_classified(exact, model, value, run, seed_step, settings):
    """The seed of ``run``'s kind near ``value`` that does not lock, classified from its
    last state at ``value``: as `_classified`, or ``(None, None)`` without such a seed."""
    near = [
        u
        for u in exact.unlocked
        if abs(u.value - value) <= seed_step * (1 + 1e-9)
        and u.evidence.source.startswith(SEED_SOURCES[run])
        and u.evidence.state
    ]
    if not near:
        return None, None
    u = min(near, key=lambda u: abs(u.value - value))
    where = f"the seed '{u.evidence.source}' at Vb = {u.value:g}"
    pmap = period_map(model)
    start = pmap.full_state(pmap.guess(u.evidence.state))
    return _classified(model, start, settings, _not_locked_text(u.evidence, where))


def _rest_rerun(model: Model, settings: SolverSettings, limit: int):
    """The run from rest at ``model`` again: ``(name, (range, max |mu|, k T))`` of the response
    it locks on, or ``(None, reason)`` where it does not lock or its response is not found."""
    strobe = run_stroboscope(model, settings=settings, limit=limit)
    k = strobe.candidate
    if k is None:
        evidence = NotLocked.of(strobe)
        return _classified(
            model, None, settings, _not_locked_text(evidence, "the run from rest at this Vb")
        )
    try:
        pmap, point = shoot(model, k, strobe.samples[-1])
    except NoPeriodicResponse as err:
        return None, f"the run from rest locks at {k} period{'s' * (k > 1)}, but {err}"
    k = minimal_periods(point.image, k)
    if k != pmap.periods:
        pmap, point = shoot(model, k, point.state)
    mu = _largest_multiplier(pmap, point)
    if not mu < 1.0:
        return None, (
            f"the run from rest locks at {k} period{'s' * (k > 1)} on a response with "
            f"|mu| = {mu:.4g}"
        )
    name = ("T" if k == 1 else f"{k}T") + " (from the run from rest)"
    return name, (point.image.velocity_range(), mu, k * pmap.period)


#: The length of a classification run [s]: long locks (up to 281T found) need their
#: return seen three times over.
CLASSIFY_T_END = 2000.0


def _classified(model, start, settings, not_locked):
    """Classify the attractor reached from ``start`` (None: rest) where no lock within the
    limit was seen: ``(name, (range, max |mu|, k T))`` of a long lock it finds, else
    ``(None, reason)`` with ``not_locked`` and the classification's evidence."""
    a = classify(model, y0=start, t_end=max(CLASSIFY_T_END, settings.t_end))
    if a.kind == "periodic":
        try:
            pmap, point = shoot(model, a.periods, a.state)
        except NoPeriodicResponse as err:  # classify's Newton converged: not expected
            return None, f"{not_locked}; classified {a.periods}T, but {err}"
        mu = _largest_multiplier(pmap, point)
        name = f"{a.periods}T (classified: rotation {a.rotation_number:+.4f})"
        return name, (point.image.velocity_range(), mu, a.periods * pmap.period)
    return None, f"{not_locked}; classified {a.kind.replace('_', '-')}: {a.evidence}"


def _largest_multiplier(pmap, point) -> float:
    mu = np.concatenate([np.linalg.eigvals(point.image.jacobian), pmap.fixed_multipliers()])
    return float(np.max(np.abs(mu)))


def _deviation(run_range, response_range):
    (lo, hi), (a, b) = run_range, response_range
    return max(abs(lo - a), abs(hi - b)) / (0.5 * (b - a))


def explain_coexistence(
    points: Sequence[float],
    found_by: Mapping[float, Sequence[str]],
    runs: Mapping[str, Run],
    vb: Sequence[float],
    exact: Coexistence,
    settings: SolverSettings,
    seed_step: float,
    limit: int = LOCK_LIMIT,
) -> list[Explanation]:
    """Each run at each simulated coexistence point, explained by a computed response or not.

    Parameters
    ----------
    points : sequence of float
        The simulated coexistence points (`beltmdsm.paper_reports.validation.verdicts.Coexistence`).
    found_by : mapping of float to sequence of str
        The runs that show the peak at each point.
    runs : mapping of str to Run
        The runs of the case on the grid ``vb``.
    vb : sequence of float
        The case's grid.
    exact : beltmdsm.multistability.coexistence.Coexistence
        The exact coexistence in ``Vb`` over a range that holds ``points``.
    settings : SolverSettings
        The runs' settings: the sampling step ``dt`` (`range_tolerance`); the start of
        the steady window, where a response whose largest multiplier ``mu`` (of ``k T``)
        leaves ``|mu|^(window_start / (k T))`` above
        `beltmdsm.run.summary.TRANSIENT_DECAYED` attracts too slowly for a run to
        have settled on it (the rule the runs apply to their own transient); the run
        from rest rerun where no computed response explains it.
    seed_step : float
        The spacing of ``exact``'s seeds: a seed this close to a point stands for it.
    limit : int
        The longest lock looked for in a rerun, in excitation periods.

    Returns
    -------
    list of Explanation
        In the order of ``points``, then of the runs.

    See Also
    --------
    beltmdsm.multistability.coexistence.coexistence : the exact side.
    beltmdsm.paper_reports.validation.exact.range_tolerance : how close "on a response" is.

    Examples
    --------
    The ``T``-periodic response of ``beta1 = 0.3`` is stable at 5.4 m/s. A run whose
    ``X1'`` spans its range to 1e-3 of the amplitude is explained by it; one whose
    range is 3 m/s wider on each side is not, and the response's slow attraction
    (``|mu| = 0.979`` a period) says why:

    >>> from beltmdsm import Model, SolverSettings, periodic_response
    >>> from beltmdsm.continuation.branch import continue_branch
    >>> from beltmdsm.periodic.engines import period_map
    >>> from beltmdsm.multistability.coexistence import Coexistence, ResponseBranch
    >>> from beltmdsm.multistability.stable_ranges import stable_parts
    >>> from beltmdsm.paper_reports.validation.verdicts import Run
    >>> model = Model(beta1=0.3, Vb=5.3)
    >>> b = continue_branch(periodic_response(model), "Vb", 5.3, 5.6)
    >>> exact = Coexistence("Vb", 5.3, 5.6, model, [ResponseBranch("T", b, stable_parts(b))],
    ...                     [], [], [], wall_s=0.0)
    >>> at = model.replace(Vb=5.4)
    >>> lo, hi = period_map(at, 1, None)(periodic_response(at).shooting_state).velocity_range()
    >>> def run(x1_dot_range):  # a continued sweep at the one grid point 5.4, by hand
    ...     return Run([True], [True], ["stick_slip"], [1.0], [], [], [x1_dot_range])
    >>> settings = SolverSettings(t_end=100.0)  # dt = 0.02 s: tolerance 1.6e-3
    >>> (e,) = explain_coexistence([5.4], {5.4: ["up"]}, {"up": run((lo, hi + 5e-4 * (hi - lo)))},
    ...                            [5.4], exact, settings, seed_step=0.5)
    >>> e.status, e.response, round(e.deviation, 6), e.tolerance
    ('explained', 'T', 0.001, 0.0016)
    >>> (e,) = explain_coexistence([5.4], {5.4: ["up"]}, {"up": run((lo - 3, hi + 3))},
    ...                            [5.4], exact, settings, seed_step=0.5)
    >>> e.status, e.closest, print(e.reason)  # doctest: +ELLIPSIS
    not settled: the closest stable response, T (...), attracts with |mu| = 0.9794 per 1.571 s, ...
    ('not_settled', 'T', None)
    """
    grid = [float(v) for v in vb]
    window = settings.window_start
    out = []
    for value in points:
        i = grid.index(float(value))
        model = exact.model.replace(Vb=float(value))
        tolerance = range_tolerance(model, settings.dt)
        stable = [
            (r.name, *at)
            for r in exact.responses
            if _stable_at(r, value)
            for at in _responses_at(r, model)
        ]
        for run in found_by[value]:
            observed = runs[run].velocity_range[i]
            candidates = list(stable)
            best = min(candidates, key=lambda c: _deviation(observed, c[1]), default=None)
            rerun, locked = None, None
            if best is None or _deviation(observed, best[1]) > tolerance:
                if run == "rest":
                    name, found = _rest_rerun(model, settings, limit)
                else:
                    name, found = _seed_classified(exact, model, value, run, seed_step, settings)
                if name is None:
                    rerun = found
                else:
                    locked = name
                    candidates.append((name, *found))
                    best = min(candidates, key=lambda c: _deviation(observed, c[1]))
            closest = None if best is None else best[0]
            deviation = None if best is None else _deviation(observed, best[1])
            if deviation is not None and deviation <= tolerance:
                out.append(
                    Explanation(value, run, "explained", closest, closest, deviation, tolerance, "")
                )
                continue
            # a lock that the classification found and the run does not span is no reason
            # to call the run "not locked": the rules below name the closest response
            reason = rerun or (None if locked else _unlocked_reason(exact, value, run, seed_step))
            if reason is not None and reason.startswith("not locked"):
                status = "not_locked"
            elif best is not None and math.log(best[2]) * window / best[3] > math.log(
                TRANSIENT_DECAYED
            ):
                status = "not_settled"
                left = best[2] ** (window / best[3])
                reason = (
                    f"not settled: the closest stable response, {closest} ({deviation:.1e} of "
                    f"its amplitude off), attracts with |mu| = {best[2]:.4f} per "
                    f"{best[3]:.4g} s, so a run reaches it only to {left:.1e} of its "
                    f"distance by the window's start ({window:g} s)"
                )
            else:
                status = "unexplained"
                lo, hi = observed
                reason = (reason + "; " if reason else "") + (
                    f"the run's X1' spans [{lo:.4g}, {hi:.4g}] m/s, no stable computed "
                    f"response's (closest: {closest}, {deviation:.1e} of its amplitude off)"
                    if closest is not None
                    else "no stable computed response at this Vb"
                )
            out.append(Explanation(value, run, status, None, closest, deviation, tolerance, reason))
    return out
