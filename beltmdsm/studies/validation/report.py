"""`render_markdown`: ``VALIDATION.md``, the tables of the validation of Figs. 2b and 17-21.

The Floquet band against the runs and the analyses (Sects. 4.2-4.3 exactly), then the
analyses (Eqs. 22-28 and the consistent MDSM) against the runs from rest, the regimes
next to what the paper reports in Appendix A.5, and the rules of
`beltmdsm.studies.validation.cases`.
"""

from __future__ import annotations

from collections.abc import Sequence

from ... import intervals
from ...continuation.band import Band
from ...periodic.floquet import PERTURBATION
from ...periodic.locked import LOCK_LIMIT
from ...run.summary import PEAK_PRESENT_RATIO, TRANSIENT_DECAYED
from ..coexistence import DEFAULT_STEP
from .cases import ANALYSES, DEFINITIONS, FLOQUET_DEFINITIONS, FLOQUET_TOL, UNRESOLVED
from .comparison import Comparison, SimulatedRanges, regime_runs
from .exact import STATUSES
from .results import CaseResult, Validation
from .verdicts import Run

#: The text of a comparison that pairs no edges, by its status.
_STATUS_TEXT = {
    "miss": "miss",
    "false_alarm": "false alarm",
    "both_empty": "both none",
    "no_prediction": "n/a",
}


def _num(x):
    return f"{x:.2f}"


def _ranges_text(ranges):
    return "n/a" if ranges is None else intervals.format_intervals(ranges, ".2f")


def _simulated_text(sim: SimulatedRanges) -> str:
    if not sim.ranges:
        return "none"
    parts = []
    for r in sim.ranges:
        lo = _num(r.lower) + ("*" if r.lower_censored else "")
        hi = _num(r.upper) + ("*" if r.upper_censored else "")
        parts.append(f"[{lo}, {hi}]")
    return ", ".join(parts)


def _delta_text(comp: Comparison) -> str:
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


def _points_text(runs):
    return ", ".join(f"{_num(a)}–{_num(b)}" if a != b else _num(a) for a, b in runs) or "none"


def _runs_text(runs):
    names = {
        "continuous_sliding": "sliding",
        "sliding_with_reversals": "reversals",
        "stick_slip": "**stick-slip**",
        "contact_loss": "**contact loss**",
        UNRESOLVED: "**unresolved**",
    }
    return "; ".join(
        f"{names[r]} {_num(a)}–{_num(b)}" if a != b else f"{names[r]} {_num(a)}" for r, a, b in runs
    )


def _band_text(band: Band) -> str:
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


def _edges_text(band: Band) -> str:
    return ", ".join(f"{e.value:.3f} {EDGE_ABBREVIATIONS[e.kind][0]}" for e in band.edges) or "—"


#: The kinds at the ends of a response's stable part besides the bifurcations: the end
#: of the range studied, a real multiplier through +1 without a turn, a continuation
#: that stopped (`beltmdsm.continuation.branch.SpecialPoint`).
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


def _kind(kind: str) -> str:
    return {**EDGE_ABBREVIATIONS, **END_ABBREVIATIONS}.get(kind, (kind, kind))[0]


def _exact_text(c: CaseResult) -> str:
    """The exact coexistence ranges of a case: range, responses, kinds of both edges."""
    return (
        "; ".join(
            f"[{r.range[0]:.3f}, {r.range[1]:.3f}] {' + '.join(r.responses)} "
            f"({_kind(r.lower)} / {_kind(r.upper)})"
            for r in c.exact.ranges
        )
        or "none"
    )


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
        "Exact: every periodic response that `beltmdsm.studies.coexistence.coexistence` "
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
        "(`beltmdsm.studies.validation.exact.range_tolerance`, "
        f"{_tolerance_text(cases)} of the amplitude); otherwise it is *not settled*, *not "
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
            f"| {c.case.name} | {_exact_text(c)} | "
            f"{intervals.format_intervals(co.ranges, '.2f')} | {', '.join(by) or '—'} | "
            f"{counts} | {_points_text([(v, v) for v in co.unsettled])} |"
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
                    f"[{s.range[0]:.3f}, {s.range[1]:.3f}] ({_kind(s.lower)} / {_kind(s.upper)})"
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
                f"| {c.case.name} | {_points_text([(first, last)])} | {text} | "
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


def _tolerance_text(cases):
    values = sorted({e.tolerance for c in cases for e in c.explanations})
    if not values:
        return "(Omega dt)^2 / 4"
    if values[0] == values[-1]:
        return f"(Omega dt)^2 / 4 = {values[0]:.1e}"
    return f"(Omega dt)^2 / 4, {values[0]:.1e} to {values[-1]:.1e}"


def _run_text(run: Run) -> str:
    text = intervals.format_intervals(run.ranges, ".2f")
    if run.unresolved:
        text += f" ({len(run.unresolved)} unresolved)"
    return text


def _floquet_delta_text(comp: Comparison) -> str:
    if comp.status != "paired":
        return _STATUS_TEXT[comp.status]
    return " / ".join(
        f"({e.delta:+.3f})*" if e.censored else f"{e.delta:+.3f}" for e in (comp.lower, comp.upper)
    )


def _floquet_sections(results: Validation) -> list[str]:
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
            f"| {c.case.name} | {_band_text(band)} | {_edges_text(band)} | "
            + " | ".join(_run_text(runs[k]) for k in ("periodic", "rest", "up", "down"))
            + f" | {intervals.format_intervals(c.coexistence.ranges, '.2f')} | "
            f"{_run_text(runs['rest_other'])} |"
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
            f"{_points_text([(v, v) for v in c.band_disagreements])} |"
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
            f"| {c.case.name} | {_band_text(c.floquet.band)} | "
            + " | ".join(_floquet_delta_text(c.floquet_comparison[k]) for k, _, _ in ANALYSES)
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


def _closer_sentence(cases: Sequence[CaseResult], key: str, reference: str, step: float) -> str:
    """One generated sentence: where ``key`` is closer to the simulation than ``reference``."""
    better, worse, tie, none = [], [], [], []
    for c in cases:
        if not c.comparable:
            continue
        ours, theirs = c.comparison[key].disagreement, c.comparison[reference].disagreement
        if ours is None or theirs is None:
            none.append(c.case.name)
            continue
        d = ours - theirs
        # Differences within one grid step are below the resolution of the sweep.
        (better if d < -step else worse if d > step else tie).append(c.case.name)
    label = {k: lab for k, lab, _ in ANALYSES}

    def names(xs):
        return ", ".join(xs) if xs else "none"

    if none and not (better or worse or tie):
        return (
            f"{label[key]} and {label[reference]} are not compared: one of them gives no "
            f"prediction in every comparable case ({names(none)})."
        )
    skipped = f" Not compared where one gives no prediction: {names(none)}." if none else ""
    return (
        f"By the disagreement length, {label[key]} is closer to the simulation than "
        f"{label[reference]} by more than one grid step ({step:g} m/s) in {len(better)} "
        f"of {len(better) + len(worse) + len(tie)} comparable cases ({names(better)}), "
        f"farther in {len(worse)} ({names(worse)}) and within one step in "
        f"{len(tie)} ({names(tie)})." + skipped
    )


def render_markdown(results: Validation, quick: bool) -> str:
    """``VALIDATION.md``: tables of ranges, edge differences, the summary and definitions.

    Parameters
    ----------
    results : Validation
        from `validate`
    quick : bool
        the mode the file names (and its command)

    Returns
    -------
    str
        the Markdown text
    """
    res = results.resolution
    cases = results.cases
    step = res.step
    tension = results.tension
    command = (
        "python -m derive validate"
        + (" --quick" if quick else "")
        + (f" --tension {tension}" if tension != "allowed" else "")
    )
    law = {
        "allowed": "`allowed` (Eq. 1 as printed: the contact force can pull)",
        "clipped": "`clipped` (a contact that cannot pull: max(F, 0), the surfaces "
        "separate where Eq. 1 would pull)",
    }[tension]
    lines = [
        "# Validation: Floquet stability, the simulated omega1 peak and the analyses",
        "",
        f"Generated by `{command}` (`beltmdsm/studies/validation/`); do not edit by hand, rerun "
        "the command.",
        "",
        "For the base set (Fig. 2b) and every case of Appendix A.5 (Figs. 17-21): where the "
        "periodic response of Eq. (4) is unstable (Floquet multipliers, exact; "
        "`beltmdsm.periodic.floquet`), where runs started on it, from rest and along continued "
        "sweeps show the omega1 peak in the spectrum of X1', where two attractors coexist, "
        "and how far each analysis' unstable range lies from the Floquet band (the "
        "quantity it approximates) and from the runs from rest.",
        "",
        "## Resolution",
        "",
        f"* Mode: {'quick' if quick else 'full'}. Grid: `Vb` = {step:g}, {2 * step:g}, ... "
        f"m/s (step h = {step:g} m/s, so every simulated edge is known to ± {step / 2:g} "
        f"m/s), up to max({res.min_top:g}, {res.top_factor:g} × the largest predicted "
        f"edge), extended by × {res.extend_factor:g} while the top point is not a sliding "
        f"point without the peak (cap {res.vb_cap:g} m/s; not for the cases marked †).",
        f"* Tension law (docs/modelling.md#tension): {law}. The paper's analyses (A1-A4) "
        "linearise at the equilibrium, where the contact force is positive: the same under "
        "both laws."
        + (
            " The consistent MDSM assumes a harmonic fast normal force, which the "
            "clip makes non-harmonic where it cuts it: n/a there "
            "(`beltmdsm.prediction.prediction.CLIPPED_MDSM`)."
            if tension == "clipped"
            else ""
        ),
        f"* Runs: {res.t_end:g} s from the unforced equilibrium, steady window after "
        f"{0.3 * res.t_end:g} s, solver `{res.settings.solver}` ({res.settings.method}, "
        f"rtol = atol = {res.rtol:g}), sampling {res.settings.dt:g} s.",
        f"* Peak criterion: omega1 peak ≥ {PEAK_PRESENT_RATIO:g} × the peak at Omega "
        "(`beltmdsm.run.summary.PEAK_PRESENT_RATIO`).",
        "* Grid per case: "
        + "; ".join(
            f"{c.case.name} {_num(c.Vb[0])}–{_num(c.Vb[-1])} ({len(c.Vb)} points)" for c in cases
        )
        + ".",
        "",
        "Analyses:",
        "",
    ]
    lines += [f"* **{lab}**: {desc}." for _, lab, desc in ANALYSES]
    lines += [""] + _floquet_sections(results)
    lines += [
        "# Against the runs from rest",
        "",
        "The tables the package has kept since before Floquet: each analysis against "
        "the run from rest, which finds whichever attractor its start leads to.",
    ]
    header = "| case | figure | simulated | " + " | ".join(lab for _, lab, _ in ANALYSES) + " |"
    rule = "|" + "---|" * (3 + len(ANALYSES))
    lines += [
        "",
        "## Unstable ranges [m/s]",
        "",
        "Simulated: the omega1-peak ranges (edges ± h/2; `*` censored). Predicted: "
        "the unstable ranges; `none`: no unstable belt speed.",
        "",
        header,
        rule,
    ]
    for c in cases:
        name = c.case.name + ("" if c.comparable else " †")
        lines.append(
            f"| {name} | {c.case.figure} | {_simulated_text(c.simulated)} | "
            + " | ".join(_ranges_text(c.predicted[k]) for k, _, _ in ANALYSES)
            + " |"
        )
    lines += [
        "",
        "## Edge differences Δ = predicted − simulated [m/s], lower / upper",
        "",
        f"Each Δ is known to ± {step / 2:g} m/s. `⁰`: the predicted lower edge is "
        f"Vb = 0 (unstable from rest), compared with the simulated lower edge "
        f"(the lowest simulated Vb is {step:g} m/s). `( )*`: censored, not in the "
        "MAE. miss: no predicted range, a simulated one; false alarm: the reverse.",
        "",
        "| case | " + " | ".join(lab for _, lab, _ in ANALYSES) + " |",
        "|" + "---|" * (1 + len(ANALYSES)),
    ]
    for c in cases:
        if not c.comparable:
            lines.append(f"| {c.case.name} † | " + " | ".join("—" for _ in ANALYSES) + " |")
            continue
        lines.append(
            f"| {c.case.name} | "
            + " | ".join(_delta_text(c.comparison[k]) for k, _, _ in ANALYSES)
            + " |"
        )
    summary = results.summary
    lines += [
        "",
        "## Summary per analysis",
        "",
        "| analysis | MAE of edges [m/s] | edges *n* | paired | miss | false alarm | "
        "both none | mean \\|P Δ S\\| [m/s] |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for key, lab, _ in ANALYSES:
        s = summary[key]
        mae = "—" if s.mae is None else _num(s.mae)
        dis = "—" if s.mean_disagreement is None else _num(s.mean_disagreement)
        lines.append(
            f"| {lab} | {mae} | {s.n_edges} | {s.paired} | {s.miss} | "
            f"{s.false_alarm} | {s.both_empty} | {dis} |"
        )
    n_comp = sum(c.comparable for c in cases)
    for key, lab, _ in ANALYSES:
        if summary[key].no_prediction:
            lines.append(
                f"\n{lab} gives no prediction in {summary[key].no_prediction} "
                f"comparable case(s) (n/a); its columns count the other "
                f"{summary[key].n_cases}."
            )
    lines += [
        "",
        f"Over {n_comp} comparable cases of {len(cases)}.",
        _closer_sentence(cases, "consistent_mdsm", "paper_tangential_paper", step),
        _closer_sentence(cases, "consistent_mdsm", "paper_coupled_paper", step),
        "",
    ]
    lines += [
        "## Regimes and the paper's statements",
        "",
        "The third column counts every point that shows the peak, whatever its regime "
        "(not used in the comparison).",
        "",
        "| case | regimes over the grid (Vb in m/s) | peak, any regime | paper (Appendix A.5) |",
        "|---|---|---|---|",
    ]
    for c in cases:
        rest = c.runs["rest"]
        note = _runs_text(regime_runs(c.Vb, rest.regime))
        anywhere = [(a, b) for r, a, b in regime_runs(c.Vb, rest.present) if r == "True"]
        if c.harmonics:
            note += (
                "; † not comparable: "
                + ", ".join(f"{k} Omega = {_num(w)} rad/s" for k, w in c.harmonics)
                + " lies in the omega1 band"
            )
        elif not c.comparable:
            note += "; † not comparable: no sliding point"
        lines.append(
            f"| {c.case.name} | {note} | {_points_text(anywhere)} | "
            f"{c.case.figure}: {c.case.paper} |"
        )
    lines += [
        "",
        "## Definitions (fixed before the numbers were looked at)",
        "",
        FLOQUET_DEFINITIONS.format(
            cap=res.vb_cap,
            tol=FLOQUET_TOL,
            perturbation=PERTURBATION,
            window=res.settings.window_start,
            decayed=TRANSIENT_DECAYED,
            limit=LOCK_LIMIT,
            seeds=DEFAULT_STEP,
        ),
        DEFINITIONS.format(ratio=PEAK_PRESENT_RATIO, cap=res.vb_cap),
    ]
    return "\n".join(lines)
