"""Parameter sweeps on any concurrent.futures.Executor, with a disk cache.

A sweep runs `runtime.simulate.simulate` once per parameter value on an executor:
by default a process pool over the local cores; any object with the
``concurrent.futures.Executor`` interface works, e.g. ``dask.distributed``'s
``Client(...).get_executor()`` for a cluster. Each point's summary is cached on
disk as a small JSON file named by a SHA-256 of the full parameter set, the contact
law, the solver settings and the cache format, so rerunning a figure recomputes
nothing. The result is a numpy structured array (`table_to_csv` writes CSV); no
pickles are stored.
"""
from __future__ import annotations

import concurrent.futures as cf
import csv
import hashlib
import json
import os
import sys
from dataclasses import asdict
from pathlib import Path

import numpy as np

from . import intervals
from .parameters import resolve_parameters
from .simulate import SolverSettings, simulate

__all__ = ["sweep", "run_point", "cache_key", "default_cache_dir", "table_to_csv",
           "table_from_csv", "COLUMNS", "omega1_peak_ranges"]

CACHE_FORMAT = "runtime-sweep-1"
COLUMNS = (("regime", "U24"), ("peak_omega1", "f8"), ("omega1_peak_at", "f8"),
           ("peak_Omega", "f8"), ("omega1_peak_present", "?"), ("energy_residual", "f8"),
           ("n_switches", "i8"), ("n_reversals", "i8"), ("n_sticks", "i8"),
           ("n_contact_losses", "i8"), ("min_normal_force", "f8"), ("tension_fraction", "f8"),
           ("mean_friction", "f8"), ("vr_min", "f8"), ("vr_max", "f8"), ("solver", "U16"),
           ("status", "U16"), ("wall_s", "f8"))
MODULATION_COLUMNS = tuple((f"mu_eff_{tag}_{stat}", "f8") for tag in ("Omega", "omega1")
                           for stat in ("mean", "std", "range"))


def default_cache_dir():
    """``$BELTMDSM_CACHE`` or ``~/.cache/beltmdsm/sweeps``."""
    return Path(os.environ.get("BELTMDSM_CACHE", Path.home() / ".cache" / "beltmdsm" / "sweeps"))


def cache_key(params, contact, settings, modulation=False):
    """SHA-256 of everything a point's result depends on."""
    blob = json.dumps({"format": CACHE_FORMAT, "params": params, "contact": contact,
                       "settings": asdict(settings), "modulation": bool(modulation)},
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


def _cached_run(params, contact, settings, modulation, cache_dir):
    if cache_dir is not None:
        path = Path(cache_dir) / f"{cache_key(params, contact, settings, modulation)}.json"
        if path.exists():
            return json.loads(path.read_text())["row"], True
    row = run_point(params, contact, settings, modulation)
    if cache_dir is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(json.dumps({"params": params, "contact": contact,
                                   "settings": asdict(settings), "row": row}))
        os.replace(tmp, path)
    return row, False


def sweep(param, values, params=None, *, contact="hertz_damp", settings=None, executor=None,
          cache_dir="default", progress=True, modulation=False):
    """Run `simulate` for each value of one parameter.

    Parameters
    ----------
    param : str
        the swept model parameter (e.g. "Vb")
    values : array_like
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
    """
    from tqdm import tqdm

    values = np.atleast_1d(np.asarray(values, dtype=float))
    if values.ndim != 1 or values.size == 0:
        raise ValueError("values must be a non-empty 1-D sequence")
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
            for i, p in enumerate(points):
                rows[i] = _cached_run(p, contact, settings, modulation, cache_dir)[0]
                bar.update()
        else:
            futures = {executor.submit(_cached_run, p, contact, settings, modulation, cache_dir): i
                       for i, p in enumerate(points)}
            for fut in cf.as_completed(futures):
                rows[futures[fut]] = fut.result()[0]
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
