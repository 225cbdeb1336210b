"""The consistent MDSM's unstable belt speeds: its damping scanned over ``Vb``.

`unstable_intervals` evaluates `beltmdsm.prediction.mdsm.consistent_mdsm_damping` on a
grid of belt speeds, continuing the fast motion from high ``Vb`` down, and refines
each change of sign: by ``brentq`` at a root of the damping, or at the onset of
friction reversal (`beltmdsm.prediction.mdsm.reversal_onset`), where the damping jumps.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import optimize

from .. import intervals
from ..arguments import count
from ..errors import Refused
from ..model import Model, as_model, require
from ..settings import MAX_VB_POINTS
from .mdsm import (
    _linear_without_reversal,
    _single_frequency,
    consistent_mdsm_damping,
    fast_motion,
    reversal_onset,
)
from .sliding import _unforced_edge

__all__ = [
    "unstable_intervals",
    "grid_note",
    "ONSET_STEP",
    "GRID_COARSE",
    "GRID_END",
]


def _check_grid(vb):
    vb = np.asarray(vb, dtype=float)
    if vb.ndim != 1 or vb.size < 2:
        raise ValueError(f"vb must be a 1-D grid of at least 2 belt speeds; got shape {vb.shape}")
    if vb.size > MAX_VB_POINTS:
        raise Refused(
            f"vb has {vb.size} belt speeds, more than MAX_VB_POINTS = {MAX_VB_POINTS:.0e} "
            "(beltmdsm/settings.py)",
            "points",
        )
    if not np.all(np.isfinite(vb)) or np.any(vb < 0):
        raise ValueError("vb must hold finite belt speeds >= 0")
    return vb


#: The grid gets a point this far below the linear amplitude ``V_lin``, relative, and
#: none between it and ``V_lin``: the damping there is that of the onset of reversal.
#: Closer to ``V_lin`` the harmonic balance can be singular: at the base set its
#: reversing solution keeps ``V - Vb = 2.1e-3 m/s`` up to ``V_lin`` (the damping tends
#: to -18.4), but where the excitation is at resonance (``Omega = omega1``) the
#: reversal vanishes as ``(V_lin - Vb)^2``, and within 1e-8 of ``V_lin`` it is below the
#: rounding of ``V`` (no solution can be resolved). At 1e-4 both are resolved (the
#: residual 7e-12 at resonance, 5e-16 at the base set), with the sign of their limits.
ONSET_STEP = 1e-4


def _check_points(points):
    points = count("points", points, 2)
    if points > MAX_VB_POINTS:
        raise Refused(
            f"points = {points} is more than MAX_VB_POINTS = {MAX_VB_POINTS:.0e} "
            "(beltmdsm/settings.py): up to 2 ms a point (6 ms under a law whose fast "
            "average is a quadrature), and every edge is "
            "refined to 1e-10 m/s anyway",
            "points",
        )


def unstable_intervals(
    model: Model | Mapping[str, Any] | None = None,
    *,
    vb: ArrayLike | None = None,
    points: int | np.integer = 400,
    progress: bool = False,
    vb_max: float | None = None,
    **kw: Any,
) -> tuple[list[tuple[float, float]], dict[str, NDArray[Any]]]:
    """Unstable belt speeds of the consistent MDSM.

    The damping is evaluated on a grid (continuation from high ``Vb`` down, where the
    friction does not reverse), and each change of sign is refined by bisection
    (``brentq``, to 1e-10 m/s) at a root of the damping; at the onset of friction
    reversal (`reversal_onset`: below it the friction reverses within a fast cycle,
    above it not, and the damping jumps) the edge is the onset itself: for Coulomb's
    law the linear amplitude ``V_lin`` in closed form.

    The edges are found on the grid with the onset and a point `ONSET_STEP` below it
    added (where they lie within the grid) and the grid's points between them left
    out (the balance may be singular there; in the table they hold the damping where
    it can be solved, else NaN), so that this edge is found on any grid, however
    coarse or fine: with 2 points the band of the base set is [4.682, 6.375], as with
    400 or 30000. An edge at a root
    of the damping is found wherever the damping changes sign between neighbours; a
    band narrower than the grid step (two roots between neighbours) can be missed,
    and a band that reaches the lowest point of the grid may extend below it
    (`predict` says so).

    Parameters
    ----------
    vb : array_like, optional
        the grid of belt speeds (at least 2, at most `MAX_VB_POINTS`, finite, >= 0);
        default: ``points`` speeds up to 1.05 times the onset of reversal; for a
        friction coefficient that varies in slip up to 1.05 times the onset plus the
        unforced critical belt speed (`beltmdsm.generated.unforced.critical_belt_speed`, where
        it is finite: above the onset the fast motion still sweeps the falling part
        of the law), doubled up to 3 times while a band reaches the top
    points : int
        size of the default grid (at least 2, at most `MAX_VB_POINTS`)
    progress : bool
        show a progress bar on stderr (tqdm) once the grid takes more than 2 s
    vb_max : float, optional
        the top of the grid instead of the default's (``vb`` not given): ``points``
        speeds up to it, and, where it lies above the default's top, the default grid
        below that too, so that a coarse grid keeps the default's resolution where the
        bands are (``--vb-max 3000``: a step of 7.5 m/s missed the base set's band
        [4.682, 6.375] entirely); `grid_note` says what the coarse part cannot resolve

    Returns
    -------
    intervals : list of (lower, upper)
        Unstable ranges of ``Vb`` within the grid (an end of the grid bounds a range
        that reaches it). Without excitation (no fast motion) and a coefficient
        constant in slip the list is empty and so is the default grid.
    table : dict of arrays
        ``Vb``, ``damping``, ``V``, ``theta``, ``reverses`` on the grid asked for
        (ascending).

    Raises
    ------
    ValueError
        For bad parameters or a bad grid (naming them), for two excitation
        frequencies (the harmonic balance needs one), for laws whose normal motion
        depends on the tangential one (`beltmdsm.model.Unsupported`);
        `beltmdsm.errors.Refused` for a grid of more than `MAX_VB_POINTS` points.
    RuntimeError
        If the harmonic balance does not converge at a belt speed.

    See Also
    --------
    beltmdsm.prediction.mdsm.consistent_mdsm_damping : the damping at one belt speed.
    beltmdsm.predict : both analyses, with the reasons.

    Examples
    --------
    The base set's band: below the onset of reversal (6.375 m/s, the upper edge) the
    damping is negative down to 4.682 m/s, on a grid of 20 speeds as of 400:

    >>> found, table = unstable_intervals(points=20)
    >>> [(round(lo, 4), round(hi, 4)) for lo, hi in found]
    [(4.6816, 6.3754)]
    >>> sorted(table), table["Vb"].size
    (['V', 'Vb', 'damping', 'reverses', 'theta'], 20)
    """
    model = as_model(model, **kw)
    _check_points(points)
    _single_frequency(model.params)
    require(model, "one_way_coupling", "the consistent MDSM's fast normal force")
    onset = reversal_onset(model)
    if vb is not None:
        return _scan(model, _check_grid(vb), onset, progress)
    # Above the onset the friction never reverses (for Coulomb's law the slope of its
    # average is 0 there); a coefficient that varies with the sliding speed keeps a
    # slope while the fast motion reaches its steep part: the unforced critical belt
    # speed is added, and the grid is doubled (up to `_EXTEND` times) while a band
    # reaches its top.
    linear = _linear_without_reversal(model)
    top = _default_top(model, onset)
    if vb_max is not None:
        if not (math.isfinite(vb_max) and vb_max > 0):
            raise ValueError(f"vb_max must be a finite belt speed > 0; got {vb_max!r}")
        grid = np.linspace(vb_max / points, vb_max, points)
        if top > 0:
            fine = np.linspace(top / points, top, points)
            grid = np.union1d(grid, fine[fine < vb_max])
        return _scan(model, grid, onset, progress)
    if not top > 0:
        return _scan(model, np.empty(0), onset, progress)
    for extend in range(_EXTEND + 1):
        vb = np.linspace(top / points, top, points)
        found, table = _scan(model, vb, onset, progress)
        if linear or not (found and found[-1][1] == vb[-1]) or extend == _EXTEND:
            return found, table
        top *= 2
    raise AssertionError("unreachable")


#: How often the default grid of a law whose coefficient varies in slip is doubled
#: while an unstable band reaches its top (`unstable_intervals`).
_EXTEND = 3


def _scan(model: Model, vb: NDArray[np.float64], onset: float, progress: bool):
    """`unstable_intervals` on the grid ``vb`` (checked), with the onset of reversal."""
    requested = np.sort(vb)
    zone = np.zeros(vb.size, bool)
    if vb.size and onset > 0:
        # the onset of reversal and a point just below it; the requested points between
        # them are evaluated for the table only (the balance may be singular there)
        onset_below = onset * (1 - ONSET_STEP)
        zone = (requested > onset_below) & (requested < onset)
        extra = [v for v in (onset_below, onset) if vb.min() < v < vb.max()]
        vb = np.union1d(requested[~zone], extra)
    if vb.size == 0:
        return [], {
            "Vb": vb,
            "damping": vb.copy(),
            "V": vb.copy(),
            "theta": vb.copy(),
            "reverses": np.zeros(0, bool),
        }
    from tqdm import tqdm

    rows, guess = [], None
    total = vb.size + int(zone.sum())
    bar = tqdm(
        total=total, desc="predict Vb", disable=not progress, file=sys.stderr, delay=2, leave=False
    )
    try:
        for v in sorted(vb, reverse=True):
            q = model.replace(Vb=float(v))
            fast = fast_motion(q, guess)
            guess = fast
            rows.append((v, consistent_mdsm_damping(q, fast), fast))
            bar.update()
        rows.sort(key=lambda r: r[0])
        found = {float(r[0]): r[1:] for r in rows}
        for v in requested[zone]:
            q = model.replace(Vb=float(v))
            try:
                fast = fast_motion(q, found[float(onset_below)][1])
                found[float(v)] = (consistent_mdsm_damping(q, fast), fast)
            except RuntimeError:
                found[float(v)] = (math.nan, None)
            bar.update()
    finally:
        bar.close()
    grid = np.array([r[0] for r in rows])
    damping = np.array([r[1] for r in rows])

    def damping_at(v, guess):
        q = model.replace(Vb=float(v))
        return consistent_mdsm_damping(q, fast_motion(q, guess))

    cuts = []
    for i in intervals.sign_changes(damping):
        below, above = rows[i][2], rows[i + 1][2]
        if below.reverses != above.reverses:
            # Onset of reversal: the edge is the onset itself (for Coulomb's law the
            # linear amplitude, independent of Vb); the harmonic balance is singular
            # there and no root-finder is needed.
            cuts.append(_onset_between(model, onset, grid[i], grid[i + 1]))
            continue
        cuts.append(optimize.brentq(damping_at, grid[i], grid[i + 1], args=(above,), xtol=1e-10))
    unstable = intervals.from_crossings(grid, damping < 0, cuts)
    at = [found[float(v)] for v in requested]
    table = {
        "Vb": requested,
        "damping": np.array([d for d, _ in at]),
        "V": np.array([f.V if f else math.nan for _, f in at]),
        "theta": np.array([f.theta if f else math.nan for _, f in at]),
        "reverses": np.array([bool(f and f.reverses) for _, f in at]),
    }
    return unstable, table


def _default_top(model: Model, onset: float) -> float:
    """The top of the default grid (before any doubling): 1.05 times the onset of
    reversal, plus the unforced critical belt speed for a coefficient that varies in slip."""
    linear = _linear_without_reversal(model)
    return 1.05 * (onset + (0.0 if linear else _unforced_edge(model)))


def grid_note(
    model: Model | Mapping[str, Any] | None = None,
    *,
    vb_max: float,
    points: int = 400,
    **kw: Any,
) -> str:
    """What a grid of ``points`` speeds up to ``vb_max`` cannot resolve ("" if nothing).

    Where ``vb_max`` lies above the default grid's top, `unstable_intervals` keeps the
    default grid below that top; above it the step is ``vb_max / points``, and a band
    narrower than that there can be missed.

    Parameters
    ----------
    model : Model or dict, optional
        The parameters and the laws (default: the base set); ``**kw`` too.
    vb_max : float
        The top of the grid [m/s].
    points : int
        The number of speeds up to it.

    Returns
    -------
    str
        `GRID_COARSE` filled in, or "" where the grid is as fine as the default's.

    Raises
    ------
    RuntimeError
        Where the onset of friction reversal is not found (`reversal_onset`).

    See Also
    --------
    unstable_intervals : the grid it describes (``vb_max``).

    Examples
    --------
    >>> grid_note(vb_max=5.0)
    ''
    >>> print(grid_note(vb_max=3000.0))  # doctest: +NORMALIZE_WHITESPACE
    the grid keeps the default's step 0.0167 m/s up to 6.694 m/s; above it the step
    is 7.5 m/s, and a band narrower than that there can be missed
    """
    model = as_model(model, **kw)
    onset = reversal_onset(model)
    top = _default_top(model, onset)
    step = vb_max / points
    if not top > 0 or top >= vb_max or step <= top / points:
        return ""
    return GRID_COARSE.format(top=top, fine=top / points, step=step)


def _onset_between(model: Model, onset: float, lo: float, hi: float) -> float:
    """The onset of reversal within ``[lo, hi]``: the one found first, or another one
    of a law whose fast amplitude varies with ``Vb`` (`reversal_onset` from ``hi``)."""
    if lo <= onset <= hi:
        return onset
    other = reversal_onset(model, start=hi)
    if not lo <= other <= hi:
        raise RuntimeError(
            f"the friction starts to reverse between Vb = {lo!r} and {hi!r}, but the "
            f"onset (V = Vb) was not found there (found {other!r})"
        )
    return other


#: The note on a grid whose step above the default's top is coarser than the default's
#: (formatted with the default top, its step and the coarse step).
GRID_COARSE = (
    "the grid keeps the default's step {fine:.3g} m/s up to {top:.4g} m/s; above it the "
    "step is {step:.3g} m/s, and a band narrower than that there can be missed"
)


#: The note on a band of the consistent MDSM that reaches an end of its grid.
GRID_END = (
    "an unstable range reaches the {end} belt speed of the grid, {value:.4g} m/s, "
    "and may extend {side} it"
)
