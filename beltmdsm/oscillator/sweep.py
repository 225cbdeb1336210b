"""One parameter of any model over a range: a run per value and what it settles on.

Each value is one `beltmdsm.oscillator.simulate` run from the same start; its row says
what the run does after ``t_discard``: the range of every state (named by the model),
the sticks and slip reversals, and its regime (``steady_sliding``: every state still to
``1e-6`` relative; ``stick_slip``: a stick; ``slip_reversal``: the slip velocity
changes sign without a stick; ``slip``: it oscillates in one slip direction). The
points run on any `concurrent.futures.Executor` (the command line passes its pool),
each worker rebuilding its `System` from the model's name and parameters.
"""

from __future__ import annotations

import csv
import os
from concurrent.futures import Executor
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike

from .hybrid import simulate
from .system import STICK, System

__all__ = ["Sweep", "sweep", "REGIMES"]

#: What a run settles on, as a row names it.
REGIMES = ("steady_sliding", "slip", "slip_reversal", "stick_slip")
#: A state whose range over the kept window is below this, relative to ``1 + |state|``,
#: is still (steady sliding).
_STILL = 1e-6


class _Cache(Protocol):
    """Where rows are kept between sweeps, by their point's identity."""

    def get(self, ident: dict) -> dict | None: ...

    def put(self, ident: dict, row: dict) -> None: ...


@dataclass(repr=False)
class Sweep:
    """Runs of a model over one parameter.

    Attributes
    ----------
    system : System
        The model at the first value.
    param : str
    rows : list of dict
        One per value: ``param``'s value, ``status``, ``regime``, ``sticks`` and
        ``reversals`` after ``t_discard``, ``<state>_min``/``<state>_max`` over the
        kept window and ``<state>_final`` for every state of the model.
    t_end, t_discard, dt : float
    n_cached : int
        Rows read from the cache.

    See Also
    --------
    sweep : makes it.
    """

    system: System
    param: str
    rows: list[dict]
    t_end: float
    t_discard: float
    dt: float
    n_cached: int = 0

    @property
    def columns(self) -> list[str]:
        return list(self.rows[0]) if self.rows else []

    def __repr__(self) -> str:
        regimes = ", ".join(f"{r[self.param]:g}: {r['regime']}" for r in self.rows)
        return f"Sweep({self.system.name}, {self.param}; {regimes})"

    def as_dict(self) -> dict:
        """Plain JSON values: the model, the swept parameter, the rows and the unit of
        each column that has one (``units``, `Sweep.units`)."""
        return {
            **self.system.as_dict(without=self.param),
            "param": self.param,
            "t_end": self.t_end,
            "t_discard": self.t_discard,
            "dt": self.dt,
            "rows": self.rows,
            "units": self.units,
            "n_points": len(self.rows),
            "n_cached": self.n_cached,
        }

    @property
    def units(self) -> dict[str, str]:
        """The unit of each column that has one: the swept parameter's (the module's
        ``UNITS``) and each state's columns (the module's ``STATE_UNITS``,
        `beltmdsm.state_names.module_units`)."""
        out = {self.param: self.system.module.UNITS[self.param]}
        for state, unit in zip(self.system.states, self.system.units):
            out.update({f"{state}_{k}": unit for k in ("min", "max", "final")})
        return {c: out[c] for c in self.columns if c in out}

    def to_csv(self, path: os.PathLike | str, units: bool = False) -> None:
        """The rows as CSV, a ``model`` column first (the model's name on every row);
        with ``units``, each header that has a unit (`Sweep.units`) as ``name [unit]``."""
        with open(path, "w", newline="") as fh:
            w = csv.writer(fh)
            shown = self.units if units else {}
            w.writerow(["model", *(f"{c} [{shown[c]}]" if c in shown else c for c in self.columns)])
            for row in self.rows:
                w.writerow([self.system.name, *(_cell(v) for v in row.values())])


def _cell(value):
    return repr(value) if isinstance(value, float) else value


def sweep(
    system: System,
    param: str,
    values: ArrayLike,
    *,
    t_end: float = 200.0,
    t_discard: float | None = None,
    dt: float = 0.02,
    y0: ArrayLike | None = None,
    executor: Executor | None = None,
    rtol: float = 1e-10,
    atol: float = 1e-10,
    cache: _Cache | None = None,
) -> Sweep:
    """A run of ``system`` for each value of ``param`` (module docstring).

    Parameters
    ----------
    system : System
    param : str
        One of ``system.params``.
    values : array_like
        The values, run in ascending order (duplicates once).
    t_end, dt : float
        Each run's length and sampling step [s], > 0.
    t_discard : float, optional
        The transient left out of each row [s], in ``[0, t_end)``; half of ``t_end``
        by default.
    y0 : array_like (2n,), optional
        Every run's start (rest by default).
    executor : concurrent.futures.Executor, optional
        Where the points run (None: here, one after another).
    rtol, atol : float
    cache : object with get(ident) and put(ident, row), optional
        Rows already computed, by the point's identity (its model, law, parameters and
        settings): ``get`` each point before running it and ``put`` each new row (the
        command line passes one on the sweeps' disk cache, beltmdsm/batch/cache.py).

    Returns
    -------
    Sweep

    Raises
    ------
    ValueError
        An unknown parameter (the model's listed), no values, a value outside the
        parameter's domain (from `System`), ``t_discard`` outside ``[0, t_end)``.

    See Also
    --------
    beltmdsm.oscillator.simulate : one run.

    Examples
    --------
    >>> from beltmdsm.oscillator import System
    >>> s = System("belt_1dof", friction="stribeck")
    >>> result = sweep(s, "Vb", [1.5, 3.0], t_end=60.0)
    >>> [(r["Vb"], r["regime"]) for r in result.rows]
    [(1.5, 'stick_slip'), (3.0, 'slip')]
    """
    if param not in system.params:
        raise ValueError(
            f"param={param!r}: not a parameter of model {system.name!r} "
            f"({', '.join(system.params)})"
        )
    values = np.unique(np.asarray(values, dtype=float).ravel())
    if values.size == 0 or not np.all(np.isfinite(values)):
        raise ValueError("values: give at least one finite number")
    t_discard = 0.5 * t_end if t_discard is None else t_discard
    if not (0 <= t_discard < t_end):
        raise ValueError(f"t_discard={t_discard!r}: not in [0, t_end = {t_end:g})")
    systems = [system.replace(**{param: float(v)}) for v in values]  # checked here, once
    # a module not registered (made at run time) runs here only: a worker rebuilds the
    # System from a registered model's name
    jobs = [
        (s.module if executor is None else s.name, s.friction, dict(s.params), param,
         float(t_end), float(t_discard), float(dt),
         None if y0 is None else [float(v) for v in np.asarray(y0, dtype=float)], rtol, atol)
        for s in systems
    ]  # fmt: skip
    rows: list[dict | None] = [None] * len(jobs)
    if cache is not None:
        rows = [cache.get(_identity(job)) for job in jobs]
    todo = [i for i, row in enumerate(rows) if row is None]
    if executor is None:
        done = [_row(*jobs[i]) for i in todo]
    else:
        done = list(executor.map(_row, *zip(*(jobs[i] for i in todo)))) if todo else []
    for i, row in zip(todo, done):
        rows[i] = row
        if cache is not None:
            cache.put(_identity(jobs[i]), row)
    result = Sweep(systems[0], param, rows, float(t_end), float(t_discard), float(dt))
    result.n_cached = len(jobs) - len(todo)
    return result


def _identity(job) -> dict:
    """What a point's row depends on, as plain JSON values (the cache's key)."""
    names = ("model", "friction", "params", "param", "t_end", "t_discard", "dt", "y0")
    ident = {**dict(zip(names, job)), "rtol": job[8], "atol": job[9]}
    return {**ident, "model": getattr(job[0], "NAME", job[0])}


def _row(name, friction, params, param, t_end, t_discard, dt, y0, rtol, atol) -> dict:
    """One point: built in the worker from plain values (a `System` holds a module), or
    here from the model's module."""
    system = System(name, friction, **params)
    run = simulate(system, t_end, y0, dt=dt, rtol=rtol, atol=atol)
    keep = run.t >= t_discard
    late = [(b, a) for t, b, a in run.switches if t >= t_discard]
    sticks = sum(1 for _, a in late if a == STICK)
    reversals = sum(1 for b, a in late if {b, a} == {1, -1})
    row: dict = {param: params[param], "status": run.status}
    still = True
    for j, state in enumerate(system.states):
        kept = run.y[j, keep]
        lo, hi = float(kept.min()), float(kept.max())
        row[f"{state}_min"], row[f"{state}_max"] = lo, hi
        still &= hi - lo <= _STILL * (1.0 + max(abs(lo), abs(hi)))
    for j, state in enumerate(system.states):
        row[f"{state}_final"] = float(run.y[j, -1])
    if sticks:
        regime = "stick_slip"
    elif still and not late:
        regime = "steady_sliding"
    elif reversals:
        regime = "slip_reversal"
    else:
        regime = "slip"
    row.update(regime=regime, sticks=sticks, reversals=reversals)
    return row
