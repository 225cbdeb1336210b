"""How far an orbit is from changing its switch structure: its margins, and the grazing test.

Margins are positive away from the change and dimensionless (`Margin`); a period map
reads them from the runs of its orbit (`beltmdsm.periodic.base.MapImage.margins`):

* ``crossing``: the rate of a switching function at a crossing, along the mode
  before, over the function's rounding scale (`beltmdsm.generated.hybrid.surface_rates`,
  `beltmdsm.generated.hybrid.surface_scales`). It vanishes where a crossing becomes tangential: a
  **tangency**, where the saltation matrix and the multipliers diverge.
* ``approach``: the closest approach of a segment to a surface it does not cross
  (an interior maximum of ``Vr`` while sliding back, a minimum while sliding
  forward, a minimum of the friction margin while sticking), over its scale. It
  vanishes at **grazing**, where the segment touches the surface and new switches
  appear.
* ``decision``: at ``Vr = 0`` (and on entering contact), how far Filippov's choice
  (`beltmdsm.integrate.switching.Switching.decide_slip`) is from the other outcome (a
  reversal from sticking, a stick from reversing). It vanishes where a stick phase
  appears or disappears, also a grazing.

**Grazing.** Where a reversal is reached with a vanishing acceleration (a velocity that
just touches the belt's), the saltation entry ``a_after / a_before`` diverges (the
square-root singularity of grazing bifurcations). A switch whose crossing margin
(`crossing_ratio`) is below `GRAZING_RATIO` is reported as grazing, and no multiplier
is returned for it. `orbit_range` is the range of a state component over an orbit's runs.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from beltmdsm.generated import hybrid

from ..integrate.switching import SURFACE_INDEX, Mode, Switching

__all__ = [
    "GRAZING_RATIO",
    "MARGIN_KINDS",
    "MarginKind",
    "Margin",
    "crossing_ratio",
    "orbit_range",
    "orbit_margins",
]

#: A switch whose rate is below this fraction of its scale is grazing: the saltation
#: entry a_after / a_before then carries a relative rounding error of about
#: ulps / ratio, so below it a multiplier would keep fewer than 8 correct digits.
GRAZING_RATIO = 1e-8
MarginKind = Literal["crossing", "approach", "decision"]
#: The kinds of `Margin`.
MARGIN_KINDS = ("crossing", "decision", "approach")
#: Samples per second of a segment when its closest approach is searched.
_SAMPLES_PER_S = 200
#: A sampled closest approach below this (relative) is refined to machine precision.
_REFINE_BELOW = 0.2
_VR = SURFACE_INDEX["relative_velocity"]
_SF = SURFACE_INDEX["stick_forward"]
_SB = SURFACE_INDEX["stick_back"]
_TANGENTIAL = ("relative_velocity", "stick_forward", "stick_back")


def crossing_ratio(sw: Switching, t: float, state: ArrayLike, before: Mode, surface: str) -> float:
    """The rate of a switching function at a crossing, along the mode before, over the
    rounding scale of the friction cone (an acceleration, as the rate of ``Vr`` and of
    the cone's functions is): the ``crossing`` margin, and the grazing test.

    Parameters
    ----------
    sw : beltmdsm.integrate.switching.Switching
        The model's switching rules.
    t : float
        Time from phase 0 [s].
    state : array_like (4,)
        ``(X1, X1', X2, X2')`` at the crossing.
    before : Mode
        The mode before it.
    surface : str
        The surface crossed (`beltmdsm.generated.hybrid.SURFACES`).

    Returns
    -------
    float
        ``|rate| / scale``, 0 where the scale vanishes; below `GRAZING_RATIO` the
        crossing grazes.

    Raises
    ------
    KeyError
        For a surface that is not one of `beltmdsm.generated.hybrid.SURFACES`.

    See Also
    --------
    Margin : the margins of an orbit, this one of kind ``crossing``.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> from beltmdsm.periodic.engines import period_map
    >>> pmap = period_map(Model(Vb=5.0))
    >>> t, before, _, surface, state = pmap.one(pmap.sliding_guess())[2].switches[0]
    >>> crossing_ratio(pmap.sw, t, state, before, surface) > GRAZING_RATIO
    True
    """
    rate = sw.rates(t, *state, float(before))[SURFACE_INDEX[surface]]
    scale = sw.scales(t, *state)[_SF]
    return float(abs(rate) / scale) if scale > 0 else 0.0


@dataclass(frozen=True)
class Margin:
    """How far one feature of an orbit is from a change of its switch structure.

    Attributes
    ----------
    kind : {"crossing", "approach", "decision"}
        See the module docstring.
    surface : str
        The switching surface (`beltmdsm.generated.hybrid.SURFACES`).
    mode : Mode
        The mode before the crossing, or of the segment.
    t : float
        Time from phase 0 [s].
    value : float
        Positive away from the change, zero at it.

    See Also
    --------
    orbit_margins : computes them.
    beltmdsm.continuation.edges : where a closing margin ends a response.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> from beltmdsm.periodic.engines import period_map
    >>> pmap = period_map(Model(Vb=5.0))
    >>> m = pmap(pmap.sliding_guess()).margins[0]
    >>> m.kind, m.surface, m.mode.name, m.value > 0
    ('crossing', 'relative_velocity', 'SLIP_BACK', True)
    """

    kind: MarginKind
    surface: str
    mode: Mode
    t: float
    value: float


def orbit_range(runs: list, component: int = 1) -> tuple[float, float]:
    """The smallest and largest of one state component over the runs of an orbit.

    ``runs`` are periods as `beltmdsm.periodic.base.PeriodMap` reads them (``starts``,
    ``ends`` and ``segments(t, index) -> (4, n)``: a
    `beltmdsm.periodic.general_map.EventPeriod` or a tangential run); ``component`` 0 is
    ``X1``, 1 ``X1'``. Each segment is sampled (`_SAMPLES_PER_S`) and an interior
    extreme is refined by a bounded search to 1e-12 s.

    Parameters
    ----------
    runs : list
        The periods of the orbit (`beltmdsm.periodic.base.MapImage` keeps them).
    component : int
        The state component: 0 ``X1``, 1 ``X1'``, 2 ``X2``, 3 ``X2'``.

    Returns
    -------
    (float, float)
        The smallest and the largest value.

    Raises
    ------
    IndexError
        For a component outside 0..3.

    See Also
    --------
    beltmdsm.periodic.base.MapImage.velocity_range : ``X1'``'s of an image.
    beltmdsm.periodic.observables.observables : the sampled extremes and means.

    Examples
    --------
    >>> from beltmdsm import Model, periodic_response
    >>> from beltmdsm.periodic.engines import period_map
    >>> r = periodic_response(Model(Vb=5.0))
    >>> image = period_map(r.model)(r.shooting_state)
    >>> [round(v, 3) for v in orbit_range(image._runs, 0)]  # X1 [m]
    [3.373, 6.623]
    """
    from scipy import optimize

    def value(run, index, s):
        return float(run.segments(np.array([s]), np.full(1, index))[component][0])

    lo, hi = np.inf, -np.inf
    for run in runs:
        for index, (t0, t1) in enumerate(zip(run.starts, run.ends)):
            n = max(8, int((t1 - t0) * _SAMPLES_PER_S))
            t = np.linspace(t0, t1, n + 1)
            v = run.segments(t, np.full(t.size, index))[component]
            for sign in (1.0, -1.0):
                k = int(np.argmax(sign * v))
                extreme = float(v[k])
                # refined also at an end sample: the extreme may lie between it and its
                # neighbour (X1's least value 1.3 ms before a stick begins, issue 36)
                a, b = t[max(k - 1, 0)], t[min(k + 1, v.size - 1)]
                if b > a:
                    res = optimize.minimize_scalar(
                        lambda s, run=run, index=index, sign=sign: -sign * value(run, index, s),
                        bounds=(a, b),
                        method="bounded",
                        options={"xatol": 1e-12},
                    )
                    extreme = sign * max(sign * extreme, -float(res.fun))
                lo, hi = (min(lo, extreme), hi) if sign < 0 else (lo, max(hi, extreme))
    return float(lo), float(hi)


def _states(run, index, t):
    """``(X1, X1', X2, X2')`` at the times ``t`` of segment ``index`` of one period's run."""
    return run.segments(t, np.full(np.size(t), index))


def _pieces(pmap, runs):
    """The segments of the orbit, joined where a mode goes on across a period boundary.

    Each piece is ``{"mode", "parts", "start", "end"}``: ``parts`` a list of
    ``(run, index, t0, t1, offset)`` (segment ``index`` of one period's ``run``,
    from ``t0`` to ``t1`` of that period, ``offset`` from phase 0 of the orbit),
    ``start`` and ``end`` whether the piece begins and ends at a switch. The last
    piece wraps around to the first where the orbit's mode goes on through phase 0.
    """
    pieces = []
    for j, run in enumerate(runs):
        offset = j * pmap.period
        n = len(run.modes)
        for i, (t0, t1, m) in enumerate(zip(run.starts, run.ends, run.modes)):
            part = (run, i, t0, t1, offset)
            if pieces and i == 0 and pieces[-1]["mode"] == m and not pieces[-1]["end"]:
                pieces[-1]["parts"].append(part)
                pieces[-1]["end"] = i < n - 1
            else:
                pieces.append({"mode": m, "parts": [part], "start": i > 0, "end": i < n - 1})
    first, last = pieces[0], pieces[-1]
    if len(pieces) > 1 and last["mode"] == first["mode"] and not last["end"]:
        wrap = pmap.periods * pmap.period
        last["parts"] += [(r, i, a, b, o + wrap) for r, i, a, b, o in first["parts"]]
        last["end"] = first["end"]
        pieces = pieces[1:]
    return pieces


def orbit_margins(pmap: Any, runs: list, kinds: Sequence[str] = MARGIN_KINDS) -> list[Margin]:
    """The margins of the given kinds of the orbit made of ``runs`` (module docstring).

    Parameters
    ----------
    pmap : beltmdsm.periodic.base.PeriodMap
        The period map that ran them (its switching rules ``sw``, ``period`` and
        ``periods``).
    runs : list
        Its ``k`` periods.
    kinds : sequence of str
        Of `MARGIN_KINDS`.

    Returns
    -------
    list of Margin

    Raises
    ------
    IndexError
        For ``runs`` empty while ``"approach"`` is asked for.

    See Also
    --------
    beltmdsm.periodic.base.MapImage.margins_of : the margins of an image, kept.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> from beltmdsm.periodic.engines import period_map
    >>> pmap = period_map(Model(Vb=5.0))
    >>> image = pmap(pmap.sliding_guess())
    >>> [m.kind for m in orbit_margins(pmap, image._runs, ("crossing",))]
    ['crossing', 'crossing']
    """
    out = []
    for j, run in enumerate(runs):
        offset = j * pmap.period
        for t, before, after, surface, state in run.switches:
            if surface in _TANGENTIAL and "crossing" in kinds:
                ratio = crossing_ratio(pmap.sw, t, state, before, surface)
                out.append(Margin("crossing", surface, before, t + offset, ratio))
            if "decision" in kinds and (
                surface == "relative_velocity"
                or (surface == "penetration" and after != Mode.FLIGHT)
            ):
                out.append(_decision(pmap, t, state, before, after, surface, offset))
    if "approach" not in kinds:
        return out
    for piece in _pieces(pmap, runs):
        if piece["mode"] in (Mode.SLIP_BACK, Mode.SLIP_FORWARD, Mode.STICK):
            margin = _approach(pmap, piece)
            if margin is not None:
                out.append(margin)
    return out


def _decision(pmap, t, state, before, after, surface, offset):
    """How far Filippov's choice at a switch onto ``Vr = 0`` is from the other outcome."""
    h = pmap.sw.surfaces(t, *state)
    scales = pmap.sw.scales(t, *state)
    sf, sb = h[_SF], h[_SB]
    if surface == "penetration" and abs(h[_VR]) > 0:
        # touchdown away from Vr = 0: the sign of Vr decides
        value = abs(h[_VR]) / scales[_VR]
    elif after == Mode.STICK:
        value = min(sf, sb) / scales[_SF]
    elif sf + sb > 0:  # a cone that could hold the mass: how far outside it
        value = -(sf if after == Mode.SLIP_FORWARD else sb) / scales[_SF]
    else:  # an empty cone: the side of a_free decides
        value = abs(0.5 * (sb - sf)) / scales[_SF]
    return Margin("decision", surface, before, t + offset, float(value))


def _distance(pmap, mode, states, t):
    """Distance of a segment in ``mode`` to the surface that would end it, and that surface."""
    sw = pmap.sw
    h = np.asarray(sw.surfaces.array(t, *states), dtype=float)
    scale = np.asarray(sw.scales.array(t, *states), dtype=float)
    if mode == Mode.SLIP_BACK:
        return -h[_VR] / scale[_VR], np.full(t.size, _VR)
    if mode == Mode.SLIP_FORWARD:
        return h[_VR] / scale[_VR], np.full(t.size, _VR)
    sf, sb = h[_SF] / scale[_SF], h[_SB] / scale[_SB]
    return np.minimum(sf, sb), np.where(sf <= sb, _SF, _SB)


def _approach(pmap, piece):
    """The smallest interior minimum of a piece's distance to the surface that would end it.

    None where the distance has no interior minimum below 1 (its saturation: a
    velocity against the belt's is as far from ``Vr = 0`` as the scale says).
    """
    from scipy import optimize

    mode, parts = piece["mode"], piece["parts"]
    times, values, where = [], [], []
    for run, index, t0, t1, offset in parts:
        n = max(8, int((t1 - t0) * _SAMPLES_PER_S))
        t = np.linspace(t0, t1, n + 1)
        d, surface = _distance(pmap, mode, _states(run, index, t), t)
        times.append(t + offset)
        values.append(d)
        where.append(surface)
    t, d, surface = np.concatenate(times), np.concatenate(values), np.concatenate(where)
    bounds = np.array([offset + t1 for _, _, _, t1, offset in parts])

    def at(s, rate_of=None):
        """The distance at ``s``, or the rate of the surface ``rate_of`` there."""
        k = min(int(np.searchsorted(bounds, s)), len(parts) - 1)
        run, index, _, _, offset = parts[k]
        local = s - offset
        state = _states(run, index, np.array([local]))[:, 0]
        if rate_of is None:
            h, scale = pmap.sw.surfaces(local, *state), pmap.sw.scales(local, *state)
            if mode == Mode.STICK:
                return min(h[_SF] / scale[_SF], h[_SB] / scale[_SB])
            return (h[_VR] if mode == Mode.SLIP_FORWARD else -h[_VR]) / scale[_VR]
        return float(pmap.sw.rates(local, *state, float(mode))[rate_of])

    # an end at a switch is on the surface by definition: only interior minima count
    candidate = np.ones(d.size, dtype=bool)
    candidate[0], candidate[-1] = not piece["start"], not piece["end"]
    candidate[1:] &= d[1:] <= d[:-1]
    candidate[:-1] &= d[:-1] <= d[1:]
    best = None
    for k in np.flatnonzero(candidate):
        value, tk = float(d[k]), float(t[k])
        if value < _REFINE_BELOW and 0 < k < d.size - 1:
            # the closest approach is where the surface's rate along the mode vanishes
            # (the scale varies slowly: the two minima agree to second order in the
            # distance, which vanishes at grazing)
            a, b, index = t[k - 1], t[k + 1], int(surface[k])
            ra, rb = at(a, index), at(b, index)
            if ra * rb < 0:
                tk = optimize.brentq(at, a, b, args=(index,), xtol=1e-14, rtol=1e-15)
                value = min(value, at(tk))
        if value < 1.0 and (best is None or value < best.value):
            name = hybrid.SURFACES[int(surface[k])]
            best = Margin("approach", name, mode, tk, value)
    return best
