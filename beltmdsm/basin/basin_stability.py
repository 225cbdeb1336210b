"""Basin stability by sampling: the share of random starts in a box each attractor claims.

bSTAB's and pyBasin's estimate (Menck et al. 2013): ``N`` starts drawn uniformly in a
box of states, each run until it lands; each attractor's fraction ``p`` comes with its
standard error ``sqrt(p (1 - p) / N)``. Here a start is decided as soon as it
provably lands (`beltmdsm.attractors.self_excited`): by the region of the plane the
computed invariant sets assign to one attractor (at once, without a run), or by a
stick phase (whose end is one state), else by a run that stops at the first of
those; the counts of each way are reported (`BasinStability.decided`).

The starts are a pure function of the box, ``samples`` and ``seed``
(``numpy.random.default_rng(seed)``): a run is reproducible, and the same seed at
another parameter value draws the same starts (common random numbers, so a change of
the fractions along a parameter is not sampling noise). They go out in chunks to an
executor (a process pool, a dask cluster's ``Client.get_executor()``), each chunk
cached on disk (`beltmdsm.batch.cache`) when a folder is given; Ctrl-C keeps the
chunks finished and the estimate is made from them (``BasinStability.interrupted``).

How the work is split (measured in ``benchmarks/bench_basin_stability.py``): a chunk
whose starts the region rule decides all at once costs well under a millisecond here,
less than sending it, so this process decides it and only chunks with starts to run
go out; those are sized to the workers (`TASKS_PER_WORKER` each, at most `CHUNK`
starts) so that the last task leaves no worker long idle; the invariant sets travel
pickled once per call and are unpickled once per worker process (`_landscape_in`),
not once per task (their tables take tens of milliseconds to rebuild).

Without excitation the cycles come from the branch through the Hopf point
(`beltmdsm.cycles.branch.cycle_branch`, over `branch_range`) and the seed from the stick
end; a forced model is refused here (`beltmdsm.basin.basins.basins` maps its basins
on the period map).
"""

from __future__ import annotations

import concurrent.futures as cf
import hashlib
import json
import math
import os
import pickle
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .._calling import public
from ..arguments import cache_dir_of, count, executor_of
from ..attractors.self_excited import T_MAX, Landscape, cycles_near, landscape
from ..batch import cache
from ..batch.pool import process_pool, stop_process_pool, workers_of
from ..model import Model, as_model
from .axes import AXES  # the states a box may span

__all__ = [
    "BasinStability",
    "basin_stability",
    "draw_starts",
    "landscape_of",
    "branch_range",
    "AXES",
    "CHUNK",
    "TASKS_PER_WORKER",
    "MAX_SAMPLES",
]

#: Most starts per task sent to an executor and per cached file.
CHUNK = 500
#: Tasks per worker of an executor (fewer where a task would have under `MIN_CHUNK`
#: starts): the last one to finish leaves the others idle for about half a task.
TASKS_PER_WORKER = 8
#: Fewest starts per task of an executor (a task's overhead is milliseconds).
MIN_CHUNK = 25
#: Most starts of one estimate.
MAX_SAMPLES = 10_000_000


def standard_error(p: float, n: int) -> float:
    """``sqrt(p (1 - p) / n)``, the standard error of a fraction of ``n`` samples."""
    return math.sqrt(p * (1.0 - p) / n) if n else math.nan


@dataclass
class BasinStability:
    """Each attractor's share of random starts in a box, with its standard error.

    Attributes
    ----------
    model : Model
    region : dict of str to (float, float)
        The box; the other states at steady sliding's.
    samples : int
        Starts decided (fewer than asked where interrupted).
    seed : int
    attractors : list of InvariantSet
        In label order.
    counts : ndarray of int
        Starts per label; ``unidentified`` those no rule decided within ``T_MAX``.
    decided : dict of str to int
        How the starts were decided: ``region``, ``stick``, ``none``.
    starts : ndarray (samples, 4)
    labels : ndarray (samples,)
    interrupted : bool

    See Also
    --------
    basin_stability : computes it.

    Examples
    --------
    >>> from beltmdsm.basin.basin_stability import standard_error
    >>> round(standard_error(0.31, 4000), 4)
    0.0073
    """

    model: Model = field(repr=False)
    region: dict = field(repr=False)
    samples: int
    seed: int
    attractors: list = field(repr=False)
    counts: NDArray[np.int_] = field(repr=False)
    unidentified: int
    decided: dict
    starts: NDArray[np.float64] = field(repr=False)
    labels: NDArray[np.int_] = field(repr=False)
    interrupted: bool = False
    boundaries: list = field(repr=False, default_factory=list)

    def fraction(self, label: int) -> tuple[float, float]:
        """``(p, standard error)`` of attractor ``label``."""
        p = float(self.counts[label]) / self.samples if self.samples else math.nan
        return p, standard_error(p, self.samples)

    def __repr__(self) -> str:
        parts = []
        for i, a in enumerate(self.attractors):
            p, e = self.fraction(i)
            parts.append(f"{a.name} {p:.4f} +- {e:.4f}")
        more = f", {self.unidentified} unidentified" if self.unidentified else ""
        cut = ", interrupted" if self.interrupted else ""
        return f"BasinStability({self.samples} starts: {'; '.join(parts)}{more}{cut})"

    def as_dict(self) -> dict:
        """JSON-ready: ``attractors`` (kind, name, period, stable, fraction,
        standard_error, count), ``samples``, ``seed``, ``region``, ``decided``,
        ``unidentified``, ``interrupted``."""
        out = []
        for i, a in enumerate(self.attractors):
            p, e = self.fraction(i)
            out.append(
                {
                    "label": i,
                    "kind": "equilibrium" if a.kind == "equilibrium" else "periodic",
                    "name": a.name,
                    "period": a.period,
                    "n_sticks": a.n_sticks,
                    "fraction": p,
                    "standard_error": e,
                    "count": int(self.counts[i]),
                    "state": [float(v) for v in a.state],
                }
            )
        return {
            "attractors": out,
            "samples": self.samples,
            "seed": self.seed,
            "region": {k: list(v) for k, v in self.region.items()},
            "decided": dict(self.decided),
            "unidentified": self.unidentified,
            "interrupted": self.interrupted,
        }


def branch_range(
    model: Model, param: str = "Vb", values: list[float] | None = None
) -> tuple[float, float] | None:
    """The range of ``param`` the branch of cycles is continued over for ``values`` (the
    model's value by default): theirs and the Hopf points' within ``[v/4, 4 v]`` (of
    positive values), 10 % wider; None where there is no Hopf point.

    Examples
    --------
    The Hopf point of the friction oscillator is at ``0.5 ln 10 = 1.1513``:

    >>> m = Model(alpha=0.0, omega1=1.0, beta1=0.05, g=1.0, friction="stribeck",
    ...           mu_s=1.0, mu_k=0.5, v_s=0.5, Vb=1.5)
    >>> [round(v, 4) for v in branch_range(m)]
    [1.0362, 1.65]
    """
    from ..cycles.hopf import hopf_points

    values = [float(model[param])] if values is None else [float(v) for v in values]
    lo, hi = min(values), max(values)
    if not 0 < lo:
        return None
    hopf = [h.value for h in hopf_points(model, param, 0.25 * lo, 4.0 * hi)]
    if not hopf:
        return None
    a, b = min(lo, *hopf), max(hi, *hopf)
    return 0.9 * a, 1.1 * b


def landscape_of(model: Model, branch: Any = None) -> Landscape:
    """The `Landscape` of an autonomous model: its cycles from ``branch`` (a
    `beltmdsm.cycles.branch.CycleBranch` through the model's value) and the seeds.

    Without a branch, first the seeds alone: the unstable cycle by a backward run
    (`beltmdsm.attractors.self_excited.backward_seed`) and the one from the stick end;
    where they leave a ring of the plane without exactly one attractor on its
    boundary (a cycle missed), or none is found while steady sliding is unstable, the
    branch through the Hopf point (over `branch_range`) is computed and its cycles
    added. Where none is found and steady sliding is stable, no start is decided by
    region (the focus, sticking and runs decide), so a cycle missed would cost runs,
    not a wrong label.
    """
    from ..cycles.branch import cycle_branch

    if branch is not None:
        return landscape(model, guesses=cycles_near(branch, float(model[branch.param])))
    ls = landscape(model)
    if ls.cycles and all(r is not None for r in ls._rules):
        return ls
    if not ls.cycles and ls.equilibrium.stable:
        return ls  # no ring is decided by region: a cycle missed would cost runs, no label
    span = branch_range(model, "Vb")
    if span is None:
        return ls
    branch = cycle_branch(model, lo=span[0], hi=span[1])
    return landscape(model, guesses=cycles_near(branch, float(model["Vb"])))


def draw_starts(
    base: NDArray[np.float64], region: dict, samples: int, seed: int
) -> NDArray[np.float64]:
    """``samples`` starts uniform in the box ``region`` (axis -> (lo, hi)), the other
    states ``base``'s, from ``numpy.random.default_rng(seed)`` (axes in `AXES` order).

    Examples
    --------
    >>> s = draw_starts(np.zeros(4), {"X1": (-2.0, 2.0), "Y1": (0.0, 2.0)}, 3, seed=0)
    >>> s.shape, bool(np.all(s[:, 2:] == 0)), bool(np.all(s[:, 1] >= 0))
    ((3, 4), True, True)
    """
    rng = np.random.default_rng(seed)
    starts = np.tile(np.asarray(base, dtype=float), (samples, 1))
    for i, axis in enumerate(AXES):
        if axis in region:
            lo, hi = region[axis]
            starts[:, i] = rng.uniform(lo, hi, samples)
    return starts


def _land_chunk(ls: Landscape, starts, t_max):
    decided = ls.decide(starts)
    rows = []
    for y, label in zip(starts, decided):
        if label >= 0:
            rows.append((int(label), "region"))
        else:
            r = ls.land(y, t_max)
            rows.append((r["label"], r["how"]))
    return {"labels": [r[0] for r in rows], "how": [r[1] for r in rows]}


def _digest(ls: Landscape):
    h = hashlib.sha256()
    for s in [ls.equilibrium, *ls.cycles]:
        h.update(json.dumps([s.kind, s.stable, s.period, s.n_sticks]).encode())
        h.update(np.round(s.state, 10).tobytes())
    return h.hexdigest()


def _cached_chunk(ls, starts, t_max, cache_dir):
    if cache_dir is None:
        return _land_chunk(ls, starts, t_max)
    ident = {
        "basin_stability": ls.model.as_dict(),
        "landscape": _digest(ls),
        "starts": hashlib.sha256(np.ascontiguousarray(starts).tobytes()).hexdigest(),
        "t_max": float(t_max),
    }
    path = Path(cache_dir) / f"{cache.cache_key(ident)}.json"
    row, _ = cache.read_cached(path, ident, ("labels", "how"))
    if row is None:
        row = _land_chunk(ls, starts, t_max)
        cache.write_cached(path, ident, row)
    return row


def _checked_region(region):
    if not isinstance(region, dict) or not region:
        raise ValueError(f"region must be a dict of axis -> (low, high); got {region!r}")
    out = {}
    for axis, span in region.items():
        if axis not in AXES:
            raise ValueError(f"region's axes must be among {AXES}; got {axis!r}")
        try:
            lo, hi = (float(v) for v in span)
        except (TypeError, ValueError):
            lo, hi = math.nan, math.nan
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            raise ValueError(
                f"region[{axis!r}] must be two finite numbers, low < high; got {span!r}"
            )
        out[axis] = (lo, hi)
    return out


@public(models=True)  # beltmdsm.basin_stability: keywords checked, other models run
def basin_stability(
    model: Model | None = None,
    region: dict | None = None,
    *,
    samples: int = 1000,
    seed: int = 0,
    executor: cf.Executor | str | None = "serial",
    cache_dir: os.PathLike | str | None = "default",
    progress: bool = False,
    branch: Any = None,
    t_max: float = T_MAX,
    landscape: Landscape | None = None,
) -> BasinStability:
    """Basin stability by sampling ``samples`` uniform starts in ``region`` (module
    docstring).

    Parameters
    ----------
    model : Model, optional
        Without excitation (`beltmdsm.Model`; a dict of its keywords is taken too).
        Another registered model (``Model(model=NAME)``) runs on the generic runtime,
        `beltmdsm.oscillator.basins.basin_stability`: ``region`` maps two of its states,
        the result is that function's `Stability`, and nothing is cached.
    region : dict of str to (float, float)
        The box: axes among `AXES` (``Y1`` is ``X1'``); the others at steady sliding.
    samples : int
    seed : int
        Of ``numpy.random.default_rng``.
    executor : concurrent.futures.Executor, "serial" or None
        Where the chunks of starts run (None: a process pool over this machine's
        cores, started and stopped by the call); the result does not depend on it.
    cache_dir : path, "default" or None
        One file per chunk: a rerun or an interrupted one resumes from it.
    progress : bool
        A progress bar on stderr.
    branch : CycleBranch, optional
        The branch of cycles through the model's value (computed where None).
    t_max : float
        The longest run of a start not decided at once [s].
    landscape : Landscape, optional
        The invariant sets, computed already (`landscape_of`).

    Returns
    -------
    BasinStability

    Raises
    ------
    ValueError
        For a forced model, a bad region, ``samples`` or ``seed``.

    See Also
    --------
    beltmdsm.basin.basin_stability_along.basin_stability_along : along a parameter.
    beltmdsm.basin.basins.basins : a grid of a plane.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> m = Model(alpha=0.0, omega1=1.0, beta1=0.05, g=1.0, friction="stribeck",
    ...           mu_s=1.0, mu_k=0.5, v_s=0.5, Vb=1.5)
    >>> b = basin_stability(m, {"X1": (-2.0, 2.0), "Y1": (0.0, 2.0)}, samples=400, seed=1)
    >>> b
    BasinStability(400 starts: steady sliding 0.2950 +- 0.0228; stick-slip cycle 0.7050 +- 0.0228)
    >>> b.decided  # every start by the region the unstable cycle bounds, none run
    {'region': 400, 'stick': 0, 'none': 0}
    """
    from ..starts.cycle_seed import require_autonomous

    model = as_model(model)
    if model.model != "paper":  # another registered model: the generic runtime
        from ..oscillator import api

        return api.basin_stability(  # type: ignore[return-value]
            model, region, count("samples", samples, 1, MAX_SAMPLES), count("seed", seed, 0),
            executor_of(executor), t_max, branch=branch, landscape=landscape,
            cache_dir=None if cache_dir_of(cache_dir) in ("default", None) else cache_dir,
            progress=progress or None,
        )  # fmt: skip
    require_autonomous(model, "basin stability by sampling")
    region = _checked_region(region)
    samples = count("samples", samples, 1, MAX_SAMPLES)
    seed = count("seed", seed, 0)
    executor = executor_of(executor)
    cache_dir = cache.default_cache_dir() if cache_dir_of(cache_dir) == "default" else cache_dir
    if cache_dir is not None:
        cache_dir = cache.writable_folder(cache_dir)
    ls = landscape if landscape is not None else landscape_of(model, branch)
    starts = draw_starts(ls.equilibrium.state, region, samples, seed)
    size = chunk_size(samples, executor)
    chunks = [starts[i : i + size] for i in range(0, samples, size)]
    rows, interrupted = _run_chunks(ls, chunks, t_max, executor, cache_dir, progress)
    done = [j for j, r in enumerate(rows) if r is not None]
    kept = np.concatenate([chunks[j] for j in done]) if done else np.zeros((0, len(AXES)))
    labels = np.array([v for j in done for v in rows[j]["labels"]], dtype=int)
    how = [v for j in done for v in rows[j]["how"]]
    counts = np.array([int(np.sum(labels == i)) for i in range(len(ls.attractors))], dtype=int)
    return BasinStability(
        model,
        region,
        len(labels),
        seed,
        ls.attractors,
        counts,
        int(np.sum(labels < 0)),
        {k: how.count(k) for k in ("region", "stick", "none")},
        kept,
        labels,
        interrupted,
        [c for c in ls.cycles if not c.stable],
    )


def chunk_size(samples: int, executor) -> int:
    """Starts per task: `CHUNK` in this process; on an executor, enough tasks for
    `TASKS_PER_WORKER` per worker (`workers_of`), of `MIN_CHUNK` to `CHUNK` starts:
    the last task to finish leaves the other workers idle for about half a task, so
    2 workers with 8 tasks of 500 starts lost about 1/16 of the run.

    Parameters
    ----------
    samples : int
    executor : concurrent.futures.Executor, "serial" or None

    Returns
    -------
    int

    See Also
    --------
    beltmdsm.batch.pool.workers_of : the workers it counts.

    Examples
    --------
    >>> chunk_size(4000, "serial"), chunk_size(100_000, "serial")
    (500, 500)
    """
    if executor == "serial":
        return CHUNK
    tasks = TASKS_PER_WORKER * workers_of(executor)
    return min(CHUNK, max(MIN_CHUNK, -(-samples // tasks)))


#: This worker process's invariant sets, by the digest of their pickle (one entry).
_LANDSCAPES: dict = {}


def _landscape_in(key: str, blob: bytes) -> Landscape:
    """The sets pickled in ``blob``, unpickled once per process (their tables rebuilt
    once, not once per task)."""
    ls = _LANDSCAPES.get(key)
    if ls is None:
        ls = pickle.loads(blob)
        _LANDSCAPES.clear()
        _LANDSCAPES[key] = ls
    return ls


def _remote_chunk(key, blob, starts, t_max, cache_dir):
    return _cached_chunk(_landscape_in(key, blob), starts, t_max, cache_dir)


def _run_chunks(ls, chunks, t_max, executor, cache_dir, progress):
    """Each chunk's row (None for those not finished when Ctrl-C came) and whether it
    came. On an executor, the chunks the region rule decides whole are done here
    while the workers run the others (module docstring)."""
    from tqdm import tqdm

    rows = [None] * len(chunks)
    bar = tqdm(total=sum(len(c) for c in chunks), disable=not progress, file=sys.stderr,
               desc="basin stability")  # fmt: skip
    futures = []
    own = executor is None  # a pool of this call's own, as in beltmdsm.sweep
    if own:
        executor = process_pool(os.cpu_count())
    try:
        if executor == "serial":
            for j, c in enumerate(chunks):
                rows[j] = _cached_chunk(ls, c, t_max, cache_dir)
                bar.update(len(c))
        else:
            here, futures, blob = [], {}, None
            for j, c in enumerate(chunks):
                if np.all(ls.decide(c) >= 0):
                    here.append(j)
                    continue
                if blob is None:
                    blob = pickle.dumps(ls, protocol=pickle.HIGHEST_PROTOCOL)
                    key = hashlib.sha256(blob).hexdigest()
                futures[executor.submit(_remote_chunk, key, blob, c, t_max, cache_dir)] = j
            for j in here:
                rows[j] = _cached_chunk(ls, chunks[j], t_max, cache_dir)
                bar.update(len(chunks[j]))
            for f in cf.as_completed(futures):
                rows[futures[f]] = f.result()
                bar.update(len(chunks[futures[f]]))
    except (KeyboardInterrupt, SystemError) as err:
        # numba wraps a Ctrl-C that lands inside compiled code in a SystemError
        if isinstance(err, SystemError) and not isinstance(err.__context__, KeyboardInterrupt):
            raise
        if own:
            stop_process_pool(executor, futures)
            own = False
        for f in futures:
            f.cancel()
        return rows, True
    finally:
        bar.close()
        if own:
            executor.shutdown()
    return rows, False
