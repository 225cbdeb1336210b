"""The readable text of each command's result, and JSON-able values.

Every function takes a result and returns the lines the command prints; none computes.
The result types are imported for the annotations only: a command loads this module
with what it runs, not with every analysis (``sweep`` would otherwise import the
predictions, SciPy's optimizers among them, before its first point).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from ..intervals import format_intervals

if TYPE_CHECKING:
    from ..continuation.band import Band
    from ..continuation.branch import Branch
    from ..continuation.floquet_map import FloquetMap
    from ..model import Model
    from ..periodic.floquet import Floquet
    from ..prediction.prediction import Prediction
    from ..run.summary import Summary
    from ..simulation import Simulation
    from ..studies.coexistence import Coexistence
    from ..studies.responses import ResponseSet
    from ..studies.sweep import Sweep
    from ..studies.validation import Validation

__all__ = [
    "jsonable",
    "peak_verdict",
    "simulation",
    "floquet",
    "cycle",
    "kind",
    "band",
    "responses",
    "branch",
    "coexistence",
    "floquet_map",
    "sweep",
    "sweep_validation",
    "prediction",
    "validation",
    "PAPER_STATEMENT",
]

#: What the paper says of the omega1 peak of Fig. 2b, printed beside a sweep over Vb.
PAPER_STATEMENT = "the omega1 peak 'vanishes after Vb ~ 8 m/s' (Sect. 3, Fig. 2b)"


def jsonable(x: Any) -> Any:
    """``x`` with numpy scalars as Python numbers, tuples as lists and NaN or inf as None."""
    if isinstance(x, dict):
        return {k: jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, (np.floating, float)):
        return None if not np.isfinite(x) else float(x)
    if isinstance(x, (np.integer, np.bool_)):
        return x.item()
    return x


def peak_verdict(summary: Summary) -> str:
    """The verdict on the omega1 peak: unresolved (and why), PRESENT or absent.

    A peak is called friction-induced vibration only where it is present, resolved,
    and the run's energy balance closes within its bound; without a forced peak
    above the noise floor, the verdict says that it was judged against the floor.
    """
    if not summary.resolved:
        return f"unresolved ({summary.unresolved_reason})"
    floor = f"the noise floor {summary.noise_floor:.2g} m/s of the tolerances"
    if summary.omega1_peak_present:
        if not summary.energy_ok:
            return "PRESENT, but not trusted (the energy balance does not close; see the warning)"
        if not summary.forced_peak:
            return f"PRESENT (friction-induced vibration, above {floor}; no forced peak)"
        return "PRESENT (friction-induced vibration)"
    if not summary.forced_peak:
        return f"absent (no forced peak either: nothing rises above {floor})"
    return "absent"


def _peak(amplitude: float, at: float | None = None) -> str:
    """``"A m/s at W rad/s"``, or ``"not read"`` where the window could not read it."""
    if not math.isfinite(amplitude):
        return "not read"
    return f"{amplitude:.6g} m/s" + (f" at {at:.6g} rad/s" if at is not None else "")


def spectrum_line(sim: Simulation) -> str:
    """The line of the readable summary on the X1' spectrum and the omega1 verdict."""
    p, s = sim.params, sim.summary
    return (
        f"X1' spectrum: omega1 peak {_peak(s.peak_omega1, s.omega1_peak_at)} "
        f"(omega1 = {p['omega1']:g}), Omega peak {_peak(s.peak_Omega)} (Omega = "
        f"{p['Omega_t']:g}); omega1 peak {peak_verdict(s)}"
    )


def simulation(sim: Simulation, out: dict, modulation: bool) -> str:
    """The readable summary of ``simulate``."""
    p, s = sim.params, sim.summary
    e = s.energy
    fractions = s.time_fraction
    if sim.tension == "clipped":
        force = (
            f"normal force: min {s.min_normal_force:.4g} m/s^2 (clipped: the contact "
            f"cannot pull; separated {100 * fractions.get('separated', 0.0):.1f}% of the "
            f"steady window, {s.n_separations} separations)"
        )
    else:
        force = (
            f"normal force: min {s.min_normal_force:.4g} m/s^2, negative (tensile, "
            f"Eq. 1 as printed) {100 * s.tension_fraction:.1f}% of the steady window"
        )
    lines = [
        f"Eq. (4), {sim.contact}, tension {sim.tension}, Vb = {p['Vb']:g} m/s, "
        f"t = 0..{s.t_end:g} s (steady window from {s.t_discard:g} s), "
        f"solver: {s.solver}",
        f"status: {sim.status} ({sim.message})",
        *(
            [
                f"start: steady sliding is unstable here; the run starts on it moved by "
                f"{s.start_perturbation:g} along its unstable direction "
                "(beltmdsm/simulation.py, START_PERTURBATION)"
            ]
            if s.start_perturbation > 0
            else []
        ),
        f"regime: {s.regime}  (time in "
        + "/".join(fractions)
        + ": "
        + "/".join(f"{100 * v:.1f}%" for v in fractions.values())
        + ")",
        f"switches: {s.n_switches} (reversals {s.n_reversals}, sticks {s.n_sticks}, "
        f"contact losses {s.n_contact_losses}, separations {s.n_separations}, "
        f"Zeno limits {s.n_zeno})",
        spectrum_line(sim),
        f"energy balance: residual {s.energy_residual:.3g}, bound {s.energy_bound:.2g} "
        f"({'closes' if s.energy_ok else 'DOES NOT CLOSE'}; dE = {e.energy_change:.6g}, "
        f"W_in = {e.work_input:.6g}, W_visc = {e.work_viscous:.6g}, "
        f"W_fric = {e.work_friction:.6g})",
        force,
        f"Vr range in the window: {s.vr_min:.4g} .. {s.vr_max:.4g} m/s; "
        f"mean friction {s.mean_friction:.6g} m/s^2",
    ]
    if modulation:
        nan = float("nan")
        lines.append(
            "mu_eff over 2pi/Omega: {:.5g} +- {:.3g}; over 2pi/omega1: {:.5g} +- {:.3g}".format(
                *(
                    out.get(f"mu_eff_{t}_{s}", nan)
                    for t in ("Omega", "omega1")
                    for s in ("mean", "std")
                )
            )
        )
        if out.get("modulation_error"):
            lines.append(f"not computed: {out['modulation_error']}")
    lines.append(f"wall time {s.wall_s:.2f} s")
    lines += [f"warning: {w}" for w in s.warnings]
    return "\n".join(lines)


def floquet(f: Floquet) -> str:
    """The readable result of ``floquet``."""
    if f.autonomous:
        return cycle(f)
    resp = f.response
    p = resp.model.params
    mus = ", ".join(f"{z.real:.6g}{z.imag:+.6g}j" for z in f.multipliers)
    per = "per period" if resp.periods == 1 else f"per {resp.periods} periods"
    lines = [
        f"periodic response of Eq. (4), {resp.model.friction} friction, "
        f"{resp.model.contact}, tension "
        f"{resp.model.tension}, Vb = {p['Vb']:g} m/s: period {f.period:.6g} s, "
        f"{f.n_reversals} reversals and {f.n_sticks} sticks {per}, Newton "
        f"{resp.iterations} iterations (residual {resp.residual:.1e}), "
        f"{f.engine} path (beltmdsm/periodic/periodmap.py)"
    ]
    if f.grazing is not None:
        lines.append(
            f"GRAZING: a reversal at t = {f.grazing['t']:.6g} s is reached with a "
            f"vanishing acceleration (ratio {f.grazing['ratio']:.1e}); no multiplier "
            "is reported"
        )
    else:
        lines += [
            f"Floquet multipliers: {mus}",
            f"largest |mu| = {f.max_abs_multiplier:.6g}: "
            f"{'stable' if f.stable else 'UNSTABLE'}{_isolation(f)}; growth rate "
            f"{f.growth_rate:.6g} 1/s, critical pair at {f.frequency:.6g} rad/s "
            f"(omega1 = {p['omega1']:g}; modulo {2 * math.pi / f.period:.6g})",
        ]
    return "\n".join(lines)


def cycle(f: Floquet) -> str:
    """The readable result of ``floquet`` for a self-excited cycle (no excitation)."""
    c = f.response.cycle
    m = c.model
    mus = ", ".join(f"{z.real:.6g}{z.imag:+.6g}j" for z in f.multipliers)
    lines = [
        f"self-excited cycle of Eq. (4) without excitation, {m.friction} friction, "
        f"{m.contact}, Vb = {m['Vb']:g} m/s: period {c.period:.8g} s (found), "
        f"{c.n_reversals} reversals and {c.n_sticks} sticks per period (stick "
        f"{c.stick_time:.6g} s), Newton {c.iterations} iterations (residual "
        f"{c.residual:.1e}) (beltmdsm/cycles/cycle.py)",
        f"X1 in [{c.x1_range[0]:.6g}, {c.x1_range[1]:.6g}] m, X1' in "
        f"[{c.velocity_range[0]:.6g}, {c.velocity_range[1]:.6g}] m/s, largest Vr "
        f"{c.max_relative_velocity:.6g} m/s",
    ]
    if f.grazing is not None:
        lines.append(
            f"GRAZING: Vr = 0 is reached at t = {f.grazing['t']:.6g} s with a vanishing "
            f"acceleration (ratio {f.grazing['ratio']:.1e}); no multiplier is reported"
        )
        return "\n".join(lines)
    mu1 = c.trivial_multiplier
    lines += [
        f"Floquet multipliers (without the trivial one): {mus}",
        f"trivial multiplier {mu1.real:.12g}{mu1.imag:+.1e}j (|mu - 1| = "
        f"{abs(mu1 - 1):.1e}: the accuracy)",
        f"largest |mu| = {f.max_abs_multiplier:.6g}: {'stable' if f.stable else 'UNSTABLE'}",
    ]
    if c.stick_collapses:
        lines.append("a stick phase collapses the velocity perturbation: one multiplier is 0")
    return "\n".join(lines)


def _isolation(f) -> str:
    """What a multiplier 1 (to `ISOLATION_TOL`) means: the response is not isolated and
    its multipliers cannot decide its stability."""
    from ..periodic.periodmap import ISOLATION_TOL

    mus = np.asarray(f.multipliers, dtype=complex)
    if mus.size and np.min(np.abs(mus - 1.0)) <= ISOLATION_TOL:
        return " (a multiplier is 1, I - M singular: not isolated, its linear stability undecided)"
    return ""


_SIDES = {
    (False, True): "unstable above",
    (True, False): "unstable below",
    (False, False): "stable on both sides",
    (True, True): "unstable on both sides",
}


def kind(name: str, frequency: float | None = None) -> str:
    """A bifurcation kind as the text prints it (a Neimark-Sacker pair with its frequency)."""
    if name == "neimark_sacker" and frequency is not None:
        return f"neimark_sacker at {frequency:.4g} rad/s"
    return name


def _laws(model: Model) -> str:
    """The model's laws and the Floquet path they take, as the headers print them."""
    from ..periodic.periodmap import engine_of

    return (
        f"{model.friction} friction, {model.contact}, tension {model.tension}; "
        f"{engine_of(model)} path"
    )


def _name(periods: int) -> str:
    return "T" if periods == 1 else f"{periods}T"


def band(result: Band, lo: float, hi: float) -> str:
    """The readable result of ``floquet-band``.

    Values are printed to the digits of the edges' tolerance (at least 4 decimals), so
    that two edges more than a tolerance apart never print alike.
    """
    spec = f".{max(4, math.ceil(-math.log10(result.tol)) + 1)}f"
    what = "periodic response" if result.periods == 1 else f"{_name(result.periods)} response"
    lines = [
        f"{what} unstable (or absent) for {result.param} in "
        f"{format_intervals(result.unstable, spec)} of {lo:g}..{hi:g} "
        f"({_laws(result.model)})"
    ]
    for e in result.edges:
        lines.append(
            f"  edge at {e.value:{spec}} ({kind(e.kind, e.frequency)}; "
            f"{_SIDES[e.unstable_below, e.unstable_above]})"
        )
    if result.no_periodic_response:
        lines.append(
            f"  no periodic response in {format_intervals(result.no_periodic_response, spec)}"
        )
    for a, b in result.merged_away:
        lines.append(
            f"  merged away: edges in [{a:{spec}}, {b:{spec}}] are closer than tol = "
            f"{result.tol:g} and count as one; values between them without a stable "
            "response, or without any, are missing from the ranges above (a finer --tol "
            "resolves them)"
        )
    for f in result.failed:
        merged = any(a < f.value < b for a, b in result.merged_away)
        inside = " (inside a merged-away bracket)" if merged else ""
        lines.append(f"  no periodic response found at {f.value:g}{inside}: {f.reason}")
    return "\n".join(lines)


def responses(found: ResponseSet) -> str:
    """The readable list of ``responses``."""
    from ..model import is_autonomous

    m = found.model
    autonomous = any(r.floquet.autonomous for r in found.responses) or is_autonomous(m)
    lines = [
        f"self-excited cycles of Eq. (4) without excitation ({_laws(m)}), Vb = {m['Vb']:g} m/s:"
        if autonomous
        else f"periodic responses of Eq. (4) ({_laws(m)}), "
        f"Vb = {m['Vb']:g} m/s (locks looked for up to {found.limit} periods):"
    ]
    for r in found.responses:
        f = r.floquet
        verdict = (
            "GRAZING (no multiplier)"
            if f.stable is None
            else f"{'stable' if f.stable else 'UNSTABLE'}, max|mu| = {f.max_abs_multiplier:.5g}"
            + _isolation(f)
        )
        check = (
            ""
            if r.run_distance is None
            else f"; the run's last samples lie on it to {r.run_distance:.1e}"
        )
        name = f"cycle of period {f.period:.6g} s" if f.autonomous else f"{_name(r.periods):>4}"
        lines.append(
            f"  {name}: {verdict}; {f.n_reversals} reversals, {f.n_sticks} "
            f"sticks per orbit; amplitude of X1' {r.amplitude:.4g} m/s; found by "
            + ", ".join(r.sources)
            + check
        )
    for u in found.unlocked:
        lines.append(f"  {u.text()}")
    for failed in found.failed:
        lines.append(f"  no response from {failed.source}: {failed.reason}")
    return "\n".join(lines)


def branch(found: Branch) -> str:
    """The readable summary of ``branch`` (of a forced response or of self-excited cycles)."""
    lo, hi = found.value_range()
    cycles = getattr(found, "hopf", None) is not None or hasattr(found, "criticality")
    what = (
        "self-excited cycles (no excitation)"
        if cycles
        else f"the {_name(found.periods)}-periodic response"
    )
    lines = [
        f"branch of {what} in {found.param} "
        f"({_laws(found.model)}): {found.param} from "
        f"{lo:.6g} to {hi:.6g}, {len(found.points)} points; stable for {found.param} in "
        f"{format_intervals(found.stable_ranges(), '.5f', 'none')}"
    ]
    if cycles and found.hopf is not None:
        h = found.hopf
        lines.append(
            f"  Hopf point of steady sliding at {found.param} = {h.value:.6f} "
            f"({h.pair} pair, {h.frequency:.6g} rad/s, period {h.period:.6g} s, "
            f"d Re(lambda)/d{found.param} = {h.transversality:.4g}): {found.criticality}"
            + (
                " (cycles where steady sliding is stable: hysteresis)"
                if found.criticality == "subcritical"
                else ""
            )
        )
    for s in found.special:
        lines.append(
            f"  {kind(s.kind, s.frequency)} at {found.param} = {s.value:.6f} "
            f"(+- {s.accuracy:.0e})" + (f": {s.detail}" if s.detail else "")
        )
    for part in found.parts():
        a, b = part.range
        state = {True: "stable", False: "unstable", None: "grazing"}[part.stable]
        lines.append(f"  {state} from {a:.6f} to {b:.6f} ({part.start} to {part.end})")
    if cycles and found.points:
        for p in (found.points[0], found.points[-1]):
            lines.append(
                f"  cycle at {found.param} = {p.value:.6g}: period {p.period:.6g} s, "
                f"amplitude of X1' {p.amplitude:.4g} m/s, largest Vr "
                f"{p.max_relative_velocity:.3g} m/s, {p.n_sticks} sticks, "
                f"{'stable' if p.stable else 'unstable'}"
            )
    return "\n".join(lines)


def coexistence(found: Coexistence) -> str:
    """The readable summary of ``coexistence``."""
    if getattr(found, "branch", False) is not False:  # without excitation
        return cycle_coexistence(found)
    param = found.param
    lines = [
        f"stable periodic responses of Eq. (4) for {param} in {found.lo:g}..{found.hi:g} "
        f"({_laws(found.model)}; {found.wall_s:.1f} s):"
    ]
    for r in found.responses:
        stable = ", ".join(
            f"[{s.range[0]:.5f}, {s.range[1]:.5f}] ({s.lower} to {s.upper})" for s in r.stable
        )
        lines.append(f"  {r.name:>6}: stable in {stable or 'none'}")
    if found.ranges:
        lines.append("coexistence:")
        for c in found.ranges:
            a, b = c.range
            lines.append(f"  [{a:.5f}, {b:.5f}]: {', '.join(c.responses)} ({c.lower} to {c.upper})")
    else:
        lines.append("coexistence: none")
    if found.unlocked:
        values = ", ".join(f"{v:g}" for v in sorted({u.value for u in found.unlocked}))
        lines.append(
            f"not locked (quasi-periodic or longer period) at {param} = {values}: "
            "attractors not among the responses above"
        )
    for u in found.unexplained:
        lines.append(f"  a lock at {param} = {u.value:g} ({u.source}) not found: {u.reason}")
    if found.n_seeds:
        lines.append(
            f"seeds every {found.seed_step:.4g} in {param} ({found.n_seeds} values): a "
            "response stable only between two seeds, over less than that, may be missed "
            "(a smaller --step looks closer)"
        )
    return "\n".join(lines)


def cycle_coexistence(found) -> str:
    """The readable summary of ``coexistence`` without excitation
    (`beltmdsm.studies.cycle_coexistence.CycleCoexistence`)."""
    param, b = found.param, found.branch

    def parts(ps):
        return (
            ", ".join(f"[{s.range[0]:.6f}, {s.range[1]:.6f}] ({s.lower} to {s.upper})" for s in ps)
            or "none"
        )

    lines = [
        f"steady sliding and self-excited cycles of Eq. (4) without excitation for {param} "
        f"in {found.lo:g}..{found.hi:g} ({_laws(found.model)}; {found.wall_s:.1f} s):",
        f"  steady sliding: stable in {parts(found.sliding)}",
    ]
    for h in found.hopf:
        lines.append(
            f"  Hopf point at {param} = {h.value:.6f} ({h.frequency:.6g} rad/s)"
            + (f": {b.criticality}" if b is not None and b.hopf and b.hopf.value == h.value else "")
        )
    if b is not None:
        from ..studies.overlay import stable_parts

        lines.append(f"  cycle: stable in {parts(stable_parts(b))}")
    if found.ranges:
        lines.append("coexistence (hysteresis: a run ends on either by where it starts):")
        for c in found.ranges:
            a, z = c.range
            lines.append(f"  [{a:.6f}, {z:.6f}]: {', '.join(c.responses)} ({c.lower} to {c.upper})")
    else:
        lines.append(f"coexistence: none: {found.reason}")
    return "\n".join(lines)


def floquet_map(result: FloquetMap, png: str | None = None) -> str:
    """The readable summary of ``floquet-map`` (``png``: the file it was drawn to)."""
    lines = [
        f"periodic response of Eq. (4) over {result.x} in {result.x_range[0]:g}..."
        f"{result.x_range[1]:g} and {result.y} in {result.y_range[0]:g}..."
        f"{result.y_range[1]:g} ({_laws(result.model)}; {len(result.rows)} rows, "
        f"{result.wall_s:.1f} s): "
        f"{len(result.curves)} boundary curves"
    ]
    for c in result.curves:
        lines.append(
            f"  {c.kind}: {result.y} {c.y[0]:.4g}..{c.y[-1]:.4g}, {result.x} "
            f"{c.x[0]:.5f}..{c.x[-1]:.5f} (to {max(c.accuracy):.0e})"
            + (f"; {c.ended}" if c.ended else "")
        )
    if png:
        lines.append(f"drawn to {png}, over the paper's linear analysis")
    return "\n".join(lines)


def _values(x) -> str:
    return ", ".join(f"{v:g}" for v in x)


def sweep_validation(result: Sweep) -> list[str]:
    """Where the omega1 peak appears in a sweep over Vb, beside the paper's statement."""
    from ..run.summary import PEAK_PRESENT_RATIO

    table, param = result.table, result.param
    x = np.asarray(table[param], float)
    resolved = np.asarray(table["resolved"], bool)
    present = np.asarray(table["omega1_peak_present"], bool) & resolved
    criterion = f"omega1 peak (>= {100 * PEAK_PRESENT_RATIO:g}% of the Omega peak)"
    swept = f"the swept {x.min():g}..{x.max():g} m/s"
    if not resolved.any():
        lines = [f"{criterion}: no point of {swept} can tell (all unresolved)"]
    elif not present.any():
        lines = [
            f"{criterion} present at none of the {int(resolved.sum())} resolved points of {swept}"
        ]
    else:
        found = format_intervals(result.omega1_peak_ranges(), "g")
        lines = [
            f"{criterion} present for {param} in {found} m/s of {swept} "
            f"({int(present.sum())} of {int(resolved.sum())} resolved points)"
        ]
    unresolved = result.unresolved_values()
    if unresolved:
        lines.append(
            f"unresolved (the run cannot tell; neither present nor absent) at {param} = "
            f"{_values(unresolved)} m/s; lengthen --t-end"
        )
    return lines + [f"paper: {PAPER_STATEMENT}"]


def sweep(result: Sweep, out_file: str | None = None) -> str:
    """The readable table of ``sweep`` and what it says."""
    table, param = result.table, result.param
    names = [
        param,
        "regime",
        "peak_omega1",
        "peak_Omega",
        "resolved",
        "energy_residual",
        "energy_ok",
        "n_switches",
        "wall_s",
    ]
    widths = {"regime": 22, "resolved": 8, "energy_ok": 9}

    def cell(r, n):
        if n in widths:
            return f"{str(r[n]):>{widths[n]}}"
        if n == "n_switches":
            return f"{r[n]:>15d}"
        # a peak the window could not read is "-", not nan
        return f"{r[n]:>15.6g}" if np.isfinite(r[n]) else f"{'-':>15}"

    lines = ["  ".join(f"{n:>{widths.get(n, 15)}}" for n in names)]
    for r in table:
        lines.append("  ".join(cell(r, n) for n in names))
    how = (
        f"continued {result.continuation} from rest at {param} = "
        f"{(table[param].min() if result.continuation == 'up' else table[param].max()):g}"
        if result.continuation
        else "each point from rest"
    )
    lines.append(
        f"tension {result.model.tension}; {how}; {result.n_cached} of {len(table)} "
        "points from the cache"
    )
    if result.dropped:
        lines.append(f"duplicate values computed once: {_values(result.dropped)}")
    x = np.asarray(table[param], float)
    ran = ~np.isin(np.asarray(table["status"]), ("no_periodic", "failed"))
    for r in table:
        if "error" in table.dtype.names and str(r["error"]):
            failed = "failed" if r["status"] == "failed" else "not all computed"
            lines.append(f"{param} = {r[param]:g} {failed}: {r['error']}")
    unforced = x[ran & ~np.asarray(table["forced_peak"], bool)]
    if unforced.size:
        lines.append(
            f"no forced peak above the noise floor of the tolerances at {param} = "
            f"{_values(unforced)}: the omega1 peak is judged against the floor alone"
        )
    untrusted = x[ran & ~np.asarray(table["energy_ok"], bool)]
    if untrusted.size:
        lines.append(
            f"warning: the energy balance does not close within its bound at {param} = "
            f"{_values(untrusted)} (energy_ok False): those points are not trusted; "
            "tighten --rtol/--atol"
        )
    if param == "Vb":
        lines += sweep_validation(result)
    if out_file:
        lines.append(f"table written to {out_file}")
    return "\n".join(lines)


def prediction(result: Prediction) -> str:
    """The readable result of ``predict``."""
    lines = []
    for name in result.ANALYSES:
        found = getattr(result, name)
        if found is None:
            lines.append(f"no prediction for {name}: {result.reasons[name]}")
            continue
        note = f"; {result.reasons[name]}" if name in result.reasons else ""
        lines.append(f"{name:>22}: unstable Vb in {format_intervals(found, '.3f')}{note}")
    return "\n".join(lines)


def validation(results: Validation, out_file: str) -> str:
    """What ``validate`` prints after writing its file."""
    from ..studies.validation import ANALYSES

    lines = []
    for key, lab, _ in ANALYSES:
        s = results.summary[key]
        mae = "—" if s.mae is None else f"{s.mae:.2f} m/s"
        na = f", no prediction {s.no_prediction}" if s.no_prediction else ""
        lines.append(
            f"{lab:>4}: MAE of edges {mae} (n = {s.n_edges}), miss {s.miss}, "
            f"false alarm {s.false_alarm}{na}"
        )
    for key, lab, _ in ANALYSES:
        s = results.floquet_summary[key]
        mae = "—" if s.mae is None else f"{s.mae:.3f} m/s"
        lines.append(f"{lab:>4}: against Floquet, MAE of edges {mae} (n = {s.n_edges})")
    ms = results.mismatch_summary
    lines.append(
        f"periodic start against Floquet: {len(ms.mismatches)} mismatches in {ms.checked} points"
    )
    lines.append(f"tension law: {results.tension}")
    lines.append(f"wrote {out_file}")
    return "\n".join(lines)
