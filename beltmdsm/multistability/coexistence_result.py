"""The result of `beltmdsm.multistability.coexistence.coexistence`: the branches found, the
ranges where stable responses coexist, and the attractors that were not continued (the
unlocked and the unexplained).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from .._tables import DataFrame
from ..continuation.branch import Branch
from ..model import Model
from ..periodic.engines import engine_of
from ..periodic.locked import NotLocked
from .stable_ranges import CoexistenceRange, StablePart

__all__ = ["ResponseBranch", "Unlocked", "Unexplained", "Coexistence"]


@dataclass
class ResponseBranch:
    """A branch of responses and its stable parts.

    Attributes
    ----------
    name : str
        ``T`` or ``kT``, numbered where several branches share ``k`` (``T#1``).
    branch : Branch
    stable : list of StablePart
        Where it is stable (merged where two parts touch at a grazing).
    sources : list of str
        The seeds that found it.

    See Also
    --------
    beltmdsm.multistability.stable_ranges.stable_parts : its stable parts.
    beltmdsm.multistability.coexistence.coexistence : what finds the branches.

    Examples
    --------
    The ``T``-periodic branch of ``beta1 = 0.3`` is stable from 5.3 m/s up to a
    Neimark-Sacker point near 5.45 m/s:

    >>> from beltmdsm import Model, periodic_response
    >>> from beltmdsm.continuation.branch import continue_branch
    >>> from beltmdsm.multistability.stable_ranges import stable_parts
    >>> b = continue_branch(periodic_response(Model(beta1=0.3, Vb=5.3)), "Vb", 5.3, 5.6)
    >>> r = ResponseBranch("T", b, stable_parts(b), ["run from rest"])
    >>> r  # doctest: +ELLIPSIS
    ResponseBranch('T', Vb from 5.3 to 5.6, stable in [5.3, 5.44...])
    >>> [(s["lower"], s["upper"]) for s in r.as_dict()["stable"]]
    [('range', 'neimark_sacker')]
    """

    name: str
    branch: Branch
    stable: list[StablePart]
    sources: list[str] = field(default_factory=list)

    def __repr__(self) -> str:
        from .._display import intervals

        lo, hi = self.branch.value_range() if self.branch.points else (math.nan, math.nan)
        return (
            f"ResponseBranch({self.name!r}, {self.branch.param} from {lo:.6g} to {hi:.6g}, "
            f"stable in {intervals(s.range for s in self.stable)})"
        )

    def as_dict(self) -> dict:
        """For JSON: ``kind`` ("periodic": a branch of periodic responses), ``name``,
        ``periods``, ``range``, ``stable``, ``special_points``, ``sources``."""
        return {
            "kind": "periodic",
            "name": self.name,
            "periods": self.branch.periods,
            "range": self.branch.value_range(),
            "stable": [s.as_dict() for s in self.stable],
            "special_points": [s.as_dict() for s in self.branch.special],
            "sources": self.sources,
        }


@dataclass(frozen=True)
class Unlocked:
    """A seed attractor that does not lock within the limit: where, and the evidence.

    Attributes
    ----------
    value : float
        the parameter's value of the seed
    evidence : beltmdsm.periodic.locked.NotLocked
        why it is not locked (rotation number, closed curve, dimension)

    See Also
    --------
    beltmdsm.periodic.locked.NotLocked : the evidence.

    Examples
    --------
    Samples that turn by 0.1234 of a circle per period lock at no period:

    >>> import numpy as np
    >>> from beltmdsm.periodic.locked import NotLocked, stroboscope
    >>> angle = 2 * np.pi * 0.1234 * np.arange(300)
    >>> s = stroboscope(np.c_[np.cos(angle), np.sin(angle)], "a torus")
    >>> u = Unlocked(6.0, NotLocked.of(s))
    >>> d = u.as_dict()
    >>> d["value"], d["closed_curve"], round(d["rotation_number"], 4)
    (6.0, True, 0.1234)
    """

    value: float
    evidence: NotLocked

    def as_dict(self) -> dict:
        """For JSON: ``value`` and the keys of `beltmdsm.periodic.locked.NotLocked.as_dict`."""
        return {"value": self.value, **self.evidence.as_dict()}


@dataclass(frozen=True)
class Unexplained:
    """A seed that locks but whose orbit Newton's method does not find.

    Attributes
    ----------
    value : float
        the parameter's value of the seed
    source : str
        the seed (``run from rest``, a ladder)
    reason : str
        why Newton's method failed

    See Also
    --------
    beltmdsm.multistability.coexistence.Coexistence : lists them.

    Examples
    --------
    >>> Unexplained(6.0, "run from rest", "Newton's method diverges").as_dict()
    {'value': 6.0, 'source': 'run from rest', 'reason': "Newton's method diverges"}
    """

    value: float
    source: str
    reason: str

    def as_dict(self) -> dict:
        """For JSON: ``value``, ``source``, ``reason``."""
        return {"value": self.value, "source": self.source, "reason": self.reason}


@dataclass
class Coexistence:
    """The result of `coexistence`: every response found, and where they coexist.

    Its ``repr`` is one screen (a line per response and per range); ``as_dict()`` is
    the JSON of ``coexistence --json``; ``plot()`` draws the stable parts.

    Parameters
    ----------
    param : str
        The parameter varied.
    lo, hi : float
        Its range.
    model : Model
        The other parameters and the options.
    responses : list of ResponseBranch
        Each response found: its name (``"T"``, ``"4T"``), branch and stable parts.
    ranges : list of CoexistenceRange
        Where two or more responses are stable, with the kinds of both edges.
    unlocked : list of Unlocked
        The seeds' attractors that do not lock within the limit.
    unexplained : list of Unexplained
        Locks that no branch passes through, and why.
    wall_s : float
        The wall time [s].
    seed_step : float
        The spacing of the seeds' grid: a response stable only between two seeds,
        over less than it, may be missed (the text says so).
    n_seeds : int
        The values of the seeds' grid.

    See Also
    --------
    beltmdsm.multistability.coexistence.coexistence : what builds it.
    beltmdsm.multistability.cycle_coexistence.CycleCoexistence : its twin without excitation.

    Examples
    --------
    Built by `coexistence`; here by hand, with nothing found:

    >>> from beltmdsm import Model
    >>> from beltmdsm.multistability.coexistence import Coexistence
    >>> found = Coexistence("Vb", 1.0, 2.0, Model(), [], [], [], [], wall_s=0.1)
    >>> found  # doctest: +NORMALIZE_WHITESPACE
    Coexistence('Vb' in [1, 2], Model(); coulomb friction, hertz_damp, tension allowed;
    0 responses): coexisting in none
    >>> found.as_dict()["coexistence"]
    []
    """

    param: str
    lo: float
    hi: float
    model: Model
    responses: list[ResponseBranch]
    ranges: list[CoexistenceRange]
    unlocked: list[Unlocked]
    unexplained: list[Unexplained]
    wall_s: float
    seed_step: float = float("nan")
    n_seeds: int = 0

    def __repr__(self) -> str:
        from .._display import block, intervals, label, laws

        lines = [
            f"{r.name}: stable in "
            + (
                ", ".join(
                    f"[{s.range[0]:.6g}, {s.range[1]:.6g}] ({label(s.lower)} to {label(s.upper)})"
                    for s in r.stable
                )
                or "none"
            )
            for r in self.responses
        ]
        lines += [
            f"coexist in [{c.range[0]:.6g}, {c.range[1]:.6g}]: {', '.join(c.responses)} "
            f"({label(c.lower)} to {label(c.upper)})"
            for c in self.ranges
        ]
        if self.unlocked:
            values = sorted({u.value for u in self.unlocked})
            lines.append(f"not locked at {self.param} = {', '.join(f'{v:g}' for v in values)}")
        lines += [f"a lock at {u.value:g} not found: {u.reason}" for u in self.unexplained]
        coexist = intervals(c.range for c in self.ranges)
        return block(
            f"Coexistence({self.param!r} in [{self.lo:g}, {self.hi:g}], {self.model!r}; "
            f"{laws(self.model)}; {len(self.responses)} responses): coexisting in {coexist}",
            lines,
        )

    def to_pandas(self, table: str = "stable") -> DataFrame:
        """A `pandas.DataFrame` (needs pandas) of the ``"stable"`` parts (one row per
        stable part of each response: ``response``, ``periods``, ``lo``, ``hi`` and the
        kinds of its ``lower`` and ``upper`` edges) or of the coexistence ``"ranges"``
        (``lo``, ``hi``, ``responses`` joined by commas, ``lower``, ``upper``).

        Raises
        ------
        ValueError
            For another ``table``.

        Examples
        --------
        >>> from beltmdsm import Model
        >>> empty = Coexistence("Vb", 1.0, 2.0, Model(), [], [], [], [], wall_s=0.1)
        >>> list(empty.to_pandas())
        ['response', 'periods', 'lo', 'hi', 'lower', 'upper']
        >>> list(empty.to_pandas("ranges"))
        ['lo', 'hi', 'responses', 'lower', 'upper']
        """
        from .._tables import frame

        if table == "stable":
            rows = [
                {
                    "response": r.name,
                    "periods": r.branch.periods,
                    "lo": p.range[0],
                    "hi": p.range[1],
                    "lower": p.lower,
                    "upper": p.upper,
                }  # fmt: skip
                for r in self.responses
                for p in r.stable
            ]
            return frame(rows, ["response", "periods", "lo", "hi", "lower", "upper"])
        if table == "ranges":
            rows = [
                {
                    "lo": c.range[0],
                    "hi": c.range[1],
                    "responses": ", ".join(c.responses),
                    "lower": c.lower,
                    "upper": c.upper,
                }  # fmt: skip
                for c in self.ranges
            ]
            return frame(rows, ["lo", "hi", "responses", "lower", "upper"])
        raise ValueError(f"table must be 'stable' or 'ranges'; got {table!r}")

    def plot(self, ax: Any = None, observable: str | None = None) -> Any:
        """Each response's bifurcation diagram (``observable`` against the parameter,
        stable solid, unstable dashed), the coexistence ranges shaded, on matplotlib
        axes ``ax`` (new ones if None), which it returns
        (`beltmdsm.plotting.coexistence`; matplotlib is imported here)."""
        from ..plotting import coexistence as draw

        return draw(self, ax, observable)

    def as_dict(self) -> dict:
        """The JSON of ``coexistence --json``: ``param``, ``range``, ``contact``,
        ``tension``, ``friction``, ``engine``, ``coexistence``, ``responses``,
        ``unlocked``, ``unexplained``, ``wall_s``, ``seed_step``, ``n_seeds``."""
        return {
            "param": self.param,
            "range": [self.lo, self.hi],
            "contact": self.model.contact,
            "tension": self.model.tension,
            "friction": self.model.friction,
            "engine": engine_of(self.model),
            "coexistence": [r.as_dict() for r in self.ranges],
            "responses": [r.as_dict() for r in self.responses],
            "unlocked": [u.as_dict() for u in self.unlocked],
            "unexplained": [u.as_dict() for u in self.unexplained],
            "wall_s": self.wall_s,
            "seed_step": self.seed_step,
            "n_seeds": self.n_seeds,
        }
