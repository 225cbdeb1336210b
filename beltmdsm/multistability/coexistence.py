"""Where stable periodic responses coexist, exactly: branches of every response found.

A run of Eq. (4) from rest, a run from the perturbed periodic response or a continued
sweep ends on one attractor; where several are stable, which one depends on where the
run starts, and a simulated range of the omega1 peak (Fig. 2b, Figs. 17-21) need not
be the unstable range of any analysis (docs/modelling.md#what-unstable-means).
`coexistence` finds the attractors over a range of one parameter and computes each
exactly:

1. **Seeds.** On a grid of the parameter: the periodic response of period ``T``
   (`beltmdsm.periodic.floquet.floquet`, continued down the grid from its neighbour);
   the attractor of a run from rest (`beltmdsm.starts.forced.run_stroboscope`);
   and those of two ladders, continued up and down the grid on the period map
   (`beltmdsm.starts.forced.ladder`). An attractor that locks at ``k`` periods
   (`beltmdsm.periodic.locked.LOCK_LIMIT` at most) is a seed; one that does not is
   listed with the evidence (`beltmdsm.periodic.locked.NotLocked`).
2. **Branches.** Every seed that no branch found so far passes through (same ``k``,
   same orbit) is continued over the whole range
   (`beltmdsm.continuation.branch.continue_branch`): its stable and unstable parts, each
   bounded by a located bifurcation.
3. **Coexistence.** The stable parts of all branches, overlaid: the ranges where two
   or more are stable, each with the responses that coexist and the kinds of its two
   edges (the bifurcations where a response starts or stops being stable, or the end of
   the range).

Without excitation (`beltmdsm.excitation.is_autonomous`) the attractors are steady sliding
and the self-excited cycles: `beltmdsm.multistability.cycle_coexistence` gives where they
coexist (hysteresis at a subcritical Hopf point), or why they do not.

What this does not see: attractors that are not locked within the limit (quasi-periodic
motion on an invariant torus, or a longer period), which are listed, not continued, and
attractors that no seed reaches.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Mapping
from typing import Any

import numpy as np

from .._calling import ranged
from ..arguments import count, flag, number
from ..continuation.branch import continue_branch
from ..continuation.settings import FORCED_SETTINGS, ContinuationSettings, as_settings
from ..errors import NoPeriodicResponse, Refused
from ..excitation import excitation_period, is_autonomous
from ..model import MODEL_PARAMETERS, Backend, Model, as_model, is_real
from ..periodic.floquet import floquet
from ..periodic.locked import LOCK_LIMIT, NotLocked, minimal_periods
from ..periodic.response import response_from
from ..settings import MAX_SEED_POINTS
from ..starts.forced import check_limit, ladder, run_stroboscope, shoot
from .coexistence_result import Coexistence, ResponseBranch, Unexplained, Unlocked
from .stable_ranges import CoexistenceRange, StablePart, overlay, stable_parts

__all__ = [
    "DEFAULT_STEP",
    "SEED_T_END",
    "StablePart",
    "ResponseBranch",
    "CoexistenceRange",
    "Unlocked",
    "Unexplained",
    "Coexistence",
    "seed_points",
    "coexistence",
    "overlay",
]

#: Spacing of the seeds' grid [in the parameter's unit].
DEFAULT_STEP = 0.5
#: Duration of the runs from rest that seed the branches [s].
SEED_T_END = 600.0
#: A run whose ``k``-returns ``|y(nT + kT) - y(nT)|`` fall from each quarter of its
#: samples to the next, and by this factor or more from the first to the last, is still
#: converging onto a ``k T`` response (`_converging`; Newton's method from its last
#: sample then decides): at Vb = 4 the ladder continued up from 2.5 spirals into the T
#: response (|mu| = 0.995 per period: its 1-returns fall from 0.066 to 0.038 over 150
#: periods) and is not yet within `beltmdsm.periodic.locked.LOCK_TOL`; the returns of
#: a torus (Vb = 3.5 from rest: 4.43 and 4.39) do not fall.
_CONVERGING = 0.8
#: The returns are compared quarter by quarter (their medians falling).
_QUARTERS = 4
#: A seed lies on a known branch when the branch, interpolated between its points,
#: comes this close (relative) to it; Newton's method from there then decides.
_NEAR = 1e-2


def _converging(samples, limit):
    """The least ``k <= limit`` whose returns fall from quarter to quarter of the samples,
    by `_CONVERGING` in all (a run still converging onto a ``k T`` response), or None."""
    y = np.asarray(samples, dtype=float)
    for k in range(1, limit + 1):
        r = np.max(np.abs(y[k:] - y[:-k]), axis=1)
        q = r.size // _QUARTERS
        if q < 2:
            continue
        quarters = [float(np.median(r[i * q : (i + 1) * q])) for i in range(_QUARTERS)]
        falling = all(b < a for a, b in zip(quarters, quarters[1:]))
        if falling and quarters[-1] <= _CONVERGING * quarters[0]:
            return k
    return None


def _on_branch(branch, value, k, phases):
    """Whether the orbit with these phase-0 states at ``value`` lies on ``branch``."""
    if branch.periods != k:
        return False
    scale = 1.0 + max(float(np.max(np.abs(x))) for x in phases)
    points = branch.points
    for a, b in zip(points[:-1], points[1:]):
        if not min(a.value, b.value) <= value <= max(a.value, b.value) or a.value == b.value:
            continue
        w = (value - a.value) / (b.value - a.value)
        x = (1 - w) * a.state + w * b.state
        if any(np.max(np.abs(x - y)) <= _NEAR * scale for y in phases):
            return True
    return False


def seed_points(lo: float, hi: float, step: float) -> int:
    """The points of the seeds' grid over ``[lo, hi]`` spaced by about ``step`` (the
    command line's ``--step``), checked as `coexistence` checks ``points``.

    Parameters
    ----------
    lo, hi : float
        The range.
    step : float
        The spacing, > 0.

    Returns
    -------
    int
        ``round((hi - lo) / step) + 1``.

    Raises
    ------
    ValueError
        For a step that is not a number > 0.
    beltmdsm.errors.Refused
        Naming ``step``, where the grid has no point inside the range or more than
        `beltmdsm.settings.MAX_SEED_POINTS` + 1 points.

    See Also
    --------
    beltmdsm.multistability.coexistence.coexistence : Takes the points.

    Examples
    --------
    >>> seed_points(0.5, 12.0, 0.5)
    24
    """
    if not (is_real(step) and step > 0):
        raise ValueError(f"step must be a number > 0; got {step!r}")
    points = max(int(round((hi - lo) / step)), 1) + 1
    return _check_points(lo, hi, points, f"step = {step:g}", "step")


def _check_points(lo: float, hi: float, points: int, said: str, name: str) -> int:
    if points < 3:
        # two seeds, the ends: a response stable only inside is never seeded
        raise Refused(
            f"{said} leaves no seed inside [{lo:g}, {hi:g}]: the seeds would be "
            f"the two ends only, and a response stable only between them is never found "
            f"(--step 20 over Vb 0.5..12 said 'coexistence: none' where the 4T response "
            f"coexists on 3.87..4.06 and 6.42..7.67); at least 3 points, a step of at "
            f"most (hi - lo) / 2 = {(hi - lo) / 2:g}",
            name,
        )
    if points - 1 > MAX_SEED_POINTS:
        raise Refused(
            f"{said} makes {points} seeds' grid points on [{lo:g}, {hi:g}], more "
            f"than MAX_SEED_POINTS = {MAX_SEED_POINTS} (beltmdsm/settings.py; each a "
            f"shooting, a run and two ladders); use points <= {MAX_SEED_POINTS + 1}, a "
            f"step >= {(hi - lo) / MAX_SEED_POINTS:.3g}",
            name,
        )
    return points


def _step_to_points(step: Any, given: Mapping[str, Any]) -> dict[str, Any]:
    """``step=`` (before: the seeds' spacing) as the ``points`` of that spacing; the
    range is in ``given`` (``lo``, ``hi``) or, in a positional call, checked later."""
    if not (is_real(step) and step > 0):
        raise ValueError(f"step must be a number > 0; got {step!r}")
    return {"points": _Spacing(float(step))}


class _Spacing(float):
    """A deprecated ``step=``, made ``points`` once the range is known."""


@ranged(renamed={"step": ("points", _step_to_points)}, models=True)
def coexistence(
    model: Model | Mapping[str, Any] | None,
    param: str,
    lo: float,
    hi: float,
    *,
    points: int | None = None,
    limit: int = LOCK_LIMIT,
    backend: Backend | None = None,
    progress: bool = False,
    settings: ContinuationSettings | None = None,
) -> Coexistence:
    """Where two or more stable periodic responses coexist in ``param`` over ``[lo, hi]``.

    Seeds on a grid of ``points`` values, each continued as a branch, the stable parts
    overlaid.

    Parameters
    ----------
    model : Model or dict or None
        The other parameters and the options (None: the base set).
    param : str
        A model parameter.
    lo, hi : float
        The range, ``lo < hi``, both finite.
    points : int, optional
        Values of the seeds' grid, the ends included: at least 3 (a seed inside the
        range) and at most `beltmdsm.settings.MAX_SEED_POINTS` + 1; default one every
        `DEFAULT_STEP`. ``step=`` (the grid's spacing, before) is deprecated.
    limit : int
        The longest period looked for, in excitation periods.
    backend : {"python", "numba", None}
        The kernels: compiled by numba, plain Python, or numba where installed.
    progress : bool
        Show the seeds on stderr (tqdm) once they take more than 2 s.
    settings : ContinuationSettings, optional
        The continuation driver's steps and tolerances for each branch
        (`beltmdsm.continuation.settings`).

    Returns
    -------
    Coexistence
        Each response's branch and stable parts, the ranges where two or more are
        stable, the attractors not locked. Without excitation
        (`beltmdsm.excitation.is_autonomous`) a
        `beltmdsm.multistability.cycle_coexistence.CycleCoexistence`: steady sliding and the
        self-excited cycles.
        Another registered model (``Model(model="belt_1dof")``): as ``coexistence
        --model NAME``, `beltmdsm.oscillator.responses.coexistence` at the ``points``
        values (the stable attractors at each, sampled, not continued; ``backend``,
        ``progress`` and ``settings`` are refused).

    Raises
    ------
    ValueError
        For an unknown parameter, a bad range, ``points`` not an integer or
        ``limit < 1``.
    beltmdsm.errors.Refused
        For ``points < 3`` (no seed inside the range), or more than
        `beltmdsm.settings.MAX_SEED_POINTS` + 1 points.

    See Also
    --------
    beltmdsm.multistability.responses.responses : every response at one point.
    beltmdsm.continuation.branch.branch : one response continued in a parameter.
    beltmdsm.continuation.band.floquet_band : where the ``T``-periodic response is unstable.

    Examples
    --------
    Between 6.5 and 7.5 m/s the ``T``-periodic response and one locked at four
    excitation periods are both stable (seeds every 0.5 m/s, locks up to 4 periods):

    >>> from beltmdsm import coexistence
    >>> found = coexistence(None, "Vb", 6.5, 7.5, points=3, limit=4)
    >>> [r.name for r in found.responses]
    ['T', '4T']
    >>> [(c.range, c.responses) for c in found.ranges]
    [((6.5, 7.5), ('4T', 'T'))]

    A grid without a seed inside the range is refused, naming the argument:

    >>> coexistence(None, "Vb", 1.0, 2.0, points=2)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    beltmdsm.errors.Refused: points = 2 leaves no seed inside [1, 2]: ...
    """
    clock = time.perf_counter()
    model = as_model(model)
    other = model.model != "paper"  # another registered model: the generic runtime
    if param not in (model.params if other else MODEL_PARAMETERS):
        of = f" of model {model.model!r} ({', '.join(model.params)})" if other else ""
        raise ValueError(f"param must be a model parameter{of}; got {param!r}")
    lo, hi = number("lo", lo), number("hi", hi)
    if not lo < hi:
        raise ValueError(f"the range must have lo < hi; got [{lo:g}, {hi:g}]")
    limit, progress = count("limit", limit, 1), flag("progress", progress)
    as_settings(settings, FORCED_SETTINGS)  # checked where it enters
    if points is None or isinstance(points, _Spacing):
        points = seed_points(lo, hi, DEFAULT_STEP if points is None else float(points))
    else:
        points = _check_points(lo, hi, count("points", points, 1), f"points = {points}", "points")
    if other:
        from ..oscillator import api

        paper = dict(backend=backend, progress=progress or None, settings=settings)
        return api.coexistence(model, param, lo, hi, points, limit, **paper)
    model = model.replace(**{param: lo})
    if is_autonomous(model):
        from .cycle_coexistence import cycle_coexistence

        return cycle_coexistence(param, lo, hi, model, backend=backend, settings=settings)
    excitation_period(model)
    grid = np.linspace(lo, hi, points)
    # the seeds: a run of SEED_T_END at each value, and ladders
    at = [model.replace(**{param: float(v)}) for v in grid]
    check_limit(limit, at, SEED_T_END, ladder=True, t_end_is_given=False)
    seeds, unlocked = [], []
    from tqdm import tqdm

    bar = tqdm(
        total=4 * grid.size,
        desc="coexistence seeds",
        unit=" seeds",
        delay=2,
        leave=False,
        disable=not progress,
        file=sys.stderr,
    )

    last = None
    for v in grid[::-1]:
        bar.update()
        for guess in ([last.response] if last is not None else []) + [None]:
            try:
                f = floquet(model.replace(**{param: float(v)}), guess=guess, backend=backend)
            except NoPeriodicResponse:
                continue
            seeds.append((float(v), 1, f.response.shooting_state, "shooting"))
            last = f
            break

    def examine(v, strobe):
        k = strobe.candidate
        if k is None:  # still converging onto a lock, where Newton's method converges
            k = _converging(strobe.samples, limit)
            try:
                if k is not None:
                    shoot(model.replace(**{param: float(v)}), k, strobe.samples[-1], backend)
            except NoPeriodicResponse:
                k = None
        if k is None:
            unlocked.append(Unlocked(float(v), NotLocked.of(strobe)))
        else:
            seeds.append((float(v), k, strobe.samples[-1], strobe.source))

    for v in grid:
        at = model.replace(**{param: float(v)})
        examine(v, run_stroboscope(at, t_end=SEED_T_END, limit=limit, backend=backend))
        bar.update()
    for values in (grid, grid[::-1]):
        strobes = ladder(model, param, values, limit=limit, backend=backend)
        for v, strobe in zip(values, strobes):
            examine(v, strobe)
            bar.update()
    bar.close()

    branches, sources, unexplained = [], [], []
    for v, k, x, source in seeds:
        at = model.replace(**{param: v})
        try:
            pmap, point = shoot(at, k, x, backend)
            k_min = minimal_periods(point.image, k)
            if k_min != k:
                pmap, point = shoot(at, k_min, point.state, backend)
                k = k_min
        except NoPeriodicResponse as err:
            unexplained.append(Unexplained(v, source, str(err)))
            continue
        phases = point.image.phases
        known = next((i for i, b in enumerate(branches) if _on_branch(b, v, k, phases)), None)
        if known is None:
            start = response_from(pmap, point)
            found = continue_branch(start, param, lo, hi, backend=backend, settings=settings)
            branches.append(found)
            sources.append([])
            known = len(branches) - 1
        label = f"{source} at {param} = {v:g}"
        if source not in {s.split(" at ")[0] for s in sources[known]}:
            sources[known].append(label)

    order = sorted(
        range(len(branches)), key=lambda i: (branches[i].periods, branches[i].value_range()[0])
    )
    counts: dict = {}
    for i in order:
        counts[branches[i].periods] = counts.get(branches[i].periods, 0) + 1
    numbered: dict = {}
    found = []
    for i in order:
        k = branches[i].periods
        name = "T" if k == 1 else f"{k}T"
        if counts[k] > 1:
            numbered[k] = numbered.get(k, 0) + 1
            name = f"{name}#{numbered[k]}"
        found.append(ResponseBranch(name, branches[i], stable_parts(branches[i]), sources[i]))
    return Coexistence(
        param,
        float(lo),
        float(hi),
        model,
        found,
        overlay(found),
        unlocked,
        unexplained,
        time.perf_counter() - clock,
        float(grid[1] - grid[0]),
        int(grid.size),
    )
