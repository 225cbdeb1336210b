"""The readable text of a run, a sweep, the predictions and the validation.

`simulation` (``simulate``), `sweep` (``sweep``) with `sweep_validation` (where the
omega1 peak appears beside the paper's statement), `prediction` (``predict``) and
`validation` (``validate``).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ...intervals import format_intervals
from ...state_names import rate_column

if TYPE_CHECKING:
    from ...batch.sweep import Sweep
    from ...paper_reports.validation import Validation
    from ...prediction.prediction import Prediction
    from ...run.summary import Summary
    from ...simulation import Simulation

__all__ = [
    "peak_verdict",
    "spectrum_line",
    "simulation",
    "sweep",
    "sweep_validation",
    "prediction",
    "validation",
    "PAPER_STATEMENT",
]

#: What the paper says of the omega1 peak of Fig. 2b, printed beside a sweep over Vb.
PAPER_STATEMENT = "the omega1 peak 'vanishes after Vb ~ 8 m/s' (Sect. 3, Fig. 2b)"


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
        f"{rate_column(sim.model)} spectrum: omega1 peak {_peak(s.peak_omega1, s.omega1_peak_at)} "
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
                "(beltmdsm/excitation.py, START_PERTURBATION)"
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


def _values(x) -> str:
    return ", ".join(f"{v:g}" for v in x)


def sweep_validation(result: Sweep) -> list[str]:
    """Where the omega1 peak appears in a sweep over Vb, beside the paper's statement."""
    from ...run.summary import PEAK_PRESENT_RATIO

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
    from ...paper_reports.validation import ANALYSES

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
