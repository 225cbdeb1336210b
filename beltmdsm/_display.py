"""What the results print as their ``repr``: one screen, in the words of the command line.

A result's ``repr`` is a heading line (what was computed, for which model) and at most
`MAX_LINES` indented lines (edges, special points, curves), then how many more there
are; the full content is in the result's attributes and ``as_dict()``. The wording
follows `beltmdsm.cli.text` (which prints the commands' results); the bifurcations
carry the short labels of the continuation literature (`LABELS`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .model import Model

__all__ = ["MAX_LINES", "LABELS", "label", "laws", "intervals", "block"]

#: Indented lines of a ``repr`` at most.
MAX_LINES = 12
#: The short label of each kind of special point (AUTO's and BifurcationKit's names:
#: NS Neimark-Sacker, PD period doubling, LP limit point (fold), GR grazing, BP branch
#: point, HB Hopf; SL, sliding, COCO's and di Bernardo's name for the onset of stick on
#: a slip cycle, grazing-sliding); kinds not listed print in full.
LABELS = {
    "stick_onset": "SL",
    "neimark_sacker": "NS",
    "period_doubling": "PD",
    "fold": "LP",
    "grazing": "GR",
    "branch_point": "BP",
    "hopf": "HB",
    "tangency": "TG",
}


def label(kind: str) -> str:
    """The short label of a kind of special point (`LABELS`), else the kind."""
    return LABELS.get(kind, kind)


def laws(model: Model) -> str:
    """``"coulomb friction, hertz_damp, tension allowed"``."""
    return f"{model.friction} friction, {model.contact}, tension {model.tension}"


def intervals(ranges: Iterable[Sequence[float]], spec: str = ".6g") -> str:
    """``"[1.5, 2], [3, 4.25]"``, or ``"none"``."""
    text = ", ".join(f"[{a:{spec}}, {b:{spec}}]" for a, b in ranges)
    return text or "none"


def number(x: float | None, spec: str = ".6g") -> str:
    """A float as the ``repr`` prints it (``nan`` and ``None`` too)."""
    if x is None:
        return "None"
    return "nan" if math.isnan(x) else f"{x:{spec}}"


def block(head: str, lines: Sequence[str] = (), limit: int = MAX_LINES) -> str:
    """``head``, then at most ``limit`` of ``lines`` indented, then how many more."""
    shown = [f"  {line}" for line in lines[:limit]]
    if len(lines) > limit:
        shown.append(f"  ... and {len(lines) - limit} more")
    return "\n".join([head, *shown])
