"""One point of a sweep: a run and the row it leaves (Fig. 2b), in one shape throughout.

`run_point` simulates one model from rest, from a given state (a continued sweep) or
from the periodic response (``start="periodic"``), and returns a `Row`. A `Row` is
what every later stage holds: the disk cache stores `Row.as_dict` and reads it back
with `Row.from_dict` (`beltmdsm.batch.cache`), the sweep's table stacks the rows
(`beltmdsm.batch.table.to_table`), and the table's records
(`beltmdsm.batch.table.records`) are the rows of ``sweep --json``, its CSV
(`beltmdsm.batch.table.table_to_csv`) and `beltmdsm.batch.sweep.Sweep.to_pandas`.
The columns, their numpy types and their conversions are defined here once: the
fields of `Row`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from ..errors import NoPeriodicResponse
from ..model import Model
from ..run.modulation import modulation_scatter
from ..settings import SolverSettings
from ..simulation import simulate
from ..starts.forced import periodic_start

__all__ = [
    "Row",
    "COLUMNS",
    "MODULATION_COLUMNS",
    "NO_PERIODIC_RESPONSE",
    "STARTS",
    "Start",
    "columns",
    "failed_row",
    "run_point",
]


def _column(dtype: str, **kw: Any) -> Any:
    """A field of `Row` that is a table column, with its numpy type."""
    return field(metadata={"dtype": dtype}, **kw)


#: The Python type each numpy kind of a column holds (`Row` converts to it, so that a
#: row is JSON-able as it is and equal after a round trip through the cache).
_PYTHON = {"U": str, "f": float, "i": int, "?": bool}


@dataclass(frozen=True)
class Row:
    """One point of a sweep: the columns of its table, and where a continued sweep goes on.

    The column fields, in table order after the swept parameter, are `COLUMNS`.
    ``omega1_peak_present`` is False where ``resolved`` is False (the run could not
    tell, `beltmdsm.run.summary.summarize`): read it together with ``resolved``, never
    alone as "no peak". ``forced_peak`` and ``noise_floor`` say whether a peak at an
    excitation frequency rose above what the tolerances can put into the spectrum,
    ``energy_ok`` whether the energy balance closed within its bound (False: the
    point's numbers are not trusted). ``error`` says what the point could not compute:
    empty where it computed everything; the reason where its run failed (``status``
    "failed", `failed_row`) or a part of it (the modulation of a period longer than
    the steady window: those columns NaN).

    ``modulation`` holds the `MODULATION_COLUMNS` where they were asked for (else
    None); ``restart_t`` and ``restart_state``, in a continued sweep, the last whole
    excitation period within the run and the state there (not table columns).

    Examples
    --------
    >>> row = Row.from_dict({name: 0 for name, _ in COLUMNS} | {"regime": "stick_slip"})
    >>> row.regime, row.peak_omega1, row.resolved
    ('stick_slip', 0.0, False)
    >>> Row.from_dict(row.as_dict()) == row
    True
    """

    regime: str = _column("U24")
    peak_omega1: float = _column("f8")
    omega1_peak_at: float = _column("f8")
    peak_Omega: float = _column("f8")
    noise_floor: float = _column("f8")
    forced_peak: bool = _column("?")
    omega1_peak_present: bool = _column("?")
    resolved: bool = _column("?")
    energy_residual: float = _column("f8")
    energy_ok: bool = _column("?")
    n_switches: int = _column("i8")
    n_reversals: int = _column("i8")
    n_sticks: int = _column("i8")
    n_contact_losses: int = _column("i8")
    min_normal_force: float = _column("f8")
    tension_fraction: float = _column("f8")
    mean_friction: float = _column("f8")
    vr_min: float = _column("f8")
    vr_max: float = _column("f8")
    tension: str = _column("U8")
    solver: str = _column("U16")
    status: str = _column("U16")
    wall_s: float = _column("f8")
    error: str = _column("U400", default="")
    modulation: Mapping[str, float] | None = field(default=None, compare=True)
    restart_t: float | None = None
    restart_state: tuple[float, ...] | None = None

    def __post_init__(self) -> None:
        for name, dtype in COLUMNS:
            object.__setattr__(self, name, _PYTHON[dtype[0]](getattr(self, name)))
        if self.modulation is not None:
            # a period that is not there (Omega_t = 0) has no cycles: NaN, as a period
            # longer than the window
            mod = {n: float(self.modulation.get(n, math.nan)) for n, _ in MODULATION_COLUMNS}
            object.__setattr__(self, "modulation", mod)
        if self.restart_state is not None:
            object.__setattr__(self, "restart_state", tuple(map(float, self.restart_state)))

    @classmethod
    def from_summary(cls, summary: Any, **extra: Any) -> Row:
        """The row of a run's `beltmdsm.run.summary.Summary` (``extra``: the other fields).

        An unresolved peak (``omega1_peak_present`` None) is stored as False beside
        ``resolved`` False: a bool column.
        """
        values = {name: getattr(summary, name) for name, _ in COLUMNS if name != "error"}
        values["omega1_peak_present"] = bool(summary.resolved and summary.omega1_peak_present)
        return cls(**values, **extra)

    @classmethod
    def empty(cls, model: Model, settings: SolverSettings, modulation: bool, **values: Any) -> Row:
        """A row without a run: NaN (0 for counts) in the numeric columns, the flags
        False, the model's tension and the settings' solver; ``values`` the rest."""
        row = {name: 0 if dtype == "i8" else math.nan for name, dtype in COLUMNS}
        row.update(forced_peak=False, omega1_peak_present=False, resolved=False, energy_ok=False)
        row.update(tension=model.tension, solver=settings.solver, **values)
        mod = {name: math.nan for name, _ in MODULATION_COLUMNS} if modulation else None
        return cls(**row, modulation=mod)

    def as_dict(self) -> dict[str, Any]:
        """The row as plain JSON values, flat: the columns, the modulation columns where
        computed, ``restart_t`` and ``restart_state`` where set (what the cache stores)."""
        out = {name: getattr(self, name) for name, _ in COLUMNS}
        out.update(self.modulation or {})
        if self.restart_t is not None:
            out["restart_t"] = self.restart_t
        if self.restart_state is not None:
            out["restart_state"] = list(self.restart_state)
        return out

    def record(self, modulation: bool) -> tuple[Any, ...]:
        """The row's values in the order of `columns` (``modulation``: with the
        `MODULATION_COLUMNS`, NaN where not computed): a record of the sweep's table.

        Examples
        --------
        >>> row = Row.from_dict({name: 0 for name, _ in COLUMNS} | {"regime": "stick_slip"})
        >>> row.record(False)[:3], len(row.record(True))
        (('stick_slip', 0.0, 0.0), 30)
        """
        mod = self.modulation or {}
        return (
            *(getattr(self, name) for name, _ in COLUMNS),
            *(mod.get(name, math.nan) for name, _ in (MODULATION_COLUMNS if modulation else ())),
        )

    def json_row(self, param: str, value: float, modulation: bool) -> dict[str, Any]:
        """The row of ``sweep --json``: ``param`` (``value``) first, then `columns`,
        NaN and infinity as None (JSON has neither).

        Examples
        --------
        >>> row = Row.from_dict({name: 0 for name, _ in COLUMNS} | {"wall_s": float("nan")})
        >>> out = row.json_row("Vb", 4.0, False)
        >>> list(out)[:3], out["wall_s"]
        (['Vb', 'regime', 'peak_omega1'], None)
        """
        names = (param, *(name for name, _ in columns(modulation)))
        return dict(zip(names, map(_json, (float(value), *self.record(modulation)))))

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> Row:
        """The row of `as_dict`'s values (the modulation columns where all are there).

        Raises
        ------
        KeyError
            Naming the columns that ``data`` lacks.
        """
        missing = [name for name, _ in COLUMNS if name not in data]
        if missing:
            raise KeyError(f"a row lacks {', '.join(missing)}")
        mod = [name for name, _ in MODULATION_COLUMNS]
        return cls(
            **{name: data[name] for name, _ in COLUMNS},
            modulation={n: data[n] for n in mod} if all(n in data for n in mod) else None,
            restart_t=data.get("restart_t"),
            restart_state=data.get("restart_state"),
        )


#: The table's columns after the swept parameter, with their numpy types: the column
#: fields of `Row`, in order.
COLUMNS: tuple[tuple[str, str], ...] = tuple(
    (f.name, f.metadata["dtype"]) for f in fields(Row) if "dtype" in f.metadata
)
MODULATION_COLUMNS = tuple(
    (f"mu_eff_{tag}_{stat}", "f8")
    for tag in ("Omega", "omega1")
    for stat in ("mean", "std", "range")
)
#: The regime of a point started on the periodic response where none is found.
NO_PERIODIC_RESPONSE = "no_periodic_response"
#: Where a (not continued) run starts: the unforced equilibrium, or the periodic
#: response moved by `beltmdsm.starts.forced.PERTURBATION` in X1.
STARTS = ("rest", "periodic")
Start = Literal["rest", "periodic"]


def columns(modulation: bool) -> tuple[tuple[str, str], ...]:
    """The row's columns and their numpy types.

    Parameters
    ----------
    modulation : bool
        Whether the friction modulation columns (`MODULATION_COLUMNS`) follow.

    Returns
    -------
    tuple of (str, str)

    See Also
    --------
    Row : whose fields they are.

    Examples
    --------
    >>> columns(False)[:2]
    (('regime', 'U24'), ('peak_omega1', 'f8'))
    >>> len(columns(False)), len(columns(True))
    (24, 30)
    """
    return COLUMNS + (MODULATION_COLUMNS if modulation else ())


def run_point(
    model: Model,
    settings: SolverSettings,
    modulation: bool = False,
    *,
    y0: ArrayLike | None = None,
    restart_period: float | None = None,
    start: Start = "rest",
) -> Row:
    """One sweep point: its run's `Row`.

    Parameters
    ----------
    model : Model
    settings : SolverSettings
    modulation : bool
        add the friction modulation columns (`beltmdsm.run.modulation`)
    y0 : sequence of 4 floats, optional
        start state (default: from rest, `beltmdsm.excitation.initial_state`)
    restart_period : float, optional
        the excitation period ``T`` (`beltmdsm.excitation.excitation_period`); the row then
        also holds ``restart_t``, the last multiple of ``T`` within the run, and
        ``restart_state``, the state there (where a continued sweep starts its next
        point; not table columns).
    start : {"rest", "periodic"}
        where no periodic response is found the row has the regime
        `NO_PERIODIC_RESPONSE`, ``resolved`` False, ``status`` "no_periodic" and NaN
        (or 0) in the numeric columns: the point cannot be run, and never counts as a
        point without the peak.

    Returns
    -------
    Row

    Raises
    ------
    ValueError, ArithmeticError, RuntimeError
        Those of `beltmdsm.simulate` (a sweep makes them a `failed_row`).

    See Also
    --------
    beltmdsm.sweep : a point for each value of one parameter.

    Examples
    --------
    >>> from beltmdsm import Model, SolverSettings
    >>> short = SolverSettings(t_end=40.0, t_discard=10.0)
    >>> row = run_point(Model(Vb=4.0), short, restart_period=1.5)
    >>> row.regime, row.status, row.error
    ('sliding_with_reversals', 'done', '')
    >>> row.restart_t, len(row.restart_state)  # the last multiple of 1.5 s
    (39.0, 4)
    """
    if start == "periodic":
        try:
            y0 = periodic_start(model, backend=settings.backend)
        except NoPeriodicResponse as err:
            return Row.empty(
                model,
                settings,
                modulation,
                regime=NO_PERIODIC_RESPONSE,
                energy_ok=True,  # nothing was integrated: no balance to fail
                status="no_periodic",
                error=_one_field(str(err)),
            )
    sim = simulate(model, settings=settings, y0=y0)
    extra: dict[str, Any] = {}
    if modulation:
        scatter = modulation_scatter(sim)
        extra["error"] = _one_field(scatter.pop("modulation_error", ""))
        extra["modulation"] = scatter
    if restart_period is not None:
        t_end = sim.trajectory.t_end
        # the last whole period; 1e-9 forgives the rounding of t_end / T at a multiple
        t_k = min(math.floor(t_end / restart_period + 1e-9) * restart_period, t_end)
        extra["restart_t"] = t_k
        extra["restart_state"] = sim.trajectory.state(np.array([t_k]))[:, 0]
    return Row.from_summary(sim.summary, **extra)


def _json(value: Any) -> Any:
    """``value`` as JSON holds it: a float that is not finite as None."""
    return None if isinstance(value, float) and not math.isfinite(value) else value


def _one_field(text: str) -> str:
    """``text`` as one CSV field that `beltmdsm.batch.table.table_from_csv` reads
    back (numpy's reader splits at every comma, quoted or not)."""
    return " ".join(str(text).replace(",", ";").split())[:400]


def failed_row(model: Model, settings: SolverSettings, modulation: bool, err: Exception) -> Row:
    """The row of a point whose run failed: ``status`` "failed", ``error`` the reason,
    NaN (or 0) in the numeric columns, ``resolved`` False (it never counts as a point
    without the peak).

    Parameters
    ----------
    model, settings : Model, SolverSettings
        The point's.
    modulation : bool
        Whether the row holds the modulation columns (NaN).
    err : Exception
        Why the run failed.

    Returns
    -------
    Row

    See Also
    --------
    run_point : the row of a run.

    Examples
    --------
    >>> from beltmdsm import Model, SolverSettings
    >>> short = SolverSettings(t_end=40.0, t_discard=10.0)
    >>> row = failed_row(Model(), short, False, RuntimeError("stopped, at t = 3 s"))
    >>> row.status, row.resolved, row.n_switches, row.error  # one CSV field: no comma
    ('failed', False, 0, 'RuntimeError: stopped; at t = 3 s')
    """
    return Row.empty(
        model,
        settings,
        modulation,
        regime="failed",
        status="failed",
        error=_one_field(f"{type(err).__name__}: {err}"),
    )
