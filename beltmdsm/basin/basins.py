"""Basins of attraction: which attractor each start of a plane of initial states reaches.

The question an engineer asks where stable responses coexist: how large a disturbance
starts the vibration. `basins` starts the model on a grid of a plane of states at the
excitation's phase 0 (default ``X1`` and ``X1'``, the normal state on its periodic
orbit) and iterates the period map (`beltmdsm.periodic.engines.period_map`, the
closed-form map where the laws allow it) from each start only until a known attractor
claims it (`beltmdsm.attractors.recurrence.land`: within a claim radius of a periodic
attractor's points and closer one cycle later), instead of running it to the end and
classifying it by its spectrum. The claim radii are measured on the map: a pilot of
the starts (every `PILOT`-th on each axis, in grid order) lands first within
`IDENTIFY_TOL` only, and each periodic attractor's radius is then half the closest
approach of any pilot trajectory bound elsewhere or of another attractor's points
(`beltmdsm.attractors.recurrence.claim_radii`).

Attractors are found and named first the one the run from rest reaches (by its returns
and Floquet multipliers where it locks,
`beltmdsm.attractors.classification.periodic_attractor`, else
`beltmdsm.attractors.classification.classify`), the T-periodic response where it is
stable (shooting and Floquet) and any the caller gives, then, round by round, the one
each start that no known attractor claims settles on (classified from its state after
`MAX_PERIODS`; the first such start in grid order). The pilot and the rounds depend on
the grid only, never on the order in which workers finish: the map and its labels are
the same on one process, a pool or a dask cluster. Labels are ordered by kind, period
and state, not by discovery.

Each start is a pure function of the model, the start, the known attractors and the
settings, cached on disk (`beltmdsm.batch.cache`) when a cache folder is given: an
interrupted map resumes from its cache.

Without excitation there is no period map: `beltmdsm.basin.self_excited_basins`
maps the basins of steady sliding and the self-excited cycles, each start decided by
the region the computed cycles assign it to or by sticking
(`beltmdsm.attractors.self_excited`).
"""

from __future__ import annotations

import concurrent.futures as cf
import hashlib
import json
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Literal

import numpy as np

from .._calling import Rename, public
from ..arguments import cache_dir_of, count, executor_of, items_of
from ..attractors.classification import (
    KINDS,
    Attractor,
    classify,
    periodic_attractor,
    run_length,
)
from ..attractors.recurrence import (
    IDENTIFY_TOL,
    LARGEST,
    attractor_points,
    claim_radii,
    land,
    one_period_map,
    same_attractor,
    tolerance,
)
from ..batch import cache
from ..batch.pool import Tally, process_pool, stop_process_pool
from ..errors import NoPeriodicResponse, Refused
from ..excitation import excitation_period, is_autonomous
from ..model import Model, as_model
from ..periodic.floquet import floquet
from .axes import AXES, TANGENTIAL, _checked, _range, axis_range
from .basins_result import BasinAttractor, Basins

__all__ = [
    "Basins",
    "BasinAttractor",
    "basins",
    "axis_range",
    "AXES",
    "IDENTIFY_TOL",
    "LARGEST",
    "PILOT",
    "MAX_PERIODS",
    "MAX_ROUNDS",
    "MAX_STARTS",
]

#: Every PILOT-th start on each axis is a pilot (`claim_radii`).
PILOT = 3
#: Periods a start is iterated before it is handed to the classification.
MAX_PERIODS = 2000
#: Rounds of classifying the first unclaimed start.
MAX_ROUNDS = 6
#: Most starts of one map (a 300 x 300 grid).
MAX_STARTS = 90_000


def _known_digest(known):
    h = hashlib.sha256()
    for label, points, tol, need in known:
        h.update(json.dumps([label, tol, need]).encode())
        h.update(np.round(np.asarray(points), 12).tobytes())
    return h.hexdigest()


def _cached_land(model, general, start, known, max_periods, cache_dir):
    if cache_dir is None:
        return land(model, general, start, known, max_periods)
    ident = {
        "basin": model.as_dict(),
        "general": bool(general),
        "start": [float(v) for v in start],
        "known": _known_digest(known),
        "max_periods": int(max_periods),
    }
    path = Path(cache_dir) / f"{cache.cache_key(ident)}.json"
    row, _ = cache.read_cached(path, ident, ("label", "periods", "final", "failed", "approach"))
    if row is None:
        row = land(model, general, start, known, max_periods)
        cache.write_cached(path, ident, row)
    return row


#: Starts per task sent to an executor (at most): a start lands in milliseconds, so one
#: task per start spends more on scheduling than on the map (2 dask workers were 1.3x one).
CHUNK = 16
#: Tasks a call is cut into at least (while it has that many starts): a small call, the
#: pilot's, would otherwise be one task on one worker.
MIN_TASKS = 8


def _chunk(fn, items):
    return [fn(*it) for it in items]


def _map_all(fn, items, executor, tally):
    """``[fn(*it) for it in items]`` on the executor, counted by ``tally``
    (`beltmdsm.batch.pool.Tally`) as they finish."""
    if executor is None or executor == "serial":
        out = []
        for it in items:
            out.append(fn(*it))
            tally.update()
        return out
    # interleaved, not consecutive: neighbouring starts cost alike (a slowly attracting
    # basin is a region of the grid), so every task gets its share of the slow ones
    n = min(max(-(-len(items) // CHUNK), MIN_TASKS), len(items))
    if n == 0:
        return []
    futures = {executor.submit(_chunk, fn, items[j::n]): j for j in range(n)}
    out = [None] * len(items)
    for f in cf.as_completed(futures):
        j = futures[f]
        out[j::n] = f.result()
        tally.update(len(out[j::n]))
    return out


def _range_to_ends(axis: str) -> Rename:
    """``x_range=(lo, hi)`` (before) as ``x_lo=lo, x_hi=hi``."""

    def convert(given: Any, _: Mapping[str, Any]) -> dict[str, Any]:
        if given is None:
            return {}
        lo, hi = _checked(f"{axis}_range", given)
        return {f"{axis}_lo": lo, f"{axis}_hi": hi}

    return f"{axis}_lo/{axis}_hi", convert


@public(renamed={"x_range": _range_to_ends("x"), "y_range": _range_to_ends("y")}, models=True)
def basins(
    model: Model | Mapping[str, Any] | None = None,
    *,
    x: str = TANGENTIAL[0],
    x_lo: float | None = None,
    x_hi: float | None = None,
    y: str = TANGENTIAL[1],
    y_lo: float | None = None,
    y_hi: float | None = None,
    points: int = 21,
    executor: cf.Executor | Literal["serial"] | None = "serial",
    cache_dir: os.PathLike | str | None = "default",
    attractors: list[Attractor] | None = None,
    max_periods: int = MAX_PERIODS,
    t_end: float = 2000.0,
) -> Basins:
    """The basins of attraction on a ``points x points`` grid of a plane (module docstring).

    Parameters
    ----------
    model : Model, optional
        Or the keywords it is built from. Without excitation the starts are states
        (the other components at steady sliding's) and the attractors steady sliding
        and the stable self-excited cycles (`beltmdsm.basin.self_excited_basins`).
    x, y : {"X1", "Y1", "X2", "Y2"}
        The axes of the plane (``Y1`` is ``X1'``); the other components are those of the
        first attractor's state at phase 0 (for the default plane: the normal state on
        its periodic orbit).
    x_lo, x_hi, y_lo, y_hi : float, optional
        The ranges of the axes, both ends or neither (``x_range=(lo, hi)`` before:
        deprecated). Default: the known attractors' points, widened threefold about
        their centre.
    points : int
        Starts per axis.
    executor : concurrent.futures.Executor, "serial" or None
        Where the starts run: "serial" in this process, None a process pool over the
        local cores (closed afterwards), otherwise as given (a process pool,
        ``Client.get_executor()`` of a dask cluster; `beltmdsm.arguments.executor_of`);
        the result does not depend on it.
    cache_dir : path, "default" or None
        The disk cache of the starts (resume after an interruption): None disables it;
        "default" is `beltmdsm.batch.cache.default_cache_dir`, as for `beltmdsm.sweep`.
    attractors : list of Attractor, optional
        Known attractors (`beltmdsm.attractors.classification.classify`), besides the run
        from rest's.
    max_periods : int
        Periods a start is iterated before the classification takes it.
    t_end : float
        The length of each classification run [s].

    Returns
    -------
    Basins

    Raises
    ------
    ValueError
        For a bad axis, range, ``points`` or ``max_periods``.
    beltmdsm.errors.Refused
        For more than `MAX_STARTS` starts.

    See Also
    --------
    beltmdsm.attractors.classification.classify : names each attractor.
    beltmdsm.multistability.coexistence.coexistence : where stable responses coexist.

    Examples
    --------
    >>> from beltmdsm import Model, basins
    >>> b = basins(Model(Vb=3.88), points=3, x_lo=3.0, x_hi=7.0, y_lo=-8.5, y_hi=-4.5,
    ...            cache_dir=None)
    >>> [(a.attractor.kind, a.attractor.periods) for a in b.attractors]
    [('periodic', 1), ('periodic', 4)]
    """
    model = as_model(model)
    if model.model != "paper":  # another registered model: the generic runtime
        from ..oscillator import api

        return api.basins(model, x, x_lo, x_hi, y, y_lo, y_hi, points, executor, t_end)
    autonomous = is_autonomous(model)
    if not autonomous:
        # a map needs a period, and its runs some periods of it: refuse before anything runs
        t_end = run_length(t_end, excitation_period(model))
    for name, axis in (("x", x), ("y", y)):
        if axis not in AXES:
            raise ValueError(f"{name} must be one of {AXES}; got {axis!r}")
    if x == y:
        raise ValueError(f"x and y must differ; got {x!r} twice")
    points = count("points", points, 2)
    if points * points > MAX_STARTS:
        raise Refused(
            f"points = {points} gives {points * points} starts, more than MAX_STARTS = "
            f"{MAX_STARTS} (beltmdsm/basin/basins.py)",
            "points",
        )
    max_periods = count("max_periods", max_periods, 1)
    x_range = axis_range(model, "x", x, x_lo, x_hi)
    y_range = axis_range(model, "y", y, y_lo, y_hi)
    executor = executor_of(executor)
    attractors = items_of("attractors", attractors, Attractor, "beltmdsm.Attractor")
    cache_dir = cache.default_cache_dir() if cache_dir_of(cache_dir) == "default" else cache_dir
    if cache_dir is not None:
        cache_dir = cache.writable_folder(cache_dir)
    if executor is None:  # a pool of this call's own, as in beltmdsm.sweep
        pool = process_pool(os.cpu_count())
        try:
            found = basins(
                model,
                x=x,
                x_lo=x_lo,
                x_hi=x_hi,
                y=y,
                y_lo=y_lo,
                y_hi=y_hi,
                points=points,
                executor=pool,
                cache_dir=cache_dir,
                attractors=attractors,
                max_periods=max_periods,
                t_end=t_end,
            )
        except BaseException:
            stop_process_pool(pool)
            raise
        pool.shutdown()
        return found
    if autonomous:
        return _self_excited(model, x, x_range, y, y_range, points, executor, cache_dir)

    general = not {x, y} <= set(TANGENTIAL)
    pmap = one_period_map(model, general)
    found, found_points = [], []
    for a in [_seed(model, None, t_end), *_periodic_response(model), *(attractors or [])]:
        p = attractor_points(pmap, a)
        if not any(same_attractor(b, q, a, p) for b, q in zip(found, found_points)):
            found.append(a)
            found_points.append(p)
    base = np.asarray(found[0].state, dtype=float)
    ix, iy = AXES.index(x), AXES.index(y)
    xs = np.linspace(*_range("x_range", x_range, found, ix), points)
    ys = np.linspace(*_range("y_range", y_range, found, iy), points)
    starts = []
    for vy in ys:
        for vx in xs:
            s = base.copy()
            s[ix], s[iy] = vx, vy
            starts.append(s)

    labels = np.full(len(starts), -1)
    periods = np.zeros(len(starts), dtype=int)
    current = dict(enumerate(starts))
    known = [
        (j, p, tolerance(a, p), a.periods if a.kind == "periodic" else 0)
        for j, (a, p) in enumerate(zip(found, found_points))
    ]

    def run(todo):
        rows = _map_all(
            _cached_land,
            [(model, general, current[i], known, max_periods, cache_dir) for i in todo],
            executor,
            tally,
        )
        left = []
        for i, row in zip(todo, rows):
            periods[i] += row["periods"]
            if row["label"] is not None:
                labels[i] = row["label"]
            elif row["final"] is not None:
                current[i] = pmap.full_state(row["final"])
                left.append(i)
        return rows, left

    # the pilot: every PILOT-th start on each axis, claimed within IDENTIFY_TOL only; its
    # trajectories set the claim radii of the rest (claim_radii)
    pilot = [
        i for i in range(len(starts)) if (i // points) % PILOT == 0 and (i % points) % PILOT == 0
    ]
    # Ctrl-C says how many starts finished and where they are kept (issue 36 item 12)
    with Tally(len(starts), "starts", "basins", cache_dir) as tally:
        rows, left = run(pilot)
        known = claim_radii(known, rows)
        piloted = set(pilot)
        _, more = run([i for i in range(len(starts)) if i not in piloted])
        left = sorted(left + more)
        for _ in range(MAX_ROUNDS):
            if not left:
                break
            new = _seed(model, current[left[0]], t_end)
            new_points = attractor_points(pmap, new)
            if any(same_attractor(a, p, new, new_points) for a, p in zip(found, found_points)):
                break  # the unclaimed starts approach a known attractor too slowly: stop
            found.append(new)
            found_points.append(new_points)
            k = new.periods if new.kind == "periodic" else 0
            known.append((len(found) - 1, new_points, tolerance(new, new_points), k))
            tally.grow(len(left))
            _, left = run(left)
    return _result(pmap, model, x, y, xs, ys, labels, periods, found, found_points)


def _self_excited(model, x, x_range, y, y_range, points, executor, cache_dir):
    """Without excitation: steady sliding and the self-excited cycles
    (`beltmdsm.basin.self_excited_basins`)."""
    from .self_excited_basins import self_excited_basins

    grid = self_excited_basins(
        model, x=x, x_range=x_range, y=y, y_range=y_range, points=points,
        executor=executor, cache_dir=cache_dir,
    )  # fmt: skip
    attractors = [
        BasinAttractor(i, a, fraction, pts, period)
        for i, (a, fraction, pts, period) in enumerate(grid["attractors"])
    ]
    shape = grid["labels"].shape
    return Basins(
        model, x, y, grid["xs"], grid["ys"], grid["labels"], attractors,
        np.zeros(shape, dtype=int), grid["boundaries"],
    )  # fmt: skip


def _seed(model, y0, t_end):
    """The attractor the run from ``y0`` (None: rest) settles on: by its returns and
    Floquet where it locks (`beltmdsm.attractors.classification.periodic_attractor`, a
    fifth of the cost), else by `classify`."""
    try:
        return periodic_attractor(model, y0=y0, t_end=t_end)
    except NoPeriodicResponse:
        return classify(model, y0=y0, t_end=t_end)


def _periodic_response(model):
    """The T-periodic response as a known attractor where it is stable (Floquet), so that
    the starts it attracts are claimed in the first round: ``[]`` or ``[Attractor]``."""
    try:
        f = floquet(model)
    except NoPeriodicResponse:
        return []
    if not f.stable:
        return []
    mu = np.sort(np.abs(f.multipliers))[::-1]
    with np.errstate(divide="ignore"):
        exponents = np.log(mu) / f.response.period
    state = f.response.state0
    return [
        Attractor(
            "periodic",
            1,
            0.0,
            0.0,
            float(exponents[0]),
            0.0,
            exponents,
            "the T-periodic response by shooting, stable (Floquet multipliers)",
            state,
            state[None, :],
        )
    ]


def _result(pmap, model, x, y, xs, ys, labels, periods, found, found_points):
    """Labels ordered by kind, period and state, fractions, the grid reshaped."""
    used = sorted(set(labels[labels >= 0].tolist()))
    order = sorted(
        used,
        key=lambda j: (
            KINDS.index(found[j].kind),
            found[j].periods or 0,
            tuple(np.round(found_points[j].min(axis=0), 6)),
        ),
    )
    relabel = {j: n for n, j in enumerate(order)}
    new = np.array([relabel.get(int(v), -1) for v in labels])
    total = labels.size
    attractors = [
        BasinAttractor(
            relabel[j],
            found[j],
            float(np.sum(labels == j)) / total,
            np.array([pmap.full_state(p) for p in found_points[j]]),
        )
        for j in order
    ]
    shape = (len(ys), len(xs))
    return Basins(model, x, y, xs, ys, new.reshape(shape), attractors, periods.reshape(shape))
