"""The readable text of periodic responses: ``floquet``, ``responses``, ``coexistence``.

`floquet` (a forced response) or `cycle` (a self-excited cycle, without excitation),
`responses` (every response at one point), `coexistence` and `cycle_coexistence`
(where stable responses coexist).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ...state_names import columns, rate_column
from .common import laws, response_name

if TYPE_CHECKING:
    from ...multistability.coexistence import Coexistence
    from ...multistability.cycle_coexistence import CycleCoexistence
    from ...multistability.responses import ResponseSet
    from ...periodic.floquet import Floquet

__all__ = ["floquet", "cycle", "responses", "coexistence", "cycle_coexistence"]


def floquet(f: Floquet) -> str:
    """The readable result of ``floquet``."""
    if f.autonomous:
        return cycle(f)
    resp = f.response
    p = resp.model.params
    per = "per period" if resp.periods == 1 else f"per {resp.periods} periods"
    lines = [
        f"periodic response of Eq. (4), {resp.model.friction} friction, "
        f"{resp.model.contact}, tension "
        f"{resp.model.tension}, Vb = {p['Vb']:g} m/s: period {f.period:.6g} s, "
        f"{f.n_reversals} reversals and {f.n_sticks} sticks {per}, Newton "
        f"{resp.iterations} iterations (residual {resp.residual:.1e}), "
        f"{f.engine} path (beltmdsm/periodic/engines.py)"
    ]
    if f.grazing is not None:
        lines.append(
            f"GRAZING: a reversal at t = {f.grazing['t']:.6g} s is reached with a "
            f"vanishing acceleration (ratio {f.grazing['ratio']:.1e}); no multiplier "
            "is reported"
        )
    else:
        lines += [
            f"Floquet multipliers: {f.multipliers_text()}",
            f"{'stable' if f.stable else 'UNSTABLE'}{_isolation(f)}: {f.largest_text()}, "
            f"critical pair at {f.frequency:.6g} rad/s "
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
        f"{c.residual:.1e}) (beltmdsm/periodic/cycle.py)",
        f"{columns(m)[0]} in [{c.x1_range[0]:.6g}, {c.x1_range[1]:.6g}] m, {rate_column(m)} in "
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
    from ...periodic.newton import ISOLATION_TOL

    mus = np.asarray(f.multipliers, dtype=complex)
    if mus.size and np.min(np.abs(mus - 1.0)) <= ISOLATION_TOL:
        return " (a multiplier is 1, I - M singular: not isolated, its linear stability undecided)"
    return ""


def responses(found: ResponseSet) -> str:
    """The readable list of ``responses``."""
    from ...excitation import is_autonomous

    m = found.model
    autonomous = any(r.floquet.autonomous for r in found.responses) or is_autonomous(m)
    lines = [
        f"self-excited cycles of Eq. (4) without excitation ({laws(m)}), Vb = {m['Vb']:g} m/s:"
        if autonomous
        else f"periodic responses of Eq. (4) ({laws(m)}), "
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
        name = (
            f"cycle of period {f.period:.6g} s"
            if f.autonomous
            else f"{response_name(r.periods):>4}"
        )
        lines.append(
            f"  {name}: {verdict}; {f.n_reversals} reversals, {f.n_sticks} "
            f"sticks per orbit; amplitude of {rate_column(m)} {r.amplitude:.4g} m/s; found by "
            + ", ".join(r.sources)
            + check
        )
    for u in found.unlocked:
        lines.append(f"  {u.text()}")
    for failed in found.failed:
        lines.append(f"  no response from {failed.source}: {failed.reason}")
    return "\n".join(lines)


def coexistence(found: Coexistence) -> str:
    """The readable summary of ``coexistence``."""
    if getattr(found, "branch", False) is not False:  # without excitation
        return cycle_coexistence(found)
    param = found.param
    lines = [
        f"stable periodic responses of Eq. (4) for {param} in {found.lo:g}..{found.hi:g} "
        f"({laws(found.model)}; {found.wall_s:.1f} s):"
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


def cycle_coexistence(found: CycleCoexistence) -> str:
    """The readable summary of ``coexistence`` without excitation
    (`beltmdsm.multistability.cycle_coexistence.CycleCoexistence`)."""
    param, b = found.param, found.branch

    def parts(ps):
        return (
            ", ".join(f"[{s.range[0]:.6f}, {s.range[1]:.6f}] ({s.lower} to {s.upper})" for s in ps)
            or "none"
        )

    lines = [
        f"steady sliding and self-excited cycles of Eq. (4) without excitation for {param} "
        f"in {found.lo:g}..{found.hi:g} ({laws(found.model)}; {found.wall_s:.1f} s):",
        f"  steady sliding: stable in {parts(found.sliding)}",
    ]
    for h in found.hopf:
        lines.append(
            f"  Hopf point at {param} = {h.value:.6f} ({h.frequency:.6g} rad/s)"
            + (f": {b.criticality}" if b is not None and b.hopf and b.hopf.value == h.value else "")
        )
    if b is not None:
        from ...multistability.stable_ranges import stable_parts

        lines.append(f"  cycle: stable in {parts(stable_parts(b))}")
    if found.ranges:
        lines.append("coexistence (hysteresis: a run ends on either by where it starts):")
        for c in found.ranges:
            a, z = c.range
            lines.append(f"  [{a:.6f}, {z:.6f}]: {', '.join(c.responses)} ({c.lower} to {c.upper})")
    else:
        lines.append(f"coexistence: none: {found.reason}")
    return "\n".join(lines)
