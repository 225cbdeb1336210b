"""The stable attractors of any model at one point, and where two or more coexist.

`responses` runs a grid of starts on the plane of the first coordinate and its rate
(`beltmdsm.oscillator.basins.land`: each start until it provably lands), keeps the
distinct attractors, and shoots each exactly: a forced response of ``k`` excitation
periods (`forced_response`, from its stroboscopic state) or a self-excited cycle
(`self_excited_cycle`, from its stick-end state), with its Floquet multipliers;
steady sliding with its eigenvalues. Only attractors are found this way: an unstable
response is no run's end. `coexistence` does so at points of one parameter and names
the ranges between points where two or more stable attractors coexist (sampled at the
points, not continued between them).
"""

from __future__ import annotations

from concurrent.futures import Executor
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..errors import NoPeriodicResponse
from .basins import BasinAttractor, merge, run_starts
from .cycle import Cycle, genuine
from .cycles import self_excited_cycle
from .equilibria import Equilibrium, steady_sliding
from .forced import Response, forced_response
from .system import System

__all__ = [
    "Found", "Attractors", "responses", "Coexistence", "coexistence", "shoot_attractor",
]  # fmt: skip


@dataclass(repr=False)
class Found:
    """One attractor, shot exactly.

    Attributes
    ----------
    attractor : BasinAttractor
        Its kind, periods and representative state, as the runs found it.
    orbit : Response, Cycle, Equilibrium or None
        The exact orbit with its multipliers (eigenvalues of steady sliding); None
        where the shooting failed (``failure`` says why).
    share : float
        The share of the starts that landed on it.
    failure : str
    """

    attractor: BasinAttractor
    orbit: object
    share: float
    failure: str = ""

    def as_dict(self) -> dict:
        out = {
            "kind": self.attractor.kind,
            "periods": self.attractor.periods,
            "state": list(self.attractor.state),
            "share": self.share,
        }
        o = self.orbit
        if hasattr(o, "multipliers"):
            out["period"] = float(o.period)
            out["multipliers"] = [[float(z.real), float(z.imag)] for z in o.multipliers]
            out["stable"] = bool(o.stable)
        elif o is not None:
            out["eigenvalues"] = [[float(z.real), float(z.imag)] for z in o.eigenvalues]
            out["stable"] = bool(o.stable)
        if self.failure:
            out["failure"] = self.failure
        return out


@dataclass(repr=False)
class Attractors:
    """The stable attractors found at one point.

    Attributes
    ----------
    system : System
    found : list of Found
    starts : int
    unresolved : float
        The share of starts that landed on nothing.

    See Also
    --------
    responses : makes it.
    """

    system: System
    found: list[Found]
    starts: int
    unresolved: float

    def __repr__(self) -> str:
        parts = ", ".join(f"{f.attractor.kind}({f.attractor.periods})" for f in self.found)
        return f"Attractors({self.system!r}; {self.starts} starts: {parts or 'none'})"

    def as_dict(self) -> dict:
        return {
            **self.system.as_dict(),
            "starts": self.starts,
            "unresolved": self.unresolved,
            "attractors": [f.as_dict() for f in self.found],
        }


def _starts(system: System, points: int):
    """A grid on the plane of the first coordinate and its rate, around steady sliding
    (rest where forced), as wide as the belt speed and the equilibrium's offset."""
    n = len(system.coordinates)
    forced = system.excitation_period() is not None
    base = np.zeros(2 * n) if forced else steady_sliding(system).state.copy()
    speed = max(1.0, abs(system.params.get("Vb", 1.0)))
    reach = max(1.0, abs(base[0]))
    near = base.copy()
    near[0] += 1e-3 * reach  # steady sliding's own basin, where it is stable
    out = [near]
    for u in np.linspace(-2.0, 2.0, points):
        for v in np.linspace(-1.5, 0.5, points):
            s = base.copy()
            s[0] += u * reach
            s[n] += v * speed
            out.append(s)
    return out


def shoot_attractor(system: System, a: BasinAttractor) -> Equilibrium | Response | Cycle:
    """The set a run landed on (`beltmdsm.oscillator.basins.land`), exactly: steady
    sliding, the forced response of ``a.periods`` periods, or the self-excited cycle
    (NoPeriodicResponse where the shooting fails or finds another kind of cycle)."""
    if a.kind == "steady_sliding":
        return steady_sliding(system)
    if a.kind == "periodic":
        return forced_response(system, np.array(a.seed), periods=a.periods, settle=0.0)
    cycle = self_excited_cycle(system, np.array(a.seed), settle=50.0)
    if (cycle.kind == "slip") != (a.kind == "slip_cycle"):
        raise NoPeriodicResponse(
            f"the shooting from the {a.kind} found by the runs converged on a {cycle.kind} cycle"
        )
    # self_excited_cycle already refuses the trivial return T -> 0 (Hoffmann's model at
    # mu_s = 1 from its default seed: period 5e-12 s); the one check, named here
    genuine(cycle)
    return cycle


def responses(
    system: System,
    *,
    points: int = 4,
    starts: list[ArrayLike] | None = None,
    t_end: float = 500.0,
    limit: int = 8,
    tol: float = 1e-6,
    executor: Executor | None = None,
) -> Attractors:
    """The stable attractors of ``system`` that runs from a grid of starts land on,
    each shot exactly with its multipliers (module docstring).

    Parameters
    ----------
    system : System
    points : int
        Starts per axis of the default grid, >= 2.
    starts : list of array_like (2n,), optional
        The starts instead of the grid.
    t_end : float
        The longest run of a start [s].
    limit : int
        The most excitation periods (or sticks per period) looked for.
    tol : float
    executor : concurrent.futures.Executor, optional

    Returns
    -------
    Attractors

    See Also
    --------
    beltmdsm.oscillator.basins.basins : which start lands where.

    Examples
    --------
    >>> from beltmdsm.oscillator import System
    >>> found = responses(System("belt_1dof", friction="stribeck", Vb=2.5), points=2)
    >>> [(f.attractor.kind, f.orbit.stable) for f in found.found]
    [('steady_sliding', True), ('stick_slip', True)]
    """
    if starts is None:
        if not (isinstance(points, int) and points >= 2):
            raise ValueError(f"points={points!r}: not a whole number >= 2")
        starts = _starts(system, points)
    m = len(system.states)
    starts = [np.asarray(s, dtype=float) for s in starts]
    if not starts or any(s.shape != (m,) or not np.all(np.isfinite(s)) for s in starts):
        raise ValueError(f"starts: each {m} finite numbers ({', '.join(system.states)})")
    landed = run_starts(system, starts, t_end, tol, limit, executor)
    merged, labels = merge(landed, tol)
    found = []
    for i, a in enumerate(merged):
        share = float(np.mean(labels == i))
        try:
            found.append(Found(a, shoot_attractor(system, a), share))
        except NoPeriodicResponse as err:
            found.append(Found(a, None, share, str(err)))
    return Attractors(system, found, len(starts), float(np.mean(labels < 0)))


@dataclass(repr=False)
class Coexistence:
    """The stable attractors at points of one parameter, and where several coexist.

    Attributes
    ----------
    system : System
    param : str
    points : list of Attractors
        One per value, in ascending order.
    ranges : list of (float, float)
        Runs of consecutive values with two or more stable attractors (their first and
        last value).

    See Also
    --------
    coexistence : makes it.
    """

    system: System
    param: str
    points: list[Attractors]
    ranges: list[tuple[float, float]]

    def __repr__(self) -> str:
        spans = ", ".join(f"[{a:g}, {b:g}]" for a, b in self.ranges) or "none"
        return f"Coexistence({self.system.name}, {self.param}; coexisting in {spans})"

    def as_dict(self) -> dict:
        return {
            **self.system.as_dict(without=self.param),
            "param": self.param,
            "ranges": [list(r) for r in self.ranges],
            "points": [
                {self.param: p.system.params[self.param], "attractors": p.as_dict()["attractors"]}
                for p in self.points
            ],
        }


def _stable(found: Found) -> bool:
    return found.orbit is not None and bool(found.orbit.stable)


def coexistence(system: System, param: str, values: ArrayLike, **options: Any) -> Coexistence:
    """`responses` at each value of ``param``, and the ranges of values where two or
    more stable attractors coexist (sampled at the values).

    Parameters
    ----------
    system : System
    param : str
        One of ``system.params``.
    values : array_like
        Run in ascending order.
    **options
        Of `responses` (``points``, ``t_end``, ``limit``, ``tol``, ``executor``).

    Returns
    -------
    Coexistence
    """
    if param not in system.params:
        raise ValueError(
            f"param={param!r}: not a parameter of model {system.name!r} "
            f"({', '.join(system.params)})"
        )
    values = np.unique(np.asarray(values, dtype=float).ravel())
    points = [responses(system.replace(**{param: float(v)}), **options) for v in values]
    ranges, start = [], None
    for v, p in zip(values, points):
        many = sum(_stable(f) for f in p.found) >= 2
        if many and start is None:
            start = float(v)
        if many:
            last = float(v)
        elif start is not None:
            ranges.append((start, last))
            start = None
    if start is not None:
        ranges.append((start, last))
    return Coexistence(points[0].system if points else system, param, points, ranges)
