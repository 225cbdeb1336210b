"""The simulated evidence of the paper check: two runs under one normal motion (Fig. 2b).

``python -m derive check-paper`` re-derives the paper's claims with SymPy (derive/
paper_check/); two of them also need the simulation of Eq. (4), and this study gives
them its numbers (the command line hands `paper_evidence` to the check, so that
derive/ never imports the runtime):

* whether the omega1 peak of Fig. 2b is a self-excited vibration under each tension
  law: a second run started away from the first (`SHIFT` in ``(X1, X1')``) keeps its
  distance (a free phase) or converges to it (a forced response), and the sign of
  the contact force at the friction reversals;
* the numerical side of derive/contraction.py: the energy ``E_d`` of the difference of
  the two runs (`beltmdsm.generated.contraction.difference_energy`) and its balance, split by
  the sign of the contact force.

`difference_runs`, `difference_works` and `reversals_by_force_sign` are the tools.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cache
from typing import Any

import numpy as np
from numpy.typing import NDArray

from beltmdsm.generated import contraction

from ..excitation import initial_state
from ..integrate.switching import Mode
from ..model import Model
from ..run.summary import PEAK_PRESENT_RATIO
from ..settings import SolverSettings
from ..simulation import Simulation, simulate

__all__ = [
    "DifferenceRun",
    "Evidence",
    "difference_runs",
    "difference_works",
    "reversals_by_force_sign",
    "paper_evidence",
    "VB",
    "T_END",
    "SHIFT",
]

#: The simulated claims: the base set at the Fig. 3 belt speed, 1000 s runs, and the
#: tangential offset of the second run of each pair.
VB = 4.0
T_END = 1000.0
SHIFT = (5.0, -3.0)


@dataclass
class DifferenceRun:
    """Two runs with one normal motion and different tangential initial states.

    ``a`` starts at the default state (Eq. 9 at rest), ``b`` at the same normal state
    with ``(X1, X1')`` shifted by ``shift``; ``energy`` is
    `beltmdsm.generated.contraction.difference_energy` at the samples ``t`` of both runs.

    Attributes
    ----------
    a, b : beltmdsm.simulation.Simulation
        the two runs
    shift : (float, float)
        ``(dX1, dX1')`` of ``b``'s initial state from ``a``'s
    t : ndarray
        the samples' times [s]
    energy : ndarray
        ``E_d`` at each sample

    See Also
    --------
    beltmdsm.paper_reports.contraction_evidence.difference_runs : what builds it.

    Examples
    --------
    Both runs see one normal motion, bit for bit; ``E_d`` starts at 17 for the shift
    ``(5, -3)``:

    >>> run = difference_runs((5.0, -3.0), Vb=4.0, t_end=20.0)
    >>> run
    DifferenceRun(shift=(5.0, -3.0))
    >>> bool((run.a.y[2] == run.b.y[2]).all()), round(float(run.energy[0]), 6)
    (True, 17.0)
    """

    a: Simulation = field(repr=False)
    b: Simulation = field(repr=False)
    shift: tuple[float, float]
    t: NDArray[np.float64] = field(repr=False)
    energy: NDArray[np.float64] = field(repr=False)


def difference_runs(
    shift: tuple[float, float] = SHIFT, model: Model | None = None, **kw: Any
) -> DifferenceRun:
    """Simulate Eq. (4) twice under one normal motion (`beltmdsm.simulate`).

    Parameters
    ----------
    shift : (dX1, dX1')
        Tangential offset of run ``b``'s initial state from run ``a``'s.
    model : Model, optional
    **kw
        Parameters, options and solver settings for both runs (``Vb=4``,
        ``tension="clipped"``, ``rtol=1e-10``). The solver is the superposition
        integrator unless given: it integrates the normal motion once, so both runs
        see the same ``F(t)``, bit for bit, as the argument has it.

    Returns
    -------
    DifferenceRun

    See Also
    --------
    beltmdsm.paper_reports.contraction_evidence.difference_works : the energy balance of
        the difference.
    beltmdsm.simulation.simulate : each run.

    Examples
    --------
    A 20 s pair at 4 m/s, the second run shifted by ``(5, -3)``: 1001 samples each,
    the normal states equal throughout:

    >>> run = difference_runs((5.0, -3.0), Vb=4.0, t_end=20.0)
    >>> run.a.solver_used, run.t.size
    ('superposition', 1001)
    >>> float(abs(run.a.y[2] - run.b.y[2]).max())
    0.0
    """
    settings = {k: kw.pop(k) for k in list(kw) if k in SolverSettings.names()}
    settings.setdefault("solver", "superposition")
    model = Model.from_mapping(None, **kw) if model is None else model.replace(**kw)
    y0 = initial_state(model)
    y0b = [y0[0] + shift[0], y0[1] + shift[1], y0[2], y0[3]]
    a = simulate(model, **settings)
    b = simulate(model, y0=y0b, **settings)
    energy = _energy(model, a.y[0] - b.y[0], a.y[1] - b.y[1])
    return DifferenceRun(a, b, tuple(shift), a.t, np.asarray(energy, dtype=float))


def _energy(model, e, e_dot):
    return contraction.difference_energy(e, e_dot, **model.arguments(contraction.difference_energy))


def _force_zeros(sim, t0, t1):
    """Times in (t0, t1) where the run's normal force changes sign, to 1e-13 s."""
    t, F = sim.t, sim.normal_force
    keep = (t >= t0) & (t <= t1)
    t, F = t[keep], F[keep]
    k = np.flatnonzero(np.sign(F[:-1]) * np.sign(F[1:]) < 0)
    lo, hi = t[k].copy(), t[k + 1].copy()
    s_lo = np.sign(F[k])
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        same = np.sign(sim.trajectory.forces(mid)[0]) == s_lo
        lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
    return 0.5 * (lo + hi)


def difference_works(
    run: DifferenceRun, t0: float | None = None, t1: float | None = None
) -> dict[str, float]:
    """The energy balance of the difference over ``[t0, t1]`` by quadrature.

    ``dE_d/dt = -c1 e'^2 + (f_a - f_b) e'`` (derive/contraction.py; ``c1`` from
    `beltmdsm.generated.contraction.difference_damping`, ``f`` the friction force of each run,
    `beltmdsm.integrate.trajectory.Trajectory.forces`: ``-mu s F`` with ``s`` in Sgn,
    the holding force in stick and 0 without contact). Integrated with
    `Trajectory.integrate` (Gauss-Legendre on the pieces of run ``a``, split at run
    ``b``'s switches and knots and at the sign changes of ``F``).

    Returns
    -------
    dict
        ``energy_change`` (``E_d(t1) - E_d(t0)`` from the states), ``work_viscous``
        (``-int c1 e'^2``), ``work_friction_push`` and ``work_friction_pull`` (the
        friction part while ``F >= 0`` and while ``F < 0``), ``imbalance``
        (change minus the three works) and ``scale`` (the integral of the absolute
        values of both parts, for tolerances).

    See Also
    --------
    beltmdsm.paper_reports.contraction_evidence.difference_runs : the two runs.

    Examples
    --------
    The change of ``E_d`` over 20 s equals the three works to within 1e-9 of their
    scale (the quadrature's error, not a tolerance of the physics):

    >>> w = difference_works(difference_runs((5.0, -3.0), Vb=4.0, t_end=20.0))
    >>> sorted(w)  # doctest: +NORMALIZE_WHITESPACE
    ['energy_change', 'imbalance', 'scale', 'work_friction_pull', 'work_friction_push',
     'work_viscous']
    >>> bool(abs(w["imbalance"]) < 1e-9 * w["scale"]), w["work_viscous"] < 0
    (True, True)
    """
    a, b = run.a.trajectory, run.b.trajectory
    model = run.a.model
    t0 = a.segments[0].t0 if t0 is None else t0
    t1 = min(a.t_end, b.t_end) if t1 is None else t1
    c1 = float(contraction.difference_damping(**model.arguments(contraction.difference_damping)))
    cuts = [np.array([t0, t1]), _force_zeros(run.a, t0, t1)]
    for s in b.segments:
        cuts.append(np.concatenate([[s.t0, s.t1], s.knots]))
    edges = np.unique(np.concatenate(cuts))
    edges = edges[(edges >= t0) & (edges <= t1)]

    def powers(t, y, mode):
        F, fa = a.forces(t, y, mode)
        yb = b.state(t)
        _, fb = b.forces(t, yb, b.mode(t))
        de = y[1] - yb[1]
        visc = -c1 * de**2
        fric = (fa - fb) * de
        push = np.where(F >= 0, fric, 0.0)
        pull = np.where(F < 0, fric, 0.0)
        return np.stack([visc, push, pull, np.abs(visc) + np.abs(fric)])

    W = a.integrate(powers, edges).sum(axis=1)
    ends = (np.array([t0]), np.array([t1]))
    E0, E1 = (float(_energy(model, *(a.state(t)[:2, 0] - b.state(t)[:2, 0]))) for t in ends)
    change = E1 - E0
    return {
        "energy_change": change,
        "work_viscous": float(W[0]),
        "work_friction_push": float(W[1]),
        "work_friction_pull": float(W[2]),
        "imbalance": change - float(W[0] + W[1] + W[2]),
        "scale": float(W[3]),
    }


def reversals_by_force_sign(sim: Simulation, t0: float = 0.0) -> dict[str, tuple[int, int]]:
    """Reversals of the friction after ``t0`` by their new direction and the sign of ``F``.

    A reversal is a ``"vr_zero"`` event of ``sim.events`` whose new mode is a slip mode
    (`beltmdsm.run.summary.summarize` counts them the same way); ``F`` is the normal
    force at its time (``sim.trajectory.forces``).

    Returns
    -------
    dict
        ``{"slip_forward": (n with F < 0, n with F >= 0), "slip_back": (...)}``.

    See Also
    --------
    beltmdsm.run.summary.summarize : counts the reversals of a run.

    Examples
    --------
    Over the last 10 s of a 20 s run at 4 m/s (tension allowed), every reversal to
    forward slip comes while the contact force pulls (``F < 0``), every one back while
    it pushes:

    >>> from beltmdsm import simulate
    >>> reversals_by_force_sign(simulate(Model(Vb=4.0), t_end=20.0), 10.0)
    {'slip_forward': (4, 0), 'slip_back': (0, 4)}
    """
    out = {}
    for name, mode in (("slip_forward", Mode.SLIP_FORWARD), ("slip_back", Mode.SLIP_BACK)):
        times = np.array(
            [t for t, kind, new in sim.events if kind == "vr_zero" and new == mode and t >= t0]
        )
        F = sim.trajectory.forces(times)[0] if times.size else np.array([])
        out[name] = (int(np.sum(F < 0)), int(np.sum(F >= 0)))
    return out


@dataclass(frozen=True)
class Evidence:
    """What the paper check reads of the two runs under one tension law.

    ``peak_ratio`` is peak_omega1 / peak_Omega of run ``a`` and ``present`` its
    verdict (threshold ``threshold``); ``energy_start``, ``energy_end`` and
    ``largest_rise`` describe ``E_d`` over the run (the largest increase between two
    samples); ``works`` is `difference_works`, ``reversals`` `reversals_by_force_sign`
    in the steady window.

    See Also
    --------
    beltmdsm.paper_reports.contraction_evidence.paper_evidence : builds one per tension
        law (1000 s runs).

    Examples
    --------
    Built by hand from a 20 s pair (the paper check's runs last 1000 s):

    >>> run = difference_runs((5.0, -3.0), Vb=4.0, t_end=20.0)
    >>> e = Evidence("allowed", 4.0, 20.0, run.shift, 0.1, 0.0, False,
    ...              float(run.energy[0]), float(run.energy[-1]), 0.0,
    ...              difference_works(run), reversals_by_force_sign(run.a, 10.0))
    >>> e.tension, round(e.energy_start, 6), e.reversals["slip_back"]
    ('allowed', 17.0, (0, 4))
    """

    tension: str
    vb: float
    t_end: float
    shift: tuple[float, float]
    threshold: float
    peak_ratio: float
    present: bool
    energy_start: float
    energy_end: float
    largest_rise: float
    works: dict[str, float]
    reversals: dict[str, tuple[int, int]]


@cache
def paper_evidence() -> dict[str, Evidence]:
    """Per tension law, the `Evidence` of the paper check (the base set at ``Vb = 4``)."""
    out = {}
    for tension in ("allowed", "clipped"):
        run = difference_runs(SHIFT, Model(Vb=VB, tension=tension), t_end=T_END)
        s, E = run.a.summary, run.energy
        out[tension] = Evidence(
            tension,
            VB,
            T_END,
            SHIFT,
            PEAK_PRESENT_RATIO,
            float(s.peak_omega1 / s.peak_Omega),
            bool(s.omega1_peak_present),
            float(E[0]),
            float(E[-1]),
            float((E[1:] - E[:-1]).max()),
            difference_works(run),
            reversals_by_force_sign(run.a, run.a.settings.window_start),
        )
    return out
