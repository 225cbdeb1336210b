"""Where a self-excited cycle and stable steady sliding coexist: hysteresis without excitation.

Without excitation the attractors of Eq. (4) are steady sliding (Eq. 9) and the
self-excited cycles. Steady sliding is stable where every eigenvalue of ``J^0``
(`beltmdsm.generated.unforced.eigenvalues`) has a negative real part; its stability changes at
the Hopf points (`beltmdsm.cycles.hopf.hopf_points`) and where a real eigenvalue
crosses 0 (placed by Brent's method on the largest real part). The cycles are the
branch born at the first Hopf point of the range
(`beltmdsm.cycles.branch.cycle_branch`), with its stable parts; without a Hopf
point in the range, the branch through a cycle seeded where a stick ends, at the
model's value or the middle of the range (a static bound above the kinetic
coefficient keeps a stick-slip cycle beside stable sliding, with no Hopf point). Where a stable
cycle and stable steady sliding share a range, a run ends on either one by where it
starts: hysteresis, the mark of a subcritical Hopf point (the cycles exist where
steady sliding is stable) or of a branch that folds back past it. The overlay is
`beltmdsm.multistability.coexistence.overlay`'s.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from ..cycles.branch import CycleBranch, cycle_branch
from ..cycles.hopf import HopfPoint, eigenvalues_over, hopf_points
from ..errors import NoPeriodicResponse
from ..model import Model
from ..periodic.engines import engine_of
from .stable_ranges import CoexistenceRange, StablePart, overlay, stable_parts

__all__ = ["CycleCoexistence", "cycle_coexistence", "SLIDING", "CYCLES"]

#: The names of the two kinds of attractor in the overlay.
SLIDING, CYCLES = "steady sliding", "cycle"
#: Grid on which the sign of the largest real part is read between the Hopf points.
_GRID = 201


@dataclass(frozen=True)
class _Attractor:
    name: str
    stable: list[StablePart]


@dataclass
class CycleCoexistence:
    """The result of `cycle_coexistence` (``coexistence`` without excitation).

    Attributes
    ----------
    param : str
    lo, hi : float
    model : Model
    hopf : list of HopfPoint
    sliding : list of StablePart
        Where steady sliding is stable, bounded by ``hopf`` or ``real_eigenvalue``.
    branch : CycleBranch or None
        The cycles born at the first Hopf point (None without one, or where none is
        found: ``reason``).
    ranges : list of CoexistenceRange
        Where a stable cycle and stable steady sliding coexist.
    reason : str
        Why there is none, where there is none.
    wall_s : float

    See Also
    --------
    beltmdsm.multistability.cycle_coexistence.cycle_coexistence : what builds it.
    beltmdsm.multistability.coexistence.Coexistence : its twin with excitation.

    Examples
    --------
    Built by hand: steady sliding stable over the whole range, no cycle, no coexistence.

    >>> from beltmdsm import Model
    >>> from beltmdsm.multistability.stable_ranges import StablePart
    >>> found = CycleCoexistence("Vb", 1.0, 3.0, Model(alpha=0), [],
    ...                          [StablePart((1.0, 3.0), "range", "range")], None, [],
    ...                          "no Hopf point", 0.1)
    >>> print(found)
    CycleCoexistence(Vb in [1, 3], coulomb friction, hertz_damp, tension allowed, 0.1 s)
      Hopf points: none
      steady sliding stable in [1, 3]
      cycles stable in none
      coexist in none
      reason: no Hopf point
    >>> d = found.as_dict()
    >>> d["autonomous"], d["sliding_stable"], d["criticality"]
    (True, [{'range': [1.0, 3.0], 'lower': 'range', 'upper': 'range'}], None)
    """

    param: str
    lo: float
    hi: float
    model: Model
    hopf: list[HopfPoint]
    sliding: list[StablePart]
    branch: CycleBranch | None = field(repr=False)
    ranges: list[CoexistenceRange]
    reason: str
    wall_s: float

    def __repr__(self) -> str:
        from .._display import block, intervals, laws

        b = self.branch
        lines = [
            "Hopf points: "
            + (", ".join(f"{h.value:.6g}" for h in self.hopf) or "none")
            + ("" if b is None or b.criticality is None else f" ({b.criticality})"),
            f"{SLIDING} stable in {intervals(s.range for s in self.sliding)}",
            f"{CYCLES}s stable in "
            + ("none" if b is None else intervals(s.range for s in stable_parts(b))),
            "coexist in " + intervals(r.range for r in self.ranges),
        ]
        if self.reason:
            lines.append(f"reason: {self.reason}")
        head = (
            f"CycleCoexistence({self.param} in [{self.lo:.6g}, {self.hi:.6g}], "
            f"{laws(self.model)}, {self.wall_s:.1f} s)"
        )
        return block(head, lines)

    def as_dict(self) -> dict:
        """The JSON of ``coexistence --json`` without excitation: ``autonomous``,
        ``param``, ``range``, the laws, ``hopf``, ``criticality``, ``sliding_stable``,
        ``cycle_stable``, ``coexistence``, ``reason``, ``special_points``, ``wall_s``."""
        b = self.branch
        return {
            "autonomous": True,
            "param": self.param,
            "range": [self.lo, self.hi],
            "contact": self.model.contact,
            "tension": self.model.tension,
            "friction": self.model.friction,
            "engine": engine_of(self.model),
            "hopf": [h.as_dict() for h in self.hopf],
            "criticality": None if b is None else b.criticality,
            "sliding_stable": [s.as_dict() for s in self.sliding],
            "cycle_stable": [] if b is None else [s.as_dict() for s in stable_parts(b)],
            "coexistence": [r.as_dict() for r in self.ranges],
            "reason": self.reason,
            "special_points": [] if b is None else [s.as_dict() for s in b.special],
            "wall_s": self.wall_s,
        }


def _sliding_parts(model, param, lo, hi, hopf):
    """Where steady sliding is stable: cut at the Hopf points and the real crossings."""

    def top(v):
        lam = eigenvalues_over(model, param, np.atleast_1d(v))
        return np.max(lam.real, axis=1)

    cuts = [(lo, "range")] + [(h.value, "hopf") for h in hopf]
    grid = np.linspace(lo, hi, _GRID)
    re = top(grid)
    for i in np.flatnonzero(np.sign(re[:-1]) * np.sign(re[1:]) < 0):
        v = brentq(lambda s: float(top(s)[0]), grid[i], grid[i + 1], xtol=1e-12)
        if all(abs(v - h.value) > 1e-8 for h in hopf):
            cuts.append((v, "real_eigenvalue"))
    cuts = sorted(cuts) + [(hi, "range")]
    parts = []
    for (a, ka), (b, kb) in zip(cuts[:-1], cuts[1:]):
        if b > a and top(0.5 * (a + b))[0] < 0:
            if parts and parts[-1].range[1] == a:
                parts[-1] = StablePart((parts[-1].range[0], b), parts[-1].lower, kb)
            else:
                parts.append(StablePart((a, b), ka, kb))
    return parts


#: Where a range without a Hopf point is seeded for cycles, as shares of the range.
_SEEDS = (0.5, 0.25, 0.75)


def _unborn(model, param, lo, hi, backend):
    """A branch of cycles through a seeded one where no Hopf point is in the range:
    ``(branch, "")``, or ``(None, reason)``."""
    values = [float(model[param])] if lo <= float(model[param]) <= hi else []
    values += [lo + share * (hi - lo) for share in _SEEDS]
    failures = []
    for v in values:
        try:
            found = cycle_branch(model.replace(**{param: v}), param=param, lo=lo, hi=hi,
                                 backend=backend)  # fmt: skip
            return found, ""
        except NoPeriodicResponse as err:
            failures.append(f"{param} = {v:g}: {str(err).split(';')[-1].strip()}")
    return None, (
        f"no Hopf point of steady sliding for {param} in [{lo:g}, {hi:g}], and no cycle "
        f"seeded where a stick ends ({'; '.join(failures[:2])})"
    )


def cycle_coexistence(
    param: str, lo: float, hi: float, model: Model, *, backend=None, settings=None
) -> CycleCoexistence:
    """Where a stable self-excited cycle and stable steady sliding coexist in ``param``.

    Parameters
    ----------
    param : str
    lo, hi : float
    model : Model
        Without excitation; the other parameters and the options.
    backend : {"python", "numba", None}
    settings : ContinuationSettings, optional
        The continuation driver's, for the branch of cycles.

    Returns
    -------
    CycleCoexistence
        Where no cycle is found, or none coexists with stable steady sliding,
        ``reason`` says why.

    See Also
    --------
    beltmdsm.cycles.hopf.hopf_points : where steady sliding changes stability.
    beltmdsm.cycles.branch.cycle_branch : the cycles born at a Hopf point.
    beltmdsm.multistability.coexistence.coexistence : what calls it without excitation.

    Examples
    --------
    Under Coulomb friction without excitation steady sliding is stable over 1-3 m/s,
    with no Hopf point and no cycle seeded where a stick ends:

    >>> from beltmdsm import Model
    >>> found = cycle_coexistence("Vb", 1.0, 3.0, Model(alpha=0))
    >>> found.hopf, [s.range for s in found.sliding], found.branch, found.ranges
    ([], [(1.0, 3.0)], None, [])
    >>> print(found.reason)  # doctest: +ELLIPSIS
    no Hopf point of steady sliding for Vb in [1, 3], and no cycle seeded where a stick ends ...
    """
    clock = time.perf_counter()
    hopf = hopf_points(model, param, lo, hi)
    sliding = _sliding_parts(model, param, lo, hi, hopf)
    branch, reason = None, ""
    if not hopf:
        # no cycle is born in the range; one may still exist there, apart from steady
        # sliding (a static bound above the kinetic coefficient keeps a stick-slip cycle
        # beside stable sliding): seeded where a stick ends, at a few values
        branch, reason = _unborn(model, param, lo, hi, backend)
    else:
        try:
            branch = cycle_branch(
                model, param=param, lo=lo, hi=hi, backend=backend, settings=settings
            )
        except NoPeriodicResponse as err:
            reason = f"no cycle found from the Hopf point: {err}"
    ranges = []
    if branch is not None:
        attractors = [_Attractor(SLIDING, sliding), _Attractor(CYCLES, stable_parts(branch))]
        ranges = overlay(attractors)
        if not ranges:
            born = (
                f"the Hopf point at {param} = {hopf[0].value:.6g} is {branch.criticality}"
                if hopf
                else "no Hopf point is in the range (the cycles were seeded where a stick ends)"
            )
            reason = (
                f"{born} and no stable part of the cycles' branch overlaps stable steady sliding"
            )
    return CycleCoexistence(
        param,
        float(lo),
        float(hi),
        model,
        hopf,
        sliding,
        branch,
        ranges,
        reason,
        time.perf_counter() - clock,
    )
