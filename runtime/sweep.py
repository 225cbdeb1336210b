"""Parameter sweeps on any concurrent.futures.Executor, with a disk cache.

A sweep runs `runtime.simulate.simulate` once per parameter value on an executor:
by default a process pool over the local cores; any object with the
``concurrent.futures.Executor`` interface works, e.g. ``dask.distributed``'s
``Client(...).get_executor()`` for a cluster. Each point's summary is cached on
disk as a small JSON file named by its `cache_key`, a SHA-256 of the full parameter
set, the contact law, the solver settings, the cache format, the package version
and the code that computes it (`code_hash`), so rerunning a figure recomputes
nothing and a change of the integrator never serves a stale result. The result is
a numpy structured array (`table_to_csv` writes CSV); no pickles are stored.

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
from dataclasses import asdict
from pathlib import Path

import numpy as np

from generated.parameters import PARAMETERS

from . import intervals
from .parameters import resolve_parameters
from .simulate import SolverSettings, simulate

__all__ = ["sweep", "run_point", "cache_key", "default_cache_dir", "table_to_csv",
           "table_from_csv", "COLUMNS", "omega1_peak_ranges", "MAX_POINTS", "SWEEPABLE",
           "linear_values", "code_files", "code_hash", "package_version", "read_cached",
           "CacheWarning"]

CACHE_FORMAT = "runtime-sweep-2"
COLUMNS = (("regime", "U24"), ("peak_omega1", "f8"), ("omega1_peak_at", "f8"),
           ("peak_Omega", "f8"), ("omega1_peak_present", "?"), ("energy_residual", "f8"),
           ("n_switches", "i8"), ("n_reversals", "i8"), ("n_sticks", "i8"),
           ("n_contact_losses", "i8"), ("min_normal_force", "f8"), ("tension_fraction", "f8"),
           ("mean_friction", "f8"), ("vr_min", "f8"), ("vr_max", "f8"), ("solver", "U16"),
           ("status", "U16"), ("wall_s", "f8"))
MODULATION_COLUMNS = tuple((f"mu_eff_{tag}_{stat}", "f8") for tag in ("Omega", "omega1")
                           for stat in ("mean", "std", "range"))
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


def default_cache_dir():
    """``$BELTMDSM_CACHE`` or ``~/.cache/beltmdsm/sweeps``."""
    return Path(os.environ.get("BELTMDSM_CACHE", Path.home() / ".cache" / "beltmdsm" / "sweeps"))


def linear_values(start, stop, step):
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
        if not (isinstance(value, (int, float, np.integer, np.floating))
                and math.isfinite(value)):
            raise ValueError(f"{name} must be a finite number; got {value!r}")
    if not step > 0:
        raise ValueError(f"step must be > 0; got {step!r}")
    if stop < start:
        raise ValueError(f"stop must be >= start; got start = {start!r}, stop = {stop!r}")
    count = math.floor((stop - start) / step + 1e-9) + 1
    if count > MAX_POINTS:
        raise ValueError(f"from {start!r} to {stop!r} in steps of {step!r} is {count:.3g} "
                         f"points, more than MAX_POINTS = {MAX_POINTS:.0e} (runtime/sweep.py)")
    return start + step * np.arange(count)


def code_files():
    """The source files a cached row depends on: ``generated/**/*.py``, ``runtime/*.py``.

    Sorted, so that their hash does not depend on the order of the file system.
    """
    return (sorted((_ROOT / "generated").rglob("*.py"))
            + sorted((_ROOT / "runtime").glob("*.py")))


@functools.lru_cache(maxsize=None)
def code_hash():
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


@functools.lru_cache(maxsize=None)
def package_version():
    """The installed version of beltmdsm, else the version in ``pyproject.toml``."""
    from importlib import metadata
    try:
        return metadata.version("beltmdsm")
    except metadata.PackageNotFoundError:
        pass
    try:
        import tomllib
    except ImportError:           # Python 3.10: read the one line
        import re
        text = (_ROOT / "pyproject.toml").read_text()
        return re.search(r'^version\s*=\s*"([^"]+)"', text, re.M).group(1)
    with open(_ROOT / "pyproject.toml", "rb") as fh:
        return tomllib.load(fh)["project"]["version"]


def cache_key(params, contact, settings, modulation=False):
    """SHA-256 of everything a point's result depends on.

    The parameters, the contact law, the solver settings, whether the modulation
    columns are wanted, the cache format, the package version (`package_version`)
    and the code (`code_hash`).
    """
    blob = json.dumps({"format": CACHE_FORMAT, "params": params, "contact": contact,
                       "settings": asdict(settings), "modulation": bool(modulation),
                       "version": package_version(), "code": code_hash()},
                      sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()


def run_point(params, contact, settings, modulation=False):
    """One sweep point: the summary row (a plain dict of numbers and strings)."""
    sim = simulate(params, contact=contact, settings=settings)
    row = {name: sim.summary[name] for name, _ in COLUMNS}
    if modulation:
        from .modulation import modulation_scatter
        row.update(modulation_scatter(sim))
    return row


def _checksum(row):
    return hashlib.sha256(json.dumps(row, sort_keys=True).encode()).hexdigest()


def _columns(modulation):
    return [name for name, _ in COLUMNS + (MODULATION_COLUMNS if modulation else ())]


def read_cached(path, params, contact, settings, modulation=False):
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
    missing = [k for k in ("key", "params", "contact", "settings", "modulation", "row",
                           "checksum") if not isinstance(data, dict) or k not in data]
    if missing:
        return None, f"missing {', '.join(missing)}"
    key = path.stem
    if data["key"] != key:
        return None, f"holds the key {str(data['key'])[:12]}..., not its name's"
    stored = (data["params"], data["contact"], data["settings"], data["modulation"])
    if stored != (params, contact, asdict(settings), bool(modulation)):
        return None, "holds another point's parameters or settings"
    row = data["row"]
    if not isinstance(row, dict) or data["checksum"] != _checksum(row):
        return None, "its row does not match its checksum"
    absent = [name for name in _columns(modulation) if name not in row]
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


def _cached_run(params, contact, settings, modulation, cache_dir):
    """One point through the cache: ``(row, cached, problem)``.

    ``problem`` says what was wrong with a cache file that was recomputed (the
    caller reports it: a warning in a worker process would be lost).
    """
    problem = None
    if cache_dir is not None:
        key = cache_key(params, contact, settings, modulation)
        path = Path(cache_dir) / f"{key}.json"
        row, problem = read_cached(path, params, contact, settings, modulation)
        if row is not None:
            return row, True, None
    row = run_point(params, contact, settings, modulation)
    if cache_dir is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        _write_atomically(path, json.dumps({
            "key": key, "params": params, "contact": contact, "settings": asdict(settings),
            "modulation": bool(modulation), "row": row, "checksum": _checksum(row)}))
    return row, False, None if problem is None else (str(path), problem)


def sweep(param, values, params=None, *, contact="hertz_damp", settings=None, executor=None,
          cache_dir="default", progress=True, modulation=False):
    """Run `simulate` for each value of one parameter.

    Parameters
    ----------
    param : str
        the swept model parameter (e.g. "Vb"; one of `SWEEPABLE`)
    values : array_like
        at most `MAX_POINTS` finite values (`linear_values` makes a range)
    params : dict, optional
        the other parameters (default: the base set)
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

    Returns
    -------
    table : numpy structured array, one row per value, with the swept parameter first

    Raises
    ------
    ValueError
        Naming what is wrong, before any run: an unknown ``param``, empty or too
        many ``values``, a bad parameter value, a bad executor.

    Warns
    -----
    CacheWarning
        For each cache file that failed its checks (`read_cached`), naming the file;
        the point is recomputed and the file rewritten.
    """
    from tqdm import tqdm

    if param not in SWEEPABLE:
        raise ValueError(f"cannot sweep {param!r}: param must be one of {', '.join(SWEEPABLE)}")
    values = np.atleast_1d(np.asarray(values, dtype=float))
    if values.ndim != 1 or values.size == 0:
        raise ValueError("values must be a non-empty 1-D sequence")
    if values.size > MAX_POINTS:
        raise ValueError(f"{values.size} values are more than MAX_POINTS = {MAX_POINTS:.0e} "
                         "(runtime/sweep.py)")
    if not (executor is None or executor == "serial" or callable(getattr(executor, "submit",
                                                                         None))):
        raise ValueError(f"executor must be None, 'serial' or a concurrent.futures.Executor; "
                         f"got {executor!r}")
    settings = settings or SolverSettings()
    points = [resolve_parameters(params, contact=contact, **{param: v}) for v in values]
    cache_dir = default_cache_dir() if cache_dir == "default" else cache_dir
    rows = [None] * len(points)
    own = executor is None
    if own:
        executor = cf.ProcessPoolExecutor(max_workers=os.cpu_count())
    bar = tqdm(total=len(points), desc=f"sweep {param}", disable=not progress, file=sys.stderr)
    try:
        if executor == "serial":
            results = ((i, _cached_run(p, contact, settings, modulation, cache_dir))
                       for i, p in enumerate(points))
        else:
            futures = {executor.submit(_cached_run, p, contact, settings, modulation, cache_dir): i
                       for i, p in enumerate(points)}
            results = ((futures[fut], fut.result()) for fut in cf.as_completed(futures))
        for i, (row, _, problem) in results:
            rows[i] = row
            if problem is not None:
                warnings.warn(f"sweep cache file {problem[0]}: {problem[1]}; recomputed and "
                              "rewritten", CacheWarning, stacklevel=2)
            bar.update()
    finally:
        bar.close()
        if own:
            executor.shutdown()
    columns = ((param, "f8"),) + COLUMNS + (MODULATION_COLUMNS if modulation else ())
    table = np.zeros(len(points), dtype=list(columns))
    for i, (v, row) in enumerate(zip(values, rows)):
        table[i][param] = v
        for name, _ in columns[1:]:
            table[i][name] = row.get(name, np.nan)
    return table


def table_to_csv(table, path):
    """Write a sweep table as CSV with a header line."""
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(table.dtype.names)
        for row in table:
            w.writerow([repr(float(x)) if isinstance(x, np.floating) else x for x in row.tolist()])


def table_from_csv(path):
    """Read a table written by `table_to_csv` back into a structured array."""
    return np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8")


def omega1_peak_ranges(table, param="Vb"):
    """Contiguous ranges of ``param`` where the omega1 peak is present: [(lo, hi), ...].

    `runtime.intervals.runs` of the table's ``omega1_peak_present`` column.
    """
    return intervals.runs(table[param], table["omega1_peak_present"])
