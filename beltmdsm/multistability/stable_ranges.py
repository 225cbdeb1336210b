"""Stable parts of branches and their overlay: where two or more attractors coexist.

Shared by `beltmdsm.multistability.coexistence` (forced responses, which re-exports these)
and `beltmdsm.multistability.cycle_coexistence` (steady sliding and self-excited cycles).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = ["StablePart", "CoexistenceRange", "stable_parts", "overlay"]


@dataclass(frozen=True)
class StablePart:
    """A range where a branch is stable, with the kinds of the special points that bound it.

    Attributes
    ----------
    range : (float, float)
        where the branch is stable
    lower, upper : str
        the kind of the special point at each end (``range`` at an end of the range)

    See Also
    --------
    beltmdsm.multistability.stable_ranges.stable_parts : computes them from a branch.

    Examples
    --------
    >>> StablePart((5.3, 5.45), "range", "neimark_sacker").as_dict()
    {'range': [5.3, 5.45], 'lower': 'range', 'upper': 'neimark_sacker'}
    """

    range: tuple[float, float]
    lower: str
    upper: str

    def as_dict(self) -> dict:
        """For JSON: ``range``, ``lower``, ``upper``."""
        return {"range": list(self.range), "lower": self.lower, "upper": self.upper}


@dataclass(frozen=True)
class CoexistenceRange:
    """A range where the same two or more stable responses coexist.

    ``responses``: their names (`ResponseBranch.name`); ``lower``, ``upper``: the kinds
    of the edges at either end (a bifurcation, or ``range`` at the end of the range).

    Attributes
    ----------
    range : (float, float)
    responses : tuple of str
    lower, upper : str

    See Also
    --------
    beltmdsm.multistability.stable_ranges.overlay : computes them.

    Examples
    --------
    >>> c = CoexistenceRange((6.5, 7.5), ("4T", "T"), "fold", "range")
    >>> c.as_dict()["responses"], c.as_dict()["range"]
    (['4T', 'T'], [6.5, 7.5])
    """

    range: tuple[float, float]
    responses: tuple[str, ...]
    lower: str
    upper: str

    def as_dict(self) -> dict:
        """For JSON: ``range``, ``responses``, ``lower``, ``upper``."""
        return {
            "range": list(self.range),
            "responses": list(self.responses),
            "lower": self.lower,
            "upper": self.upper,
        }


def stable_parts(branch: Any) -> list[StablePart]:
    """The stable parts of a branch, merged where they touch (a grazing between them).

    Parameters
    ----------
    branch : beltmdsm.continuation.branch.Branch
        anything with ``parts()`` returning parts with ``stable``, ``range``, ``lower``
        and ``upper``

    Returns
    -------
    list of StablePart
        ascending

    See Also
    --------
    beltmdsm.multistability.stable_ranges.overlay : where stable parts of several branches coexist.

    Examples
    --------
    Two stable parts that touch at a grazing are one, bounded by the outer kinds; the
    unstable part is left out:

    >>> from types import SimpleNamespace as Part
    >>> parts = [Part(stable=True, range=(1.0, 2.0), lower="range", upper="grazing"),
    ...          Part(stable=True, range=(2.0, 3.0), lower="grazing", upper="fold"),
    ...          Part(stable=False, range=(3.0, 4.0), lower="fold", upper="range")]
    >>> stable_parts(Part(parts=lambda: parts))
    [StablePart(range=(1.0, 3.0), lower='range', upper='fold')]
    """
    parts = sorted((p for p in branch.parts() if p.stable), key=lambda p: p.range)
    out = []
    for p in parts:
        if out and p.range[0] <= out[-1].range[1] + 1e-12:
            if p.range[1] > out[-1].range[1]:
                out[-1] = StablePart((out[-1].range[0], p.range[1]), out[-1].lower, p.upper)
            continue
        out.append(StablePart(p.range, p.lower, p.upper))
    return out


def overlay(responses: list[Any]) -> list[CoexistenceRange]:
    """The ranges where two or more responses are stable together (constant membership).

    Parameters
    ----------
    responses : list of beltmdsm.multistability.coexistence.ResponseBranch
        anything with ``name`` and ``stable`` (a list of `StablePart`)

    Returns
    -------
    list of CoexistenceRange
        ascending; a new range starts wherever the set of stable responses changes

    See Also
    --------
    beltmdsm.multistability.stable_ranges.stable_parts

    Examples
    --------
    ``T`` is stable on [1, 3], ``4T`` on [2, 4]: they coexist on [2, 3], bounded by
    the fold where ``4T`` appears and the Neimark-Sacker point where ``T`` ends:

    >>> from types import SimpleNamespace as Response
    >>> t = Response(name="T", stable=[StablePart((1.0, 3.0), "range", "neimark_sacker")])
    >>> t4 = Response(name="4T", stable=[StablePart((2.0, 4.0), "fold", "range")])
    >>> [(c.range, c.responses, c.lower, c.upper) for c in overlay([t, t4])]
    [((2.0, 3.0), ('4T', 'T'), 'fold', 'neimark_sacker')]
    """
    intervals = [(r.name, s) for r in responses for s in r.stable]
    cuts = sorted({v for _, s in intervals for v in s.range})
    segments = []
    for a, b in zip(cuts[:-1], cuts[1:]):
        mid = 0.5 * (a + b)
        active = tuple(sorted({n for n, s in intervals if s.range[0] < mid < s.range[1]}))
        if len(active) < 2:
            continue
        if segments and segments[-1][1] == a and segments[-1][2] == active:
            segments[-1][1] = b
        else:
            segments.append([a, b, active])

    def kind_at(value):
        # the interval end at this value that starts or stops a membership
        for _, s in intervals:
            if s.range[0] == value:
                return s.lower
            if s.range[1] == value:
                return s.upper
        return "range"

    return [CoexistenceRange((a, b), active, kind_at(a), kind_at(b)) for a, b, active in segments]
