"""The text of one cell of ``VALIDATION.md``: ranges, edge differences, edge kinds.

The abbreviations of the edges' kinds in the Floquet and coexistence tables
(`EDGE_ABBREVIATIONS`, `END_ABBREVIATIONS`) and their legends;
`beltmdsm.paper_reports.validation.report` and
`beltmdsm.paper_reports.validation.floquet_report` write the tables.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from ... import intervals
from ...continuation.band_result import Band
from .cases import UNRESOLVED
from .comparison import Comparison, SimulatedRanges
from .results import CaseResult
from .verdicts import Run

__all__ = ["EDGE_ABBREVIATIONS", "EDGE_LEGEND", "END_ABBREVIATIONS", "COEXISTENCE_LEGEND"]


#: The text of a comparison that pairs no edges, by its status.
_STATUS_TEXT = {
    "miss": "miss",
    "false_alarm": "false alarm",
    "both_empty": "both none",
    "no_prediction": "n/a",
}


def num(x):
    return f"{x:.2f}"


def ranges_text(ranges):
    return "n/a" if ranges is None else intervals.format_intervals(ranges, ".2f")


def simulated_text(sim: SimulatedRanges) -> str:
    if not sim.ranges:
        return "none"
    parts = []
    for r in sim.ranges:
        lo = num(r.lower) + ("*" if r.lower_censored else "")
        hi = num(r.upper) + ("*" if r.upper_censored else "")
        parts.append(f"[{lo}, {hi}]")
    return ", ".join(parts)


def delta_text(comp: Comparison) -> str:
    if comp.status != "paired":
        return _STATUS_TEXT[comp.status]
    texts = []
    for e in (comp.lower, comp.upper):
        t = f"{e.delta:+.2f}"
        if e.censored:
            t = f"({t})*"
        if e.from_zero:
            t += "⁰"
        texts.append(t)
    return " / ".join(texts)


def points_text(runs):
    return ", ".join(f"{num(a)}–{num(b)}" if a != b else num(a) for a, b in runs) or "none"


def runs_text(runs):
    names = {
        "continuous_sliding": "sliding",
        "sliding_with_reversals": "reversals",
        "stick_slip": "**stick-slip**",
        "contact_loss": "**contact loss**",
        UNRESOLVED: "**unresolved**",
    }
    return "; ".join(
        f"{names[r]} {num(a)}–{num(b)}" if a != b else f"{names[r]} {num(a)}" for r, a, b in runs
    )


def band_text(band: Band) -> str:
    if not band.unstable:
        return "none"
    text = intervals.format_intervals(band.unstable, ".3f")
    if band.no_periodic_response:
        text += (
            " (none found in " + intervals.format_intervals(band.no_periodic_response, ".3f") + ")"
        )
    return text


#: The kinds of a band's edges (`beltmdsm.continuation.edges.KINDS`, and ``existence`` for an
#: end that is not classified): their abbreviation in the Floquet table and its legend.
EDGE_ABBREVIATIONS = {
    "neimark_sacker": ("NS", "Neimark-Sacker"),
    "period_doubling": ("PD", "period doubling"),
    "fold": ("fold", "fold"),
    "grazing": ("graz", "grazing"),
    "tangency": ("tang", "tangency"),
    "unclassified": ("end", "an end not classified"),
}
#: The legend of `EDGE_ABBREVIATIONS` ("NS = Neimark-Sacker, ...").
EDGE_LEGEND = ", ".join(a if a == w else f"{a} = {w}" for a, w in EDGE_ABBREVIATIONS.values())


def edges_text(band: Band) -> str:
    return ", ".join(f"{e.value:.3f} {EDGE_ABBREVIATIONS[e.kind][0]}" for e in band.edges) or "—"


#: The kinds at the ends of a response's stable part besides the bifurcations: the end
#: of the range studied, a real multiplier through +1 without a turn, a continuation
#: that stopped (`beltmdsm.continuation.branch_result.SpecialPoint`).
END_ABBREVIATIONS = {
    "range": ("end", "the end of the range"),
    "branch_point": ("BP", "branch point"),
    "failed": ("stop", "the continuation stops"),
}
#: The legend of the exact coexistence tables.
COEXISTENCE_LEGEND = ", ".join(
    a if a == w else f"{a} = {w}"
    for key, (a, w) in {**EDGE_ABBREVIATIONS, **END_ABBREVIATIONS}.items()
    if key != "unclassified"
)


def kind(kind: str) -> str:
    return {**EDGE_ABBREVIATIONS, **END_ABBREVIATIONS}.get(kind, (kind, kind))[0]


def exact_text(c: CaseResult) -> str:
    """The exact coexistence ranges of a case: range, responses, kinds of both edges."""
    return (
        "; ".join(
            f"[{r.range[0]:.3f}, {r.range[1]:.3f}] {' + '.join(r.responses)} "
            f"({kind(r.lower)} / {kind(r.upper)})"
            for r in c.exact.ranges
        )
        or "none"
    )


def tolerance_text(cases):
    values = sorted({e.tolerance for c in cases for e in c.explanations})
    if not values:
        return "(Omega dt)^2 / 4"
    if values[0] == values[-1]:
        return f"(Omega dt)^2 / 4 = {values[0]:.1e}"
    return f"(Omega dt)^2 / 4, {values[0]:.1e} to {values[-1]:.1e}"


def run_text(run: Run) -> str:
    text = intervals.format_intervals(run.ranges, ".2f")
    if run.unresolved:
        text += f" ({len(run.unresolved)} unresolved)"
    return text


def floquet_delta_text(comp: Comparison) -> str:
    if comp.status != "paired":
        return _STATUS_TEXT[comp.status]
    return " / ".join(
        f"({e.delta:+.3f})*" if e.censored else f"{e.delta:+.3f}" for e in (comp.lower, comp.upper)
    )
