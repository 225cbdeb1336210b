"""Friction against relative velocity (Fig. 3b) and friction modulation (Figs. 10-12).

The friction force is the tangential force of the belt on the mass per unit mass,
``-mu_s sgn(Vr) Fn`` while sliding (positive along the belt, i.e. forward when the
mass is slower than the belt), the holding force while sticking, zero in flight.
The effective friction coefficient of a cycle is ``mu_eff = <F_f> / <F_n>`` over
that cycle (the steady sliding value is mu_s); with Eq. (23)'s sign convention
(the sign of Vr) the paper's mu_bar is ``-mu_eff``.
Cycle averages are integrals of the trajectory, split at every switch, not sums of
samples.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from ..integrate.trajectory import Trajectory
from ..settings import SolverSettings
from ..state_names import rate_row

__all__ = ["friction_loop", "cycle_averages", "modulation_scatter", "Simulated"]


class Simulated(Protocol):
    """What these analyses read of a run (`beltmdsm.simulation.Simulation` has it).

    Attributes
    ----------
    params : mapping
        The model's parameters.
    trajectory : beltmdsm.integrate.trajectory.Trajectory
        The run's trajectory.
    settings : SolverSettings
        The run's settings (the steady window).

    See Also
    --------
    beltmdsm.simulation.Simulation : the run that has them.

    Examples
    --------
    >>> from beltmdsm import Model, simulate
    >>> sim = simulate(Model(Vb=4.0), t_end=40.0, t_discard=10.0)
    >>> sim.params["Vb"], sim.trajectory.t_end, sim.settings.window_start
    (4.0, 40.0, 10.0)
    """

    @property
    def params(self) -> Mapping[str, float]: ...

    @property
    def trajectory(self) -> Trajectory: ...

    @property
    def settings(self) -> SolverSettings: ...


def friction_loop(
    sim: Simulated, period: float | None = None, t_stop: float | None = None, n: int = 2000
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Friction force against relative velocity over one period (Fig. 3b).

    Parameters
    ----------
    sim : beltmdsm.simulation.Simulation
    period : float, optional
        default ``2 pi / omega1`` as in Fig. 3b
    t_stop : float, optional
        end of the period shown; default the end of the run
    n : int
        the number of points

    Returns
    -------
    t, Vr, friction : ndarray (n,)
        times [s], relative velocity ``X1' - Vb`` [m/s], friction force per unit mass
        [m/s^2]

    Raises
    ------
    ValueError
        Where ``period`` is not positive or does not fit in the run before ``t_stop``.

    See Also
    --------
    beltmdsm.simulation.Simulation.plot : draws it (``kind="friction"``).

    Examples
    --------
    >>> from beltmdsm import Model, simulate
    >>> sim = simulate(Model(Vb=4.0), t_end=40.0, t_discard=10.0)
    >>> t, vr, friction = friction_loop(sim)  # the last 2 pi / omega1 of the run
    >>> t.shape, round(float(t[-1] - t[0]), 4)
    ((2000,), 6.2832)
    >>> bool(vr.min() < 0 < vr.max())  # the friction reverses
    True
    """
    period = 2 * np.pi / sim.params["omega1"] if period is None else float(period)
    t_stop = sim.trajectory.t_end if t_stop is None else float(t_stop)
    if not (period > 0 and t_stop - period >= sim.trajectory.segments[0].t0):
        raise ValueError(
            f"period={period!r} must be > 0 and fit in the run before t_stop={t_stop!r}"
        )
    t = np.linspace(t_stop - period, t_stop, n)
    y = sim.trajectory.state(t)
    _, friction = sim.trajectory.forces(t, y)
    return t, y[rate_row(sim.model)] - sim.params["Vb"], friction


def cycle_averages(
    sim: Simulated, period: float, t_start: float | None = None
) -> dict[str, NDArray[np.float64]]:
    """Mean friction and normal force over consecutive cycles of ``period``.

    Cycles start at the first multiple of ``period`` after ``t_start`` (default the
    start of the steady window), so they keep a fixed phase to the excitation.

    Parameters
    ----------
    sim : beltmdsm.simulation.Simulation
    period : float
        the cycle's length [s]
    t_start : float, optional
        where the cycles may start [s]

    Returns
    -------
    dict of arrays: ``t0`` (cycle starts), ``friction``, ``normal_force``, ``mu_eff``

    Raises
    ------
    ValueError
        Where ``period`` is not positive, or no full cycle fits (naming the times).

    See Also
    --------
    modulation_scatter : their mean and scatter over the steady window.

    Examples
    --------
    Cycles of the excitation period 2 pi / 4 s from the first multiple after 10 s:

    >>> import math
    >>> from beltmdsm import Model, simulate
    >>> sim = simulate(Model(Vb=4.0), t_end=40.0, t_discard=10.0)
    >>> cycles = cycle_averages(sim, 2 * math.pi / 4.0)
    >>> sorted(cycles), cycles["t0"].size
    (['friction', 'mu_eff', 'normal_force', 't0'], 18)
    >>> round(float(cycles["t0"][0]), 4)  # 7 periods
    10.9956
    """
    if not period > 0:
        raise ValueError(f"period must be > 0; got {period!r}")
    t_start = sim.settings.window_start if t_start is None else float(t_start)
    first = np.ceil(t_start / period - 1e-12) * period
    count = int(np.floor((sim.trajectory.t_end - first) / period + 1e-9))
    if count < 1:
        raise ValueError(
            f"no full cycle of {period:.6g} s fits between t = {t_start:.6g} s and the "
            f"end t = {sim.trajectory.t_end:.6g} s (cycles start at multiples of the "
            f"period, the first at t = {first:.6g} s; lengthen t_end)"
        )
    edges = first + period * np.arange(count + 1)
    traj = sim.trajectory

    def integrand(t, y, mode):
        Fn, friction = traj.forces(t, y, mode)
        return np.stack([friction, Fn])

    F, N = traj.integrate(integrand, edges) / period
    return {"t0": edges[:-1], "friction": F, "normal_force": N, "mu_eff": F / N}


def modulation_scatter(sim: Simulated) -> dict[str, float]:
    """Effective friction averaged over 2 pi/Omega_t and over 2 pi/omega1 (Figs. 10-12).

    Returns a dict with, for each averaging period, the mean of ``mu_eff`` over the
    cycles of the steady window and its scatter (standard deviation and range). Where
    no full cycle of a period fits in the steady window, its three numbers are NaN and
    ``"modulation_error"`` says why (the run and the other period are kept).

    Parameters
    ----------
    sim : beltmdsm.simulation.Simulation

    Returns
    -------
    dict of float
        ``mu_eff_{Omega,omega1}_{mean,std,range}`` (a period of 0 left out), and
        ``modulation_error`` where a period did not fit.

    See Also
    --------
    cycle_averages : the averages of each cycle.
    beltmdsm.batch.row.Row : the sweep columns that hold them.

    Examples
    --------
    >>> from beltmdsm import Model, simulate
    >>> sim = simulate(Model(Vb=4.0), t_end=40.0, t_discard=10.0)
    >>> scatter = modulation_scatter(sim)
    >>> sorted(scatter)  # doctest: +NORMALIZE_WHITESPACE
    ['mu_eff_Omega_mean', 'mu_eff_Omega_range', 'mu_eff_Omega_std',
     'mu_eff_omega1_mean', 'mu_eff_omega1_range', 'mu_eff_omega1_std']
    >>> round(scatter["mu_eff_Omega_mean"], 3)  # above mu_s = 0.4
    0.486
    """
    out, missing = {}, []
    for tag, omega in (("Omega", sim.params["Omega_t"]), ("omega1", sim.params["omega1"])):
        if omega <= 0:
            continue
        try:
            mu = cycle_averages(sim, 2 * np.pi / omega)["mu_eff"]
        except ValueError as err:
            for stat in ("mean", "std", "range"):
                out[f"mu_eff_{tag}_{stat}"] = float("nan")
            missing.append(f"mu_eff over 2pi/{tag}: {err}")
            continue
        out[f"mu_eff_{tag}_mean"] = float(mu.mean())
        out[f"mu_eff_{tag}_std"] = float(mu.std())
        out[f"mu_eff_{tag}_range"] = float(mu.max() - mu.min())
    if missing:
        out["modulation_error"] = "; ".join(missing)
    return out
