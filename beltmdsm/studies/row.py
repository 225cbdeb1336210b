"""One point of a sweep: a run and the row of numbers and strings it leaves (Fig. 2b).

`run_point` simulates one model from rest, from a given state (a continued sweep) or
from the periodic response (``start="periodic"``), and returns its `COLUMNS` as a
plain dict, the unit of the sweep cache (`beltmdsm.studies.cache`).
"""

from __future__ import annotations

import math
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from ..errors import NoPeriodicResponse
from ..model import Model
from ..periodic.start import periodic_start
from ..run.modulation import modulation_scatter
from ..settings import SolverSettings
from ..simulation import simulate

__all__ = [
    "COLUMNS",
    "MODULATION_COLUMNS",
    "NO_PERIODIC_RESPONSE",
    "STARTS",
    "Start",
    "columns",
    "failed_row",
    "run_point",
]

#: The table's columns after the swept parameter. ``omega1_peak_present`` is False
#: where ``resolved`` is False (the run could not tell,
#: `beltmdsm.run.summary.summarize`): read it together with ``resolved``, never
#: alone as "no peak". ``forced_peak`` and ``noise_floor`` say whether a peak at an
#: excitation frequency rose above what the tolerances can put into the spectrum,
#: ``energy_ok`` whether the energy balance closed within its bound (False: the
#: point's numbers are not trusted). ``error`` says what the point could not compute:
#: empty where it computed everything; the reason where its run failed (``status``
#: "failed", `failed_row`) or a part of it (the modulation of a period longer than the
#: steady window: those columns NaN).
COLUMNS = (
    ("regime", "U24"),
    ("peak_omega1", "f8"),
    ("omega1_peak_at", "f8"),
    ("peak_Omega", "f8"),
    ("noise_floor", "f8"),
    ("forced_peak", "?"),
    ("omega1_peak_present", "?"),
    ("resolved", "?"),
    ("energy_residual", "f8"),
    ("energy_ok", "?"),
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
    ("error", "U400"),
)
MODULATION_COLUMNS = tuple(
    (f"mu_eff_{tag}_{stat}", "f8")
    for tag in ("Omega", "omega1")
    for stat in ("mean", "std", "range")
)
#: The regime of a point started on the periodic response where none is found.
NO_PERIODIC_RESPONSE = "no_periodic_response"
#: Where a (not continued) run starts: the unforced equilibrium, or the periodic
#: response moved by `beltmdsm.periodic.start.PERTURBATION` in X1.
STARTS = ("rest", "periodic")
Start = Literal["rest", "periodic"]


def columns(modulation: bool) -> tuple[tuple[str, str], ...]:
    """The row's columns and their numpy types."""
    return COLUMNS + (MODULATION_COLUMNS if modulation else ())


def run_point(
    model: Model,
    settings: SolverSettings,
    modulation: bool = False,
    *,
    y0: ArrayLike | None = None,
    restart_period: float | None = None,
    start: Start = "rest",
) -> dict[str, Any]:
    """One sweep point: the summary row (a plain dict of numbers and strings).

    Parameters
    ----------
    model : Model
    settings : SolverSettings
    modulation : bool
        add the friction modulation columns (`beltmdsm.run.modulation`)
    y0 : sequence of 4 floats, optional
        start state (default: from rest, `beltmdsm.model.initial_state`)
    restart_period : float, optional
        the excitation period ``T`` (`beltmdsm.model.excitation_period`); the row then
        also holds ``restart_t``, the last multiple of ``T`` within the run, and
        ``restart_state``, the state there (where a continued sweep starts its next
        point; not table columns).
    start : {"rest", "periodic"}
        where no periodic response is found the row has the regime
        `NO_PERIODIC_RESPONSE`, ``resolved`` False, ``status`` "no_periodic" and NaN
        (or 0) in the numeric columns: the point cannot be run, and never counts as a
        point without the peak.
    """
    if start == "periodic":
        try:
            y0 = periodic_start(model, backend=settings.backend)
        except NoPeriodicResponse as err:
            row = {name: 0 if kind == "i8" else float("nan") for name, kind in columns(modulation)}
            row.update(
                regime=NO_PERIODIC_RESPONSE,
                omega1_peak_present=False,
                resolved=False,
                forced_peak=False,
                energy_ok=True,  # nothing was integrated: no balance to fail
                tension=model.tension,
                solver=settings.solver,
                status="no_periodic",
                error=_one_field(str(err)),
            )
            return row
    sim = simulate(model, settings=settings, y0=y0)
    summary = sim.summary
    row = {name: getattr(summary, name) for name, _ in COLUMNS if name != "error"}
    row["error"] = ""
    # None (unresolved) is stored as False beside resolved = False: a bool column
    row["omega1_peak_present"] = bool(row["resolved"] and row["omega1_peak_present"])
    if modulation:
        row.update(modulation_scatter(sim))
        row["error"] = _one_field(row.pop("modulation_error", ""))
    if restart_period is not None:
        t_end = sim.trajectory.t_end
        # the last whole period; 1e-9 forgives the rounding of t_end / T at a multiple
        t_k = min(math.floor(t_end / restart_period + 1e-9) * restart_period, t_end)
        row["restart_t"] = float(t_k)
        row["restart_state"] = [float(x) for x in sim.trajectory.state(np.array([t_k]))[:, 0]]
    return row


def _one_field(text: str) -> str:
    """``text`` as one CSV field that `beltmdsm.studies.sweep.table_from_csv` reads back
    (numpy's reader splits at every comma, quoted or not)."""
    return " ".join(str(text).replace(",", ";").split())[:400]


def failed_row(model: Model, settings: SolverSettings, modulation: bool, err: Exception) -> dict:
    """The row of a point whose run failed: ``status`` "failed", ``error`` the reason,
    NaN (or 0) in the numeric columns, ``resolved`` False (it never counts as a point
    without the peak)."""
    row = {name: 0 if kind == "i8" else float("nan") for name, kind in columns(modulation)}
    row.update(
        regime="failed",
        omega1_peak_present=False,
        resolved=False,
        forced_peak=False,
        energy_ok=False,
        tension=model.tension,
        solver=settings.solver,
        status="failed",
        error=_one_field(f"{type(err).__name__}: {err}"),
    )
    return row
