"""The Floquet half of ``VALIDATION.md``: the runs against the band, the mismatches, the
exact and simulated coexistence, and the analyses against Floquet (`floquet_sections`).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from ... import intervals
from ...multistability.coexistence import DEFAULT_STEP
from ...periodic.locked import LOCK_LIMIT
from .cases import ANALYSES, FLOQUET_TOL
from .cells import (
    COEXISTENCE_LEGEND,
    EDGE_LEGEND,
    band_text,
    edges_text,
    exact_text,
    floquet_delta_text,
    kind,
    points_text,
    run_text,
    tolerance_text,
)
from .exact import STATUSES
from .results import CaseResult, Validation

__all__: list[str] = []


def _explanation_groups(c: CaseResult) -> list[tuple[float, float, str]]:
    """Consecutive grid points whose runs have the same explanations, as one row each:
    ``(first, last, text)``."""
    grid = c.Vb
    step = grid[1] - grid[0] if len(grid) > 1 else 1.0
    by_point: dict = {}
    for e in c.explanations:
        by_point.setdefault(e.Vb, []).append(e)
    groups = []
    for value in sorted(by_point):
        parts = []
        for e in by_point[value]:
            status = e.response if e.explained else e.status.replace("_", " ")
            parts.append(f"{e.run}: {status}")
        text = "; ".join(parts)
        if groups and groups[-1][2] == text and value - groups[-1][1] <= step * (1 + 1e-9):
            groups[-1][1] = value
        else:
            groups.append([value, value, text])
    return [tuple(g) for g in groups]


def _coexistence_section(results: Validation) -> list[str]:
    """The exact coexistence of each case beside the simulated one, point by point."""
    cases = results.cases
    lines = [
        "",
        "## Coexistence: exact and simulated",
        "",
        "Exact: every periodic response that `beltmdsm.multistability.coexistence.coexistence` "
        "finds in `Vb` over the case's grid cells (seeds every "
        f"{DEFAULT_STEP:g} m/s: shooting, runs from rest and ladders continued up and "
        "down on the period map; locks looked for up to "
        f"{LOCK_LIMIT} periods), each continued as a branch, and the ranges where "
        "two or more are stable: the responses that coexist there (`T`: period 2 pi / "
        "Omega; `kT`: phase-locked, numbered where several share k) and the kinds of "
        f"both edges ({COEXISTENCE_LEGEND}). Simulated: the grid points where the "
        "periodic start stays on a stable periodic response while a run from rest or a "
        "continued sweep shows the omega1 peak (definitions below). A run there is "
        "*explained* by a computed response that is stable at its `Vb` and whose range of "
        "X1' its steady window spans, to the sampling error "
        "(`beltmdsm.paper_reports.validation.exact.range_tolerance`, "
        f"{tolerance_text(cases)} of the amplitude); otherwise it is *not settled*, *not "
        "locked* or *unexplained*, with the reason.",
        "",
        "| case | exact coexistence [m/s]: responses (edges) | simulated [m/s] | shown by "
        "| runs: explained / not settled / not locked / unexplained | unsettled points "
        "(slow attraction) |",
        "|---|---|---|---|---|---|",
    ]
    for c in cases:
        co = c.coexistence
        by = sorted({k for ks in co.found_by.values() for k in ks})
        counts = " / ".join(str(sum(e.status == s for e in c.explanations)) for s in STATUSES)
        lines.append(
            f"| {c.case.name} | {exact_text(c)} | "
            f"{intervals.format_intervals(co.ranges, '.2f')} | {', '.join(by) or '—'} | "
            f"{counts} | {points_text([(v, v) for v in co.unsettled])} |"
        )
    lines += [
        "",
        "### The responses found",
        "",
        "Each branch's stable parts, with the kinds of the edges that bound them; a response "
        "that is nowhere stable in the range is listed with its extent.",
        "",
        "| case | response | periods | stable in [m/s] (edges) | exists in [m/s] |",
        "|---|---|---|---|---|",
    ]
    for c in cases:
        for r in c.exact.responses:
            stable = (
                "; ".join(
                    f"[{s.range[0]:.3f}, {s.range[1]:.3f}] ({kind(s.lower)} / {kind(s.upper)})"
                    for s in r.stable
                )
                or "nowhere"
            )
            lo, hi = r.branch.value_range()
            lines.append(
                f"| {c.case.name} | {r.name} | {r.branch.periods} | {stable} | "
                f"[{lo:.3f}, {hi:.3f}] |"
            )
    lines += [
        "",
        "### Each simulated coexistence point",
        "",
        "Per run that shows the peak: the computed response it is on, *not settled* (the "
        "closest stable response attracts too slowly for the run to have reached it), *not "
        "locked* (neither the run nor a seed of the exact study next to it, of the same kind "
        "of run, locks within 12 periods, and their classification by Lyapunov exponents "
        "and returns after any number of periods, `beltmdsm.attractors.classification.classify`, "
        "names no long lock: the attractor's kind is given), or *unexplained*. A long lock "
        "that the classification finds is named kT (classified). Consecutive points "
        "with the same answers share a row; the largest deviation of a run's X1' range "
        "from its response's, over the response's amplitude, is given.",
        "",
        "| case | Vb [m/s] | runs | largest deviation |",
        "|---|---|---|---|",
    ]
    for c in cases:
        for first, last, text in _explanation_groups(c):
            inside = [e for e in c.explanations if first <= e.Vb <= last and e.explained]
            worst = max((e.deviation for e in inside), default=None)
            lines.append(
                f"| {c.case.name} | {points_text([(first, last)])} | {text} | "
                + ("—" if worst is None else f"{worst:.1e}")
                + " |"
            )
    unexplained = [(c, e) for c in cases for e in c.explanations if not e.explained]
    if unexplained:
        lines += ["", "Why each run that no response explains is not explained:", ""]
        lines += [
            f"* {c.case.name}, Vb = {e.Vb:g} m/s, {e.run}: {e.reason}." for c, e in unexplained
        ]
    lines.append("")
    return lines


def floquet_sections(results: Validation) -> list[str]:
    """The Floquet tables of `render_markdown`: the runs, mismatches, coexistence, edges."""
    cases, step = results.cases, results.resolution.step
    other = {"allowed": "clipped", "clipped": "allowed"}[results.tension]
    lines = [
        "## Floquet: where the periodic response is unstable, and what the runs find",
        "",
        "The Floquet band is exact (edges to "
        f"{FLOQUET_TOL:g} m/s, ends of the response to about 1e-6; kinds: {EDGE_LEGEND}). "
        "The runs' ranges hold the grid points that show the omega1 peak (resolved, any "
        f"regime), each ± {step / 2:g} m/s. Coexistence: a stable "
        "periodic response beside a self-excited oscillation (definitions below).",
        "",
        "| case | Floquet unstable [m/s] | edges | periodic start | from rest | up sweep "
        f"| down sweep | coexistence (runs) | from rest, {other} |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for c in cases:
        band, runs = c.floquet.band, c.runs
        lines.append(
            f"| {c.case.name} | {band_text(band)} | {edges_text(band)} | "
            + " | ".join(run_text(runs[k]) for k in ("periodic", "rest", "up", "down"))
            + f" | {intervals.format_intervals(c.coexistence.ranges, '.2f')} | "
            f"{run_text(runs['rest_other'])} |"
        )
    ms = results.mismatch_summary
    lines += [
        "",
        "## The periodic start against Floquet",
        "",
        f"**{len(ms.mismatches)} mismatches** in {ms.checked} compared grid points "
        f"of {ms.cases} cases: the run started on the perturbed periodic response "
        "shows the omega1 peak exactly where Floquet says unstable"
        + (" everywhere it is compared." if not ms.mismatches else ", except at:"),
    ]
    lines += [
        f"* {name}, Vb = {m.Vb:g} m/s: Floquet {m.floquet}, peak "
        f"{'present' if m.peak else 'absent'}."
        for name, m in ms.mismatches
    ]
    if ms.not_counted:
        lines.append("")
        lines.append(
            "Not counted (an excitation harmonic in the omega1 band): "
            + "; ".join(
                f"{c.case.name} ({len(c.mismatches.mismatches)} of "
                f"{c.mismatches.checked} points differ)"
                for c in cases
                if c.case.name in ms.not_counted
            )
            + "."
        )
    lines += [
        "",
        "| case | compared | near an edge | no verdict | unresolved | band and grid disagree |",
        "|---|---|---|---|---|---|",
    ]
    for c in cases:
        m = c.mismatches
        lines.append(
            f"| {c.case.name} | {m.checked} | {len(m.near_edge)} | "
            f"{len(m.no_verdict)} | {len(m.unresolved)} | "
            f"{points_text([(v, v) for v in c.band_disagreements])} |"
        )
    lines += _coexistence_section(results)
    lines += [
        "",
        "## The analyses against Floquet",
        "",
        "Δ = predicted − Floquet [m/s], lower / upper, exact on both sides; `( )*`: censored.",
        "",
        "| case | Floquet | " + " | ".join(lab for _, lab, _ in ANALYSES) + " |",
        "|" + "---|" * (2 + len(ANALYSES)),
    ]
    for c in cases:
        lines.append(
            f"| {c.case.name} | {band_text(c.floquet.band)} | "
            + " | ".join(floquet_delta_text(c.floquet_comparison[k]) for k, _, _ in ANALYSES)
            + " |"
        )
    fs = results.floquet_summary
    lines += [
        "",
        "| analysis | MAE of edges [m/s] | largest \\|Δ\\| | edges *n* | paired | miss "
        "| false alarm | both none | mean \\|P Δ F\\| [m/s] |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for key, lab, _ in ANALYSES:
        s = fs[key]
        cell = [
            "—" if x is None else f"{x:.3f}" for x in (s.mae, s.max_abs_delta, s.mean_disagreement)
        ]
        lines.append(
            f"| {lab} | {cell[0]} | {cell[1]} | {s.n_edges} | {s.paired} | "
            f"{s.miss} | {s.false_alarm} | {s.both_empty} | {cell[2]} |"
        )
    lines += ["", f"Over all {len(cases)} cases.", ""]
    return lines
