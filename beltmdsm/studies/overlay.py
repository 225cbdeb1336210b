"""Stable parts of branches and their overlay: where two or more attractors coexist.

Shared by `beltmdsm.studies.coexistence` (forced responses, which re-exports these)
and `beltmdsm.studies.cycle_coexistence` (steady sliding and self-excited cycles).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = ["StablePart", "CoexistenceRange", "stable_parts", "overlay"]


@dataclass(frozen=True)
class StablePart:
    """A range where a branch is stable, with the kinds of the special points that bound it."""

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
    """The stable parts of a branch, merged where they touch (a grazing between them)."""
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
    """The ranges where two or more responses are stable together (constant membership)."""
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
