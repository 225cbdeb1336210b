"""Parameter sweeps on any concurrent.futures.Executor, with a disk cache.

A sweep runs one point per parameter value (`beltmdsm.batch.row.run_point`) on an
executor: by default a process pool over the local cores; any object with the
``concurrent.futures.Executor`` interface works, e.g. ``dask.distributed``'s
``Client(...).get_executor()`` for a cluster. Each point goes through the disk cache
of `beltmdsm.batch.cache`, so rerunning a figure recomputes nothing and a change of
the integrator never serves a stale result. The values are sorted and duplicates
dropped; the result (`Sweep`) holds the table as a numpy structured array
(`table_to_csv` writes CSV) and what the sweep found: where the omega1 peak is
present, the points that could not tell, how many came from the cache.

A sweep with ``continuation="up"`` or ``"down"`` follows an attractor: the points run
one after another in ascending (descending) order of the swept value, each from the
previous point's state at its last whole excitation period (`excitation_period`),
the first from rest. Such a sweep is sequential by nature and runs in this process.
"""

from __future__ import annotations

import concurrent.futures as cf
import math
import os
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._calling import valued
from .._tables import DataFrame
from ..arguments import cache_dir_of, executor_of, flag, reals, settings_of
from ..errors import Refused
from ..excitation import excitation_period
from ..model import MODEL_PARAMETERS, Backend, Model, as_model
from ..settings import (
    MAX_POINTS,
    ContactLoss,
    Method,
    Solver,
    SolverSettings,
    check_request,
    with_fields,
)
from .cache import (
    CacheWarning,
    Problem,
    cache_key,
    default_cache_dir,
    identity,
    read_cached,
    writable_folder,
    write_cached,
)
from .pool import _collect, process_pool, stop_process_pool
from .row import MODULATION_COLUMNS, STARTS, Row, Start, columns, failed_row, run_point
from .table import omega1_peak_ranges, records, to_table, unresolved_values

__all__ = [
    "sweep",
    "Sweep",
    "linear_values",
    "MAX_POINTS",
    "SWEEPABLE",
    "CONTINUATIONS",
    "CacheWarning",
]

#: Directions of a continued sweep (`sweep`'s ``continuation``).
CONTINUATIONS = ("up", "down")
#: `CONTINUATIONS` as an annotation.
Continuation = Literal["up", "down"]
#: Parameters a sweep can vary: every model parameter.
SWEEPABLE = MODEL_PARAMETERS


def linear_values(start: float, stop: float, step: float) -> NDArray[np.float64]:
    """``start, start + step, ...`` up to ``stop`` (within 1e-9 steps), checked first.

    The values are ``start + step * k``, as the command line has always computed
    them (they key the sweep cache, so they must not change by a rounding).

    Parameters
    ----------
    start, stop, step : float
        The first value, the last one (reached within 1e-9 steps) and the step.

    Returns
    -------
    ndarray
        The values, ascending.

    Raises
    ------
    ValueError
        Naming ``start``, ``stop`` or ``step``: not finite, ``step <= 0``,
        ``stop < start``, or more than `MAX_POINTS` values.

    See Also
    --------
    sweep : what takes them.

    Examples
    --------
    >>> linear_values(1.0, 2.0, 0.25).tolist()
    [1.0, 1.25, 1.5, 1.75, 2.0]
    >>> linear_values(1.0, 2.0, 0.0)
    Traceback (most recent call last):
    ...
    ValueError: step must be > 0; got 0.0
    """
    for name, value in (("start", start), ("stop", stop), ("step", step)):
        if not (isinstance(value, (int, float, np.integer, np.floating)) and math.isfinite(value)):
            raise ValueError(f"{name} must be a finite number; got {value!r}")
    if not step > 0:
        raise ValueError(f"step must be > 0; got {step!r}")
    if stop < start:
        raise ValueError(f"stop must be >= start; got start = {start!r}, stop = {stop!r}")
    count = math.floor((stop - start) / step + 1e-9) + 1
    if count > MAX_POINTS:
        raise ValueError(
            f"from {start!r} to {stop!r} in steps of {step!r} is {count:.3g} "
            f"points, more than MAX_POINTS = {MAX_POINTS:.0e} (beltmdsm/settings.py)"
        )
    return start + step * np.arange(count)


@dataclass
class Sweep:
    """The result of a sweep: the table and what it says.

    Attributes
    ----------
    param : str
        The swept parameter.
    model : Model
        The model of the other parameters and the options.
    settings : SolverSettings
    table : numpy structured array
        One record per value, ascending: the swept parameter, then the columns of
        its `beltmdsm.batch.row.Row` (`beltmdsm.batch.row.to_table`).
    continuation : {None, "up", "down"}
    start : {"rest", "periodic"}
    n_cached : int
        Points read from the cache.
    problems : list of `beltmdsm.batch.cache.Problem`
        Cache files that failed their checks and were recomputed.
    dropped : list of float
        Duplicate values given, computed once.
    rows : list of `beltmdsm.batch.row.Row`
        The row of each record of ``table``, in its order: ``sweep --json`` writes them
        (`beltmdsm.batch.row.Row.json_row`), each as it was computed.

    See Also
    --------
    beltmdsm.sweep : what returns it.
    beltmdsm.batch.row.Row : one row of its table.
    beltmdsm.floquet_band : where the periodic response is unstable, from its multipliers.

    Examples
    --------
    >>> from beltmdsm import sweep
    >>> result = sweep(None, "Vb", [1.0, 4.0, 4.0], t_end=300.0, executor="serial",
    ...                cache_dir=None, progress=False)
    >>> result  # doctest: +NORMALIZE_WHITESPACE
    Sweep(Vb over 2 values in [1, 4]; coulomb friction, hertz_damp, tension allowed;
          from rest; 0 from the cache)
      omega1 peak present in [4, 4]
    >>> result.table["Vb"].tolist(), result.dropped
    ([1.0, 4.0], [4.0])
    >>> result.table["regime"].tolist()
    ['sliding_with_reversals', 'sliding_with_reversals']
    >>> result.omega1_peak_ranges(), result.unresolved_values()
    ([(4.0, 4.0)], [])
    >>> rows = result.as_dict()["rows"]  # the rows of ``sweep --json``
    >>> list(rows[0])[:4]
    ['Vb', 'regime', 'peak_omega1', 'omega1_peak_at']
    """

    param: str
    model: Model
    settings: SolverSettings
    table: NDArray[np.void] = field(repr=False)
    continuation: str | None = None
    start: str = "rest"
    n_cached: int = 0
    problems: list[Problem] = field(default_factory=list)
    dropped: list[float] = field(default_factory=list)
    rows: list[Row] = field(default_factory=list, repr=False)

    def omega1_peak_ranges(self) -> list[tuple[float, float]]:
        """Where the omega1 peak is present (`beltmdsm.batch.table.omega1_peak_ranges`)."""
        return omega1_peak_ranges(self.table, self.param)

    def unresolved_values(self) -> list[float]:
        """Values whose run could not tell the omega1 peak
        (`beltmdsm.batch.table.unresolved_values`)."""
        return unresolved_values(self.table, self.param)

    def __repr__(self) -> str:
        from .._display import block, intervals, laws

        x = self.table[self.param]
        span = f" in [{x.min():g}, {x.max():g}]" if x.size else ""
        how = f"continued {self.continuation}" if self.continuation else f"from {self.start}"
        head = (
            f"Sweep({self.param} over {x.size} values{span}; {laws(self.model)}; "
            f"{how}; {self.n_cached} from the cache)"
        )
        lines = [f"omega1 peak present in {intervals(self.omega1_peak_ranges())}"]
        unresolved = self.unresolved_values()
        if unresolved:
            lines.append(f"unresolved at {self.param} = {', '.join(f'{v:g}' for v in unresolved)}")
        failed = int(np.isin(self.table["status"], ("failed", "no_periodic")).sum())
        if failed:
            lines.append(f"{failed} points not run or failed (their error column says why)")
        if self.problems:
            lines.append(f"{len(self.problems)} cache files failed their checks, recomputed")
        return block(head, lines)

    def to_pandas(self) -> DataFrame:
        """The table as a `pandas.DataFrame`: one row per value, the columns of `table`
        (needs pandas, imported here)."""
        from .._tables import frame

        return frame(records(self.table), self.table.dtype.names)

    def as_dict(self) -> dict[str, Any]:
        """The JSON of ``sweep --json`` (keys in docs/reference/json.md)."""
        # each row as it was computed, in one step (not through the table's records)
        if len(self.rows) != len(self.table):
            raise ValueError(
                f"a Sweep's rows are the rows of its table: {len(self.rows)} rows for "
                f"{len(self.table)} records"
            )
        modulation = MODULATION_COLUMNS[0][0] in (self.table.dtype.names or ())
        rows = [
            row.json_row(self.param, value, modulation)
            for value, row in zip(self.table[self.param].tolist(), self.rows)
        ]
        model = self.model.as_dict()
        del model["params"][self.param]  # its values are the rows'
        return {
            "param": self.param,
            **model,
            "settings": asdict(self.settings),
            "continuation": self.continuation,
            "start": self.start,
            "rows": rows,
            "omega1_peak_ranges": [list(r) for r in self.omega1_peak_ranges()],
            "unresolved": self.unresolved_values(),
            "n_points": len(rows),
            "n_cached": self.n_cached,
            "cache_problems": [asdict(p) for p in self.problems],
            "dropped_duplicates": self.dropped,
        }


def _cached_run(
    model, settings, modulation, cache_dir, continuation=None, y0=None, period=None, start="rest"
):
    """One point through the cache: ``(row, cached, problem)``, ``row`` a `Row`.

    ``problem`` (a `Problem` or None) says what was wrong with a cache file that was
    recomputed (the caller reports it: a warning in a worker process would be lost).
    ``continuation``, ``y0`` and ``period``: a point of a continued sweep, started at
    ``y0`` (None: from rest), its row with the state after its last whole excitation
    period ``period``; ``start``: `run_point`'s.
    """
    problem = None
    if cache_dir is not None:
        ident = identity(model, settings, modulation, continuation=continuation, y0=y0, start=start)
        path = Path(cache_dir) / f"{cache_key(ident)}.json"
        needed = [n for n, _ in columns(modulation)]
        needed += ["restart_t", "restart_state"] if continuation else []
        stored, reason = read_cached(path, ident, needed)
        if stored is not None:
            return Row.from_dict(stored), True, None
        problem = None if reason is None else Problem(str(path), reason)
    try:
        row = run_point(model, settings, modulation, y0=y0, restart_period=period, start=start)
    except (ValueError, ArithmeticError, RuntimeError) as err:
        if continuation is not None:
            raise  # the next point has no state to start from
        # the point is a row that says why, not the end of the sweep; not cached
        # (a rerun tries again)
        return failed_row(model, settings, modulation, err), False, problem
    if cache_dir is not None:
        write_cached(path, ident, row.as_dict())
    return row, False, problem


@valued(models=True)
def sweep(
    model: Model | Mapping[str, Any] | None,
    param: str,
    values: ArrayLike,
    *,
    settings: SolverSettings | None = None,
    executor: cf.Executor | Literal["serial"] | None = None,
    cache_dir: os.PathLike | str | None = "default",
    progress: bool = True,
    modulation: bool = False,
    continuation: Continuation | None = None,
    start: Start = "rest",
    t_end: float | None = None,
    t_discard: float | None = None,
    dt: float | None = None,
    rtol: float | None = None,
    atol: float | None = None,
    solver: Solver | None = None,
    method: Method | None = None,
    on_contact_loss: ContactLoss | None = None,
    backend: Backend | None = None,
) -> Sweep:
    """Run one point for each value of one parameter.

    Parameters
    ----------
    model : Model or dict or None
        the other parameters and the options (None: the base set). The swept
        parameter must not be among the parameters given.
    param : str
        the swept model parameter (e.g. "Vb"; one of `SWEEPABLE`)
    values : array_like
        at most `MAX_POINTS` finite values (`linear_values` makes a range); sorted,
        duplicates computed once
    settings : SolverSettings, optional
        How each run is computed.
    executor : concurrent.futures.Executor, "serial" or None
        None: a process pool over the local cores (closed afterwards); "serial":
        in this process; otherwise used as given (and left open), e.g. a dask
        ``Client.get_executor()`` (`beltmdsm.arguments.executor_of`).
    cache_dir : path, "default" or None
        None disables the cache; "default" is `beltmdsm.batch.cache.default_cache_dir`.
    progress : bool
        show a tqdm progress bar on stderr
    modulation : bool
        add the friction modulation columns (`beltmdsm.run.modulation`)
    continuation : {None, "up", "down"}
        None: every point from rest (the unforced equilibrium), independently.
        "up"/"down": follow an attractor. The points run in ascending ("up") or
        descending ("down") order of the value; the first starts from rest, each
        next one from the previous run's state at its last time ``k T <= t_end``
        (``T``: `excitation_period` of the previous point, so the excitation phase
        is 0 there as at the start of a run). Each point needs its predecessor's end,
        so the runs are sequential, in this process: ``executor`` must be None or
        "serial". Needs a periodic excitation (`excitation_period`) with
        ``T <= t_end``.
    start : {"rest", "periodic"}
        where each (not continued) run starts (`beltmdsm.batch.row.run_point`)
    t_end, t_discard, dt, rtol, atol, solver, method, on_contact_loss, backend : optional
        the fields of `SolverSettings`, in place of ``settings``' where given, as in
        `beltmdsm.simulate`

    Returns
    -------
    Sweep

    Raises
    ------
    ValueError
        Naming what is wrong, before any run: an unknown ``param``, empty or too
        many ``values``, a bad parameter value, the swept parameter also given as a
        fixed one, a bad executor, a bad ``continuation`` or one that cannot be done
        (an executor given, no periodic excitation, a period longer than ``t_end``),
        a cache folder that cannot be written.
    beltmdsm.errors.Refused
        A ValueError too: for a point that `beltmdsm.settings.check_request` refuses
        (a sampling step that aliases, a run that would not fit in memory).
    KeyboardInterrupt
        On Ctrl-C, saying how many points were done (each is kept in the cache).

    Warns
    -----
    CacheWarning
        For each cache file that failed its checks, naming the file; the point is
        recomputed and the file rewritten.

    See Also
    --------
    beltmdsm.simulate : one run.
    beltmdsm.batch.sweep.linear_values : a range of values as the command line makes it.
    beltmdsm.batch.cache : the disk cache.

    Examples
    --------
    Two belt speeds, in this process and without the disk cache; a run too short to
    tell the omega1 peak says so instead of reporting it absent:

    >>> from beltmdsm import sweep
    >>> result = sweep(None, "Vb", [1.0, 4.0], t_end=40.0, t_discard=10.0,
    ...                executor="serial", cache_dir=None, progress=False)
    >>> result.table["resolved"].tolist(), result.unresolved_values()
    ([False, False], [1.0, 4.0])
    >>> int(result.table["n_reversals"][1]) > 0
    True

    The swept parameter cannot be given as a fixed one too:

    >>> sweep({"Vb": 3.0}, "Vb", [1.0], executor="serial", cache_dir=None, progress=False)
    Traceback (most recent call last):
    ...
    ValueError: Vb is swept: give its values, not a fixed Vb as well
    """
    if isinstance(model, Model) and model.model != "paper":  # the generic runtime
        from ..oscillator import api

        fields = dict(t_end=t_end, t_discard=t_discard, dt=dt, rtol=rtol, atol=atol)
        return api.sweep(model, param, values, with_fields(settings_of(settings), **fields),
                         executor_of(executor))  # fmt: skip
    if param not in SWEEPABLE:
        raise ValueError(f"cannot sweep {param!r}: param must be one of {', '.join(SWEEPABLE)}")
    given = model.params if isinstance(model, Model) else (model or {})
    if not isinstance(model, Model) and param in given:
        raise ValueError(f"{param} is swept: give its values, not a fixed {param} as well")
    values = np.atleast_1d(reals("values", values))
    settings = with_fields(
        settings_of(settings),
        t_end=t_end,
        t_discard=t_discard,
        dt=dt,
        rtol=rtol,
        atol=atol,
        solver=solver,
        method=method,
        on_contact_loss=on_contact_loss,
        backend=backend,
    )
    cache_dir = cache_dir_of(cache_dir)
    progress, modulation = flag("progress", progress), flag("modulation", modulation)
    if values.ndim != 1 or values.size == 0:
        raise ValueError("values must be a non-empty 1-D sequence")
    if values.size > MAX_POINTS:
        raise ValueError(
            f"{values.size} values are more than MAX_POINTS = {MAX_POINTS:.0e} "
            "(beltmdsm/settings.py)"
        )
    executor = executor_of(executor)
    if start not in STARTS:
        raise ValueError(f"start must be one of {', '.join(map(repr, STARTS))}; got {start!r}")
    if continuation is not None:
        if continuation not in CONTINUATIONS:
            raise ValueError(f"continuation must be None, 'up' or 'down'; got {continuation!r}")
        if start != "rest":
            raise ValueError(
                f"a continued sweep starts from rest and then from each "
                f"previous point's end: start must be 'rest'; got {start!r}"
            )
        if not (executor is None or executor == "serial"):
            raise ValueError(
                "continuation runs the points one after another (each starts "
                "from the previous point's state), in this process: executor "
                f"must be None or 'serial'; got {executor!r}"
            )
    model = as_model(model)
    unique = np.unique(values)
    dropped = sorted(float(v) for v in values if (values == v).sum() > 1)
    dropped = sorted(set(dropped))
    points = [model.replace(**{param: float(v)}) for v in unique]
    for m in points:
        try:
            check_request(m, settings)
        except Refused as err:
            raise Refused(f"at {param} = {m[param]:g}: {err}", *err.names) from None
    cache_dir = default_cache_dir() if cache_dir == "default" else cache_dir
    if cache_dir is not None:
        cache_dir = writable_folder(cache_dir)
    if continuation is not None:
        periods = [_continuation_period(m, settings, param) for m in points]
        order = np.arange(len(points))[:: 1 if continuation == "up" else -1]
        results = _continued(points, periods, order, settings, modulation, cache_dir, continuation)
        collected = _collect(
            results, len(points), f"sweep {param} ({continuation})", progress, cache_dir
        )
    else:
        own = executor is None
        if own:
            # the workers leave Ctrl-C to this process, which stops them (`_stop`)
            executor = process_pool(os.cpu_count())
        futures = {}
        try:
            if executor == "serial":
                results = (
                    (i, _cached_run(m, settings, modulation, cache_dir, start=start))
                    for i, m in enumerate(points)
                )
            else:
                futures = {
                    executor.submit(_cached_run, m, settings, modulation, cache_dir, start=start): i
                    for i, m in enumerate(points)
                }
                results = ((futures[fut], fut.result()) for fut in cf.as_completed(futures))
            collected = _collect(results, len(points), f"sweep {param}", progress, cache_dir)
        except KeyboardInterrupt:
            if own:
                stop_process_pool(executor, futures)
                own = False
            else:
                for fut in futures:
                    fut.cancel()
            raise
        finally:
            if own:
                executor.shutdown()
    rows, n_cached, problems = collected
    found = to_table(param, unique, rows, modulation)
    return Sweep(
        param, model, settings, found, continuation, start, n_cached, problems, dropped, rows
    )


def _continuation_period(model, settings, param):
    """`excitation_period` of a point of a continued sweep, checked against ``t_end``."""
    try:
        period = excitation_period(model)
    except ValueError as err:
        raise ValueError(f"continuation at {param} = {model[param]:g}: {err}") from None
    if period > settings.t_end:
        raise ValueError(
            f"continuation at {param} = {model[param]:g}: the excitation period "
            f"{period:.6g} s is longer than t_end = {settings.t_end:g} s, so a "
            "run holds no whole period to continue from"
        )
    return period


def _continued(points, periods, order, settings, modulation, cache_dir, continuation):
    """The runs of a continued sweep in ``order``: yields ``(index, result)``."""
    y0 = None
    for i in order:
        result = _cached_run(
            points[i], settings, modulation, cache_dir, continuation, y0, periods[i]
        )
        yield i, result
        y0 = result[0].restart_state
