"""``floquet_band`` and ``floquet_map`` of a derived model's forced response (issue 39).

`oscillator_band` walks a grid of one parameter from ``hi`` down to ``lo``, the forced
response at each value shot from its neighbour's
(`beltmdsm.oscillator.forced.forced_response`), and refines every interval between
neighbours whose state differs (found or not, stable or not, the switch structure) to
``tol``: a change of stability within one structure by the secant of ``log max |mu|``
(the edge's kind from the critical multiplier: fold, period doubling, Neimark-Sacker),
a change of structure by bisection (``stick_onset`` or ``grazing``), a response found
on one side only by bisection (``unclassified``, its detail saying so: no tangency is
located here). `oscillator_map` is a band on every row of a second parameter, its edges
joined into curves by kind. The results are `Band` and `FloquetMap`, their JSON and
``repr`` naming the model and its states.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..errors import NoPeriodicResponse
from ..model import Model
from ..oscillator.forced import Response, forced_response
from ..oscillator.system import STICK
from .band_result import Band, BandFailure, BandPoint, Edge
from .edges import OLD_KINDS, multiplier_kind
from .map_result import Curve, FloquetMap
from .oscillator_branch import _check_forced, forced_system

__all__ = ["OscillatorBand", "OscillatorMap", "oscillator_band", "oscillator_map"]


class OscillatorBand(Band):
    """A `Band` of a derived model: its JSON names the model, its parameters and states
    (``state0`` in that order), not the paper's laws.

    Examples
    --------
    >>> from beltmdsm import Model, floquet_band
    >>> m = Model(model="belt_1dof", Vb=3.0, mu_s=0.1, alpha_t=0.5, Omega_t=2.0)
    >>> band = floquet_band(m, "Omega_t", 1.9, 2.1, points=3, tol=0.05)
    >>> band.unstable, band.as_dict()["states"]
    ([], ['x', 'x_dot'])
    """

    def __repr__(self) -> str:
        from .._display import block, intervals, label

        lines = [
            f"{label(e.kind)} at {self.param} = {e.value:.6g} (+- {e.accuracy:.0e})"
            for e in self.edges
        ]
        return block(
            f"Band({self.param!r}, {self.model!r}; {self.model.friction} friction; "
            f"{len(self.grid)} values): unstable in {intervals(self.unstable)}",
            lines,
        )

    def _model_dict(self) -> dict:
        """The model's part of `Band.as_dict` (``model``, ``friction``, ``params``,
        ``states``) and ``periods``, in place of the paper's laws."""
        from ..oscillator.api import system_of

        return {**system_of(self.model).as_dict(without=self.param), "periods": self.periods}


class OscillatorMap(FloquetMap):
    """A `FloquetMap` of a derived model (every row a band; ``linear`` empty: the paper's
    linear analysis is the paper's model's)."""

    def __repr__(self) -> str:
        from .._display import block

        return block(
            f"FloquetMap({self.x!r} in [{self.x_range[0]:g}, {self.x_range[1]:g}], "
            f"{self.y!r} in [{self.y_range[0]:g}, {self.y_range[1]:g}], {self.model!r}; "
            f"{len(self.rows)} rows, {self.wall_s:.1f} s): {len(self.curves)} boundary curves",
            [repr(c) for c in self.curves],
        )

    def _model_dict(self) -> dict:
        """The model's part of `FloquetMap.as_dict`, in place of the paper's laws."""
        from ..oscillator.api import system_of

        return system_of(self.model).as_dict()


def _state(r: Response | None) -> tuple:
    if r is None:
        return (False,)
    return (True, r.stable, tuple(sorted((b, a) for _, b, a in r.switches)))


def _log_max(r: Response) -> float:
    return math.log(float(np.max(np.abs(r.multipliers))))


def oscillator_band(
    model: Model,
    param: str,
    lo: float,
    hi: float,
    *,
    points: int = 17,
    tol: float = 1e-3,
    periods: int = 1,
) -> OscillatorBand:
    """Ranges of ``param`` in ``[lo, hi]`` where a derived model's forced response is
    unstable or not found (module docstring).

    Parameters
    ----------
    model : Model
        Another registered model than the paper's, with excitation.
    param : str
        One of its parameters.
    lo, hi : float
    points : int
        Grid values (>= 2).
    tol : float
        The edges' tolerance.
    periods : int

    Returns
    -------
    OscillatorBand

    Raises
    ------
    beltmdsm.errors.Unsupported
        A model without excitation.
    ValueError
        An unknown parameter, a bad range, ``points < 2``, ``tol <= 0``.

    See Also
    --------
    beltmdsm.continuation.band.floquet_band : the public entry.
    beltmdsm.continuation.oscillator_branch.oscillator_branch : the response continued.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> m = Model(model="belt_1dof", Vb=3.0, mu_s=0.1, alpha_t=0.5, Omega_t=2.0)
    >>> [g.stable for g in oscillator_band(m, "Omega_t", 1.9, 2.1, points=2, tol=0.1).grid]
    [True, True]
    """
    system = forced_system(model, "floquet_band", (param,))
    lo, hi = float(lo), float(hi)
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"the range must be finite with lo < hi; got [{lo:g}, {hi:g}]")
    if not (isinstance(points, int) and points >= 2):
        raise ValueError(f"points must be a whole number >= 2; got {points!r}")
    if not tol > 0:
        raise ValueError(f"tol must be > 0; got {tol!r}")
    _check_forced(system, param, lo, hi)
    seen: dict[float, Response | None] = {}
    failed: list[BandFailure] = []

    def evaluate(v, near, record=False):
        s = system.replace(**{param: float(v)})
        r = None
        for guess, settle in ((near.state, 0.0), (near.state, 100.0)) if near else ((None, 100.0),):
            try:
                r = forced_response(s, guess, periods=periods, settle=settle)
                break
            except NoPeriodicResponse as err:
                reason = str(err)
        if r is None and record:
            failed.append(BandFailure(float(v), reason))
        seen[float(v)] = r
        return r

    grid, last = [], None
    for v in np.linspace(hi, lo, points):
        r = evaluate(v, last, record=True)
        last = r or last
        grid.append((float(v), r))
    grid.sort(key=lambda g: g[0])
    edges: list[Edge] = []

    def edge(a, fa, b, fb):
        kind, frequency, detail = "unclassified", None, ""
        if fa is not None and fb is not None and _state(fa)[2] == _state(fb)[2]:
            unstable = fa if not fa.stable else fb
            kind, frequency = multiplier_kind(complex(unstable.multipliers[0]), unstable.period)
        elif fa is not None and fb is not None:
            sticks = [sum(1 for _, _, x in f.switches if x == STICK) for f in (fa, fb)]
            kind = "stick_onset" if min(sticks) == 0 < max(sticks) else "grazing"
        else:
            detail = "the response is found on one side only (located by bisection)"
        edges.append(
            Edge(
                0.5 * (a + b),
                kind,
                OLD_KINDS.get(kind, "grazing" if kind == "stick_onset" else "existence"),
                (a, b),
                0.5 * (b - a),
                frequency,
                fa is None or not fa.stable,
                fb is None or not fb.stable,
                detail,
            )  # fmt: skip
        )

    def refine(a, fa, b, fb, secant=True):
        """Split ``[a, b]`` until each change is below ``tol``: the secant of
        ``log max |mu|`` and the middle in turn (so that the bracket shrinks from both
        sides), the middle alone across a change of structure or existence."""
        if _state(fa) == _state(fb):
            return
        if b - a <= tol:
            edge(a, fa, b, fb)
            return
        m = 0.5 * (a + b)
        if secant and fa is not None and fb is not None and _state(fa)[2] == _state(fb)[2]:
            la, lb = _log_max(fa), _log_max(fb)
            if la != lb:
                guess = a + (b - a) * la / (la - lb)
                m = min(max(guess, a + 0.01 * (b - a)), b - 0.01 * (b - a))
        fm = evaluate(m, fa if (abs(m - a) <= abs(b - m) and fa is not None) or fb is None else fb)
        refine(a, fa, m, fm, not secant)
        refine(m, fm, b, fb, not secant)

    for (a, fa), (b, fb) in zip(grid[:-1], grid[1:]):
        refine(a, fa, b, fb)
    edges.sort(key=lambda e: e.value)
    values = sorted(seen)
    unstable = _runs(values, seen, edges, lambda r: r is None or not r.stable, lo, hi)
    gaps = _runs(values, seen, edges, lambda r: r is None, lo, hi)
    table = [
        BandPoint(
            v,
            float(np.max(np.abs(r.multipliers))),
            r.stable,
            _log_max(r) / r.period,
            sum(1 for _, b, a in r.switches if {b, a} == {1, -1}),
            r.sticks,
            False,
            tuple(float(x) for x in r.state),
        )  # fmt: skip
        for v in values
        if (r := seen[v]) is not None
    ]
    return OscillatorBand(
        param=param, model=model, periods=int(periods), unstable=unstable, edges=edges,
        grazing_points=[e.value for e in edges if e.kind in ("grazing", "stick_onset")],
        no_periodic_response=gaps, grid=table, failed=failed, tol=float(tol),
    )  # fmt: skip


def _runs(values, seen, edges, bad, lo, hi) -> list[list[float]]:
    """The ranges of consecutive evaluated values where ``bad`` holds, bounded by the
    edge between the last good and the first bad value (else ``lo``/``hi``)."""
    out, start = [], None
    for i, v in enumerate(values):
        if bad(seen[v]) and start is None:
            start = lo if i == 0 else _between(edges, values[i - 1], v)
        if not bad(seen[v]) and start is not None:
            out.append([start, _between(edges, values[i - 1], v)])
            start = None
    if start is not None:
        out.append([start, hi])
    return out


def _between(edges, a, b) -> float:
    inside = [e.value for e in edges if a <= e.value <= b]
    return inside[0] if inside else 0.5 * (a + b)


def oscillator_map(
    model: Model,
    x: str,
    x_lo: float,
    x_hi: float,
    y: str,
    y_lo: float,
    y_hi: float,
    *,
    points: int = 100,
    tol: float | None = None,
) -> OscillatorMap:
    """Where a derived model's forced response is unstable over ``(x, y)``: a band in
    ``x`` on each of ``points`` rows of ``y`` (`oscillator_band`, ``tol`` default a
    thousandth of the x range, 9 grid values), the edges joined into curves by kind.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> m = Model(model="belt_1dof", Vb=3.0, mu_s=0.1, alpha_t=0.5, Omega_t=2.0)
    >>> fm = oscillator_map(m, "Omega_t", 1.9, 2.1, "beta1", 0.1, 0.2, points=2, tol=0.05)
    >>> fm.unstable, fm.curves
    ([[], []], [])
    """
    system = forced_system(model, "floquet_map", (x, y))
    if x == y:
        raise ValueError(f"y must differ from x ({x})")
    if not (isinstance(points, int) and points >= 2):
        raise ValueError(f"points must be a whole number >= 2; got {points!r}")
    tol = (x_hi - x_lo) / 1000.0 if tol is None else tol
    started = time.perf_counter()
    rows = np.linspace(y_lo, y_hi, points)
    curves: list[Curve] = []
    unstable = []
    for row in rows:
        m = model.replace(**{y: float(row)})
        system.replace(**{y: float(row)})  # checked: a value the model takes
        band = oscillator_band(m, x, x_lo, x_hi, points=9, tol=tol)
        unstable.append(band.unstable)
        for e in band.edges:
            open_ = [c for c in curves if c.kind == e.kind and c.y and c.y[-1] != float(row)]
            near = min(open_, key=lambda c: abs(c.x[-1] - e.value), default=None)
            if near is None or near.y[-1] != rows[list(rows).index(row) - 1]:
                near = Curve(
                    e.kind, unstable_below=e.unstable_below, unstable_above=e.unstable_above
                )
                curves.append(near)
            near.y.append(float(row))
            near.x.append(e.value)
            near.accuracy.append(e.accuracy)
            near.frequency.append(e.frequency)
    return OscillatorMap(
        x, y, [float(x_lo), float(x_hi)], [float(y_lo), float(y_hi)], rows, model, curves,
        unstable, [[] for _ in rows], [float(r) for r in rows], time.perf_counter() - started,
    )  # fmt: skip
