"""How far an orbit is from changing its switch structure: its margins, and the grazing test.

Margins are positive away from the change and dimensionless (`Margin`); a period map
reads them from the runs of its orbit (`beltmdsm.periodic.base.MapImage.margins`):

* ``crossing``: the rate of a switching function at a crossing, along the mode
  before, over the function's rounding scale (`generated.hybrid.surface_rates`,
  `surface_scales`). It vanishes where a crossing becomes tangential: a
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
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from ..integrate.switching import SURFACE_INDEX, Mode, Switching

__all__ = [
    "GRAZING_RATIO",
    "MARGIN_KINDS",
    "MarginKind",
    "Margin",
    "crossing_ratio",
    "orbit_range",
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
    the cone's functions is): the ``crossing`` margin, and the grazing test."""
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
        The switching surface (`generated.hybrid.SURFACES`).
    mode : Mode
        The mode before the crossing, or of the segment.
    t : float
        Time from phase 0 [s].
    value : float
        Positive away from the change, zero at it.
    """

    kind: MarginKind
    surface: str
    mode: Mode
    t: float
    value: float


def orbit_range(runs: list, component: int = 1) -> tuple[float, float]:
    """The smallest and largest of one state component over the runs of an orbit.

    ``runs`` are periods as `PeriodMap` reads them (``starts``, ``ends`` and
    ``segments(t, index) -> (4, n)``: an `EventPeriod` or a tangential run);
    ``component`` 0 is ``X1``, 1 ``X1'``. Each segment is sampled (`_SAMPLES_PER_S`)
    and an interior extreme is refined by a bounded search to 1e-12 s.
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
                if 0 < k < v.size - 1:
                    res = optimize.minimize_scalar(
                        lambda s, run=run, index=index, sign=sign: -sign * value(run, index, s),
                        bounds=(t[k - 1], t[k + 1]),
                        method="bounded",
                        options={"xatol": 1e-12},
                    )
                    extreme = sign * max(sign * extreme, -float(res.fun))
                lo, hi = (min(lo, extreme), hi) if sign < 0 else (lo, max(hi, extreme))
    return float(lo), float(hi)
