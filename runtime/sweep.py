"""Parameter sweeps on any concurrent.futures.Executor, with a disk cache.

A sweep runs `runtime.simulate.simulate` once per parameter value on an executor:
by default a process pool over the local cores; any object with the
``concurrent.futures.Executor`` interface works, e.g. ``dask.distributed``'s
``Client(...).get_executor()`` for a cluster. Each point's summary is cached on
disk as a small JSON file named by its `cache_key`, a SHA-256 of the full parameter
set, the contact and tension laws, the solver settings, the start state of a
continued point, the cache format, the package version and the code that computes
it (`code_hash`), so rerunning a figure recomputes nothing and a change of the
integrator never serves a stale result. The result is a numpy structured array
(`table_to_csv` writes CSV); no pickles are stored.

A sweep with ``continuation="up"`` or ``"down"`` follows an attractor: the points run
one after another in ascending (descending) order of the swept value, each from the
previous point's state at its last whole excitation period (`excitation_period`),
the first from rest. Such a sweep is sequential by nature and runs in this process.

The cache is safe to share between processes and hosts (dask workers on several
machines): a file is written under a unique temporary name and renamed into place,
so a reader sees a whole file or none, and a file that fails its checks (not JSON,
keys missing, another point's key or parameters, a row that does not match its
checksum) is reported with a `CacheWarning`, recomputed and rewritten, never served.
"""

from __future__ import annotations

import concurrent.futures as cf
import csv
import functools
import hashlib
import json
import math
import os
import sys
import uuid
import warnings
from collections.abc import Iterable, Mapping
from dataclasses import asdict
from pathlib import Path
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from generated.parameters import PARAMETERS

from . import intervals
from .parameters import Contact, Tension, excitation_period, resolve_parameters
from .simulate import STARTS, SolverSettings, Start, simulate

__all__ = [
    "sweep",
    "run_point",
    "cache_key",
    "default_cache_dir",
    "table_to_csv",
    "table_from_csv",
    "COLUMNS",
    "omega1_peak_ranges",
    "MAX_POINTS",
    "SWEEPABLE",
    "linear_values",
    "code_files",
    "code_hash",
    "package_version",
    "read_cached",
    "CacheWarning",
    "excitation_period",
    "CONTINUATIONS",
    "STARTS",
    "NO_PERIODIC_RESPONSE",
    "resolved_mask",
    "unresolved_values",
]

CACHE_FORMAT = "runtime-sweep-3"
#: The table's columns after the swept parameter. ``omega1_peak_present`` is False
#: where ``resolved`` is False (the run could not tell, `runtime.simulate.summarize`):
#: read it together with ``resolved``, never alone as "no peak".
COLUMNS = (
    ("regime", "U24"),
    ("peak_omega1", "f8"),
    ("omega1_peak_at", "f8"),
    ("peak_Omega", "f8"),
    ("omega1_peak_present", "?"),
    ("resolved", "?"),
    ("energy_residual", "f8"),
    ("n_switches", "i8"),
    ("n_reversals", "i8"),
    ("n_sticks", "i8"),
    ("n_contact_losses", "i8"),
    ("min_normal_force", "f8"),
    ("tension_fraction", "f8"),
    ("mean_friction", "f8"),
    ("vr_min", "f8"),
    ("vr_max", "f8"),
    ("tension", "U8"),
    ("solver", "U16"),
    ("status", "U16"),
    ("wall_s", "f8"),
)
#: The regime of a point started on the periodic response where none is found.
NO_PERIODIC_RESPONSE = "no_periodic_response"
#: Directions of a continued sweep (`sweep`'s ``continuation``).
CONTINUATIONS = ("up", "down")
#: `CONTINUATIONS` as an annotation.
Continuation = Literal["up", "down"]
#: Largest denominator tried when writing Omega_t / Omega_n as a fraction
MODULATION_COLUMNS = tuple(
    (f"mu_eff_{tag}_{stat}", "f8")
    for tag in ("Omega", "omega1")
    for stat in ("mean", "std", "range")
)
#: Most points of one sweep. A sweep of 10^6 runs of a second each is eleven days on
#: one core; a larger one is a mistake (a step of 1e-15), refused before anything is
#: allocated.
MAX_POINTS = 10**6
#: Parameters a sweep can vary: every model parameter (``Vhat`` belongs to Eq. 23
#: only, the simulation does not use it).
SWEEPABLE = tuple(p["name"] for p in PARAMETERS if p["name"] != "Vhat")
_ROOT = Path(__file__).resolve().parents[1]


class CacheWarning(UserWarning):
    """A sweep cache file failed its checks; it was recomputed and rewritten."""


def default_cache_dir() -> Path:
    """``$BELTMDSM_CACHE`` or ``~/.cache/beltmdsm/sweeps``."""
    return Path(os.environ.get("BELTMDSM_CACHE", Path.home() / ".cache" / "beltmdsm" / "sweeps"))


def linear_values(start: float, stop: float, step: float) -> NDArray[np.float64]:
    """``start, start + step, ...`` up to ``stop`` (within 1e-9 steps), checked first.

    The values are ``start + step * k``, as the command line has always computed
    them (they key the sweep cache, so they must not change by a rounding).

    Raises
    ------
    ValueError
        Naming ``start``, ``stop`` or ``step``: not finite, ``step <= 0``,
        ``stop < start``, or more than `MAX_POINTS` values.
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
            f"points, more than MAX_POINTS = {MAX_POINTS:.0e} (runtime/sweep.py)"
        )
    return start + step * np.arange(count)


def code_files() -> list[Path]:
    """The source files a cached row depends on: ``generated/**/*.py``, ``runtime/*.py``.

    Sorted, so that their hash does not depend on the order of the file system.
    """
    return sorted((_ROOT / "generated").rglob("*.py")) + sorted((_ROOT / "runtime").glob("*.py"))


@functools.cache
def code_hash() -> str:
    """SHA-256 over the path and bytes of every file of `code_files` (once per process).

    Part of `cache_key`: a change of the generated model or of the integrator gives
    new keys, so that no stale result is served.
    """
    digest = hashlib.sha256()
    for path in code_files():
        data = path.read_bytes()
        name = path.relative_to(_ROOT).as_posix().encode()
        # lengths first, so that no two file sets can hash the same byte stream
        digest.update(b"%d:%s%d:" % (len(name), name, len(data)))
        digest.update(data)
    return digest.hexdigest()


@functools.cache
def package_version() -> str:
    """The installed version of beltmdsm, else the version in ``pyproject.toml``."""
    from importlib import metadata

    try:
        return metadata.version("beltmdsm")
    except metadata.PackageNotFoundError:
        pass
    try:
        import tomllib
    except ImportError:  # Python 3.10: read the one line
        import re

        text = (_ROOT / "pyproject.toml").read_text()
        return re.search(r'^version\s*=\s*"([^"]+)"', text, re.M).group(1)
    with open(_ROOT / "pyproject.toml", "rb") as fh:
        return tomllib.load(fh)["project"]["version"]


def _identity(
    params, contact, tension, settings, modulation, continuation=None, y0=None, start="rest"
):
    """What a point's result depends on, besides the code: keys and checks the cache.

    A continued point (``continuation`` "up" or "down") is another run than the
    point from rest: its direction and its start state ``y0`` (None: from rest)
    belong to it; so does the start on the periodic response (``start``).
    """
    ident = {
        "params": params,
        "contact": contact,
        "tension": tension,
        "settings": asdict(settings),
        "modulation": bool(modulation),
    }
    if start != "rest":
        ident["start"] = start
    if continuation is not None:
        ident["continuation"] = continuation
        ident["y0"] = None if y0 is None else [float(x) for x in y0]
    return ident


def cache_key(
    params: dict[str, float],
    contact: Contact,
    settings: SolverSettings,
    modulation: bool = False,
    *,
    tension: Tension = "allowed",
    continuation: Continuation | None = None,
    y0: Iterable[float] | None = None,
    start: Start = "rest",
) -> str:
    """SHA-256 of everything a point's result depends on.

    The parameters, the contact and tension laws, the solver settings, whether the
    modulation columns are wanted, for a continued point its direction and start
    state, a start on the periodic response, the cache format, the package version
    (`package_version`) and the code (`code_hash`).
    """
    blob = json.dumps(
        {
            "format": CACHE_FORMAT,
            **_identity(params, contact, tension, settings, modulation, continuation, y0, start),
            "version": package_version(),
            "code": code_hash(),
        },
        sort_keys=True,
    )
    return hashlib.sha256(blob.encode()).hexdigest()


def run_point(
    params: Mapping[str, float | None] | None,
    contact: Contact,
    settings: SolverSettings,
    modulation: bool = False,
    *,
    tension: Tension = "allowed",
    y0: ArrayLike | None = None,
    restart_period: float | None = None,
    start: Start = "rest",
) -> dict[str, Any]:
    """One sweep point: the summary row (a plain dict of numbers and strings).

    Parameters
    ----------
    tension : {"allowed", "clipped"}
    y0 : sequence of 4 floats, optional
        start state (default: from rest, `runtime.parameters.initial_state`)
    restart_period : float, optional
        the excitation period ``T`` (`excitation_period`); the row then also holds
        ``restart_t``, the last multiple of ``T`` within the run, and
        ``restart_state``, the state there (where a continued sweep starts its next
        point; not table columns).
    start : {"rest", "periodic"}
        `runtime.simulate.simulate`'s; where no periodic response is found the row
        has the regime `NO_PERIODIC_RESPONSE`, ``resolved`` False, ``status`` "no_periodic"
        and NaN (or 0) in the numeric columns: the point cannot be run, and never
        counts as a point without the peak.
    """
    if start == "periodic":
        from .floquet import NoPeriodicResponse

        try:
            sim = simulate(params, contact=contact, tension=tension, settings=settings, start=start)
        except NoPeriodicResponse:
            row = {
                name: 0 if kind == "i8" else float("nan")
                for name, kind in COLUMNS + (MODULATION_COLUMNS if modulation else ())
            }
            row.update(
                regime=NO_PERIODIC_RESPONSE,
                omega1_peak_present=False,
                resolved=False,
                tension=tension,
                solver=settings.solver,
                status="no_periodic",
            )
            return row
    else:
        sim = simulate(params, contact=contact, tension=tension, settings=settings, y0=y0)
    row = {name: sim.summary[name] for name, _ in COLUMNS}
    # None (unresolved) is stored as False beside resolved = False: a bool column
    row["omega1_peak_present"] = bool(row["resolved"] and row["omega1_peak_present"])
    if modulation:
        from .modulation import modulation_scatter

        row.update(modulation_scatter(sim))
    if restart_period is not None:
        t_end = sim.trajectory.t_end
        # the last whole period; 1e-9 forgives the rounding of t_end / T at a multiple
        t_k = min(math.floor(t_end / restart_period + 1e-9) * restart_period, t_end)
        row["restart_t"] = float(t_k)
        row["restart_state"] = [float(x) for x in sim.trajectory.state(np.array([t_k]))[:, 0]]
    return row


def _checksum(row):
    return hashlib.sha256(json.dumps(row, sort_keys=True).encode()).hexdigest()


def _columns(modulation):
    return [name for name, _ in COLUMNS + (MODULATION_COLUMNS if modulation else ())]


def read_cached(
    path: os.PathLike | str,
    params: dict[str, float],
    contact: Contact,
    settings: SolverSettings,
    modulation: bool = False,
    *,
    tension: Tension = "allowed",
    continuation: Continuation | None = None,
    y0: Iterable[float] | None = None,
    start: Start = "rest",
) -> tuple[dict[str, Any] | None, str | None]:
    """The row stored at ``path`` for this point, after checking the file.

    Returns
    -------
    (row, problem)
        ``row`` (a dict) and ``None`` for a valid file; ``None`` and what is wrong
        (a short phrase) for a file that is not JSON, lacks a key or a column,
        belongs to another point, or whose row does not match its checksum;
        ``(None, None)`` for no file.
    """
    path = Path(path)
    try:
        text = path.read_text()
    except FileNotFoundError:
        return None, None
    try:
        data = json.loads(text)
    except ValueError as err:
        return None, f"not valid JSON ({err})"
    ident = _identity(params, contact, tension, settings, modulation, continuation, y0, start)
    missing = [
        k for k in ("key", *ident, "row", "checksum") if not isinstance(data, dict) or k not in data
    ]
    if missing:
        return None, f"missing {', '.join(missing)}"
    key = path.stem
    if data["key"] != key:
        return None, f"holds the key {str(data['key'])[:12]}..., not its name's"
    stored = {k: v for k, v in data.items() if k not in ("key", "row", "checksum")}
    if stored != ident:
        return None, "holds another point's parameters or settings"
    row = data["row"]
    if not isinstance(row, dict) or data["checksum"] != _checksum(row):
        return None, "its row does not match its checksum"
    needed = _columns(modulation) + (["restart_t", "restart_state"] if continuation else [])
    absent = [name for name in needed if name not in row]
    if absent:
        return None, f"its row lacks {', '.join(absent)}"
    return row, None


def _write_atomically(path, text):
    """Write ``text`` to ``path`` through a unique temporary file and a rename.

    The temporary name holds a random UUID, unique across processes and hosts that
    share the folder; ``os.replace`` is atomic, so a reader (or a writer of the
    same point) never sees a partial file.
    """
    tmp = path.with_name(f".{path.name}.{uuid.uuid4().hex}.tmp")
    try:
        with open(tmp, "w") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def _cached_run(
    params,
    contact,
    settings,
    modulation,
    cache_dir,
    tension="allowed",
    continuation=None,
    y0=None,
    period=None,
    start="rest",
):
    """One point through the cache: ``(row, cached, problem)``.

    ``problem`` says what was wrong with a cache file that was recomputed (the
    caller reports it: a warning in a worker process would be lost).
    ``continuation``, ``y0`` and ``period``: a point of a continued sweep, started
    at ``y0`` (None: from rest), its row with the state after its last whole
    excitation period ``period``; ``start``: `run_point`'s.
    """
    problem = None
    extra = dict(tension=tension, continuation=continuation, y0=y0, start=start)
    if cache_dir is not None:
        key = cache_key(params, contact, settings, modulation, **extra)
        path = Path(cache_dir) / f"{key}.json"
        row, problem = read_cached(path, params, contact, settings, modulation, **extra)
        if row is not None:
            return row, True, None
    row = run_point(
        params,
        contact,
        settings,
        modulation,
        tension=tension,
        y0=y0,
        restart_period=period,
        start=start,
    )
    if cache_dir is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        _write_atomically(
            path,
            json.dumps(
                {
                    "key": key,
                    **_identity(
                        params,
                        contact,
                        tension,
                        settings,
                        modulation,
                        **{k: extra[k] for k in ("continuation", "y0", "start")},
                    ),
                    "row": row,
                    "checksum": _checksum(row),
                }
            ),
        )
    return row, False, None if problem is None else (str(path), problem)


def sweep(
    param: str,
    values: ArrayLike,
    params: Mapping[str, float | None] | None = None,
    *,
    contact: Contact = "hertz_damp",
    tension: Tension = "allowed",
    settings: SolverSettings | None = None,
    executor: cf.Executor | Literal["serial"] | None = None,
    cache_dir: os.PathLike | str | None = "default",
    progress: bool = True,
    modulation: bool = False,
    continuation: Continuation | None = None,
    start: Start = "rest",
) -> NDArray[np.void]:
    """Run `simulate` for each value of one parameter.

    Parameters
    ----------
    param : str
        the swept model parameter (e.g. "Vb"; one of `SWEEPABLE`)
    values : array_like
        at most `MAX_POINTS` finite values (`linear_values` makes a range)
    params : dict, optional
        the other parameters (default: the base set)
    contact : {"hertz_damp", "kelvin_voigt"}
    tension : {"allowed", "clipped"}
        the tension law of every run (docs/modelling.md#tension)
    settings : SolverSettings, optional
    executor : concurrent.futures.Executor, "serial" or None
        None: a process pool over the local cores (closed afterwards); "serial":
        in this process; otherwise used as given (and left open), e.g. a dask
        ``Client.get_executor()``.
    cache_dir : path, "default" or None
        None disables the cache; "default" is `default_cache_dir()`.
    progress : bool
        show a tqdm progress bar on stderr
    modulation : bool
        add the friction modulation columns (`runtime.modulation.modulation_scatter`)
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
        where each (not continued) run starts: the unforced equilibrium, or the
        periodic response plus `runtime.simulate.PERTURBATION` in ``X1``
        (`runtime.simulate.simulate`); a point without a periodic response gets the
        regime `NO_PERIODIC_RESPONSE` and ``resolved`` False (`run_point`).

    Returns
    -------
    table : numpy structured array, one row per value, with the swept parameter first;
        in the order of ``values``, or ascending for a continued sweep (whatever its
        direction).

    Raises
    ------
    ValueError
        Naming what is wrong, before any run: an unknown ``param``, empty or too
        many ``values``, a bad parameter value, a bad executor or tension law, a bad
        ``continuation`` or one that cannot be done (an executor given, no periodic
        excitation, a period longer than ``t_end``).

    Warns
    -----
    CacheWarning
        For each cache file that failed its checks (`read_cached`), naming the file;
        the point is recomputed and the file rewritten.
    """
    from .model import TENSIONS

    if param not in SWEEPABLE:
        raise ValueError(f"cannot sweep {param!r}: param must be one of {', '.join(SWEEPABLE)}")
    if tension not in TENSIONS:
        raise ValueError(
            f"tension must be one of {', '.join(map(repr, TENSIONS))}; got {tension!r}"
        )
    values = np.atleast_1d(np.asarray(values, dtype=float))
    if values.ndim != 1 or values.size == 0:
        raise ValueError("values must be a non-empty 1-D sequence")
    if values.size > MAX_POINTS:
        raise ValueError(
            f"{values.size} values are more than MAX_POINTS = {MAX_POINTS:.0e} (runtime/sweep.py)"
        )
    if not (
        executor is None or executor == "serial" or callable(getattr(executor, "submit", None))
    ):
        raise ValueError(
            f"executor must be None, 'serial' or a concurrent.futures.Executor; got {executor!r}"
        )
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
    settings = settings or SolverSettings()
    points = [resolve_parameters(params, contact=contact, **{param: v}) for v in values]
    cache_dir = default_cache_dir() if cache_dir == "default" else cache_dir
    rows = [None] * len(points)
    columns = ((param, "f8"),) + COLUMNS + (MODULATION_COLUMNS if modulation else ())
    if continuation is not None:
        periods = [_continuation_period(p, settings, param) for p in points]
        order = np.argsort(values, kind="stable")
        if continuation == "down":
            order = order[::-1]
        results = _continued(
            points, periods, order, contact, tension, settings, modulation, cache_dir, continuation
        )
        rows = _collect(results, rows, len(points), f"sweep {param} ({continuation})", progress)
        order = np.argsort(values, kind="stable")
        return _table(columns, param, values[order], [rows[i] for i in order])
    own = executor is None
    if own:
        executor = cf.ProcessPoolExecutor(max_workers=os.cpu_count())
    try:
        if executor == "serial":
            results = (
                (i, _cached_run(p, contact, settings, modulation, cache_dir, tension, start=start))
                for i, p in enumerate(points)
            )
        else:
            futures = {
                executor.submit(
                    _cached_run, p, contact, settings, modulation, cache_dir, tension, start=start
                ): i
                for i, p in enumerate(points)
            }
            results = ((futures[fut], fut.result()) for fut in cf.as_completed(futures))
        rows = _collect(results, rows, len(points), f"sweep {param}", progress)
    finally:
        if own:
            executor.shutdown()
    return _table(columns, param, values, rows)


def _continuation_period(p, settings, param):
    """`excitation_period` of a point of a continued sweep, checked against ``t_end``."""
    try:
        period = excitation_period(p)
    except ValueError as err:
        raise ValueError(f"continuation at {param} = {p[param]:g}: {err}") from None
    if period > settings.t_end:
        raise ValueError(
            f"continuation at {param} = {p[param]:g}: the excitation period "
            f"{period:.6g} s is longer than t_end = {settings.t_end:g} s, so a "
            "run holds no whole period to continue from"
        )
    return period


def _continued(
    points, periods, order, contact, tension, settings, modulation, cache_dir, continuation
):
    """The runs of a continued sweep in ``order``: yields ``(index, result)``."""
    y0 = None
    for i in order:
        result = _cached_run(
            points[i],
            contact,
            settings,
            modulation,
            cache_dir,
            tension,
            continuation,
            y0,
            periods[i],
        )
        yield i, result
        y0 = result[0]["restart_state"]


def _collect(results, rows, n, desc, progress):
    """Put ``(index, (row, cached, problem))`` results into ``rows``, with a progress bar."""
    from tqdm import tqdm

    bar = tqdm(total=n, desc=desc, disable=not progress, file=sys.stderr)
    try:
        for i, (row, _, problem) in results:
            rows[i] = row
            if problem is not None:
                # stacklevel 3: the caller of sweep (sweep -> _collect -> warn)
                warnings.warn(
                    f"sweep cache file {problem[0]}: {problem[1]}; recomputed and rewritten",
                    CacheWarning,
                    stacklevel=3,
                )
            bar.update()
    finally:
        bar.close()
    return rows


def _table(columns, param, values, rows):
    table = np.zeros(len(rows), dtype=list(columns))
    for i, (v, row) in enumerate(zip(values, rows)):
        table[i][param] = v
        for name, _ in columns[1:]:
            table[i][name] = row.get(name, np.nan)
    return table


def table_to_csv(table: NDArray[np.void], path: os.PathLike | str) -> None:
    """Write a sweep table as CSV with a header line."""
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(table.dtype.names)
        for row in table:
            w.writerow([repr(float(x)) if isinstance(x, np.floating) else x for x in row.tolist()])


def table_from_csv(path: os.PathLike | str) -> NDArray[np.void]:
    """Read a table written by `table_to_csv` back into a structured array."""
    return np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8")


def resolved_mask(
    table: NDArray[np.void] | dict[str, Any], param: str | None = None
) -> NDArray[np.bool_]:
    """The ``resolved`` column of a sweep table; all True for a table without one.

    ``table``: a structured array (`sweep`) or a dict of columns (the notebooks'
    scans); ``param`` names a column whose length counts the points of a dict.
    """
    names = (
        table.keys()
        if isinstance(table, dict)
        else getattr(getattr(table, "dtype", None), "names", None) or ()
    )
    if "resolved" in names:
        return np.asarray(table["resolved"], dtype=bool)
    n = len(table[param]) if isinstance(table, dict) else len(table)
    return np.ones(n, dtype=bool)


def omega1_peak_ranges(
    table: NDArray[np.void] | dict[str, Any], param: str = "Vb"
) -> list[tuple[float, float]]:
    """Contiguous ranges of ``param`` where the omega1 peak is present: [(lo, hi), ...].

    `runtime.intervals.runs` of ``omega1_peak_present`` at resolved points. An
    unresolved point (``resolved`` False: the run could not tell) is treated like
    an excluded point of the validation: it is not a point with the peak, so it
    ends a range, and it is not a point without it either; `unresolved_values`
    lists them, so that a reader never takes the gap for "no peak".
    """
    present = np.asarray(table["omega1_peak_present"], dtype=bool) & resolved_mask(table, param)
    return intervals.runs(table[param], present)


def unresolved_values(table: NDArray[np.void] | dict[str, Any], param: str = "Vb") -> list[float]:
    """Values of ``param`` whose run could not tell the omega1 peak (ascending)."""
    return sorted(float(v) for v in np.asarray(table[param])[~resolved_mask(table, param)])
