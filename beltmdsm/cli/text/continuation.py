"""The readable text of continuation: ``floquet-band``, ``branch``, ``floquet-map``."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from ...intervals import format_intervals
from ...state_names import rate_column
from .common import kind, laws, response_name

if TYPE_CHECKING:
    from ...continuation.band_result import Band
    from ...continuation.branch import Branch
    from ...continuation.map_result import FloquetMap

__all__ = ["band", "branch", "floquet_map"]


_SIDES = {
    (False, True): "unstable above",
    (True, False): "unstable below",
    (False, False): "stable on both sides",
    (True, True): "unstable on both sides",
}


def band(result: Band, lo: float, hi: float) -> str:
    """The readable result of ``floquet-band``.

    Values are printed to the digits of the edges' tolerance (at least 4 decimals), so
    that two edges more than a tolerance apart never print alike.
    """
    spec = f".{max(4, math.ceil(-math.log10(result.tol)) + 1)}f"
    what = (
        "periodic response" if result.periods == 1 else f"{response_name(result.periods)} response"
    )
    lines = [
        f"{what} unstable (or absent) for {result.param} in "
        f"{format_intervals(result.unstable, spec)} of {lo:g}..{hi:g} "
        f"({laws(result.model)})"
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


def branch(found: Branch) -> str:
    """The readable summary of ``branch`` (of a forced response or of self-excited cycles)."""
    lo, hi = found.value_range()
    cycles = found.kind == "cycle"
    what = (
        "self-excited cycles (no excitation)"
        if cycles
        else f"the {response_name(found.periods)}-periodic response"
    )
    lines = [
        f"branch of {what} in {found.param} "
        f"({laws(found.model)}): {found.param} from "
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
                f"amplitude of {rate_column(found.model)} {p.amplitude:.4g} m/s, largest Vr "
                f"{p.max_relative_velocity:.3g} m/s, {p.n_sticks} sticks, "
                f"{'stable' if p.stable else 'unstable'}"
            )
    return "\n".join(lines)


def floquet_map(result: FloquetMap, png: str | None = None) -> str:
    """The readable summary of ``floquet-map`` (``png``: the file it was drawn to)."""
    lines = [
        f"periodic response of Eq. (4) over {result.x} in {result.x_range[0]:g}..."
        f"{result.x_range[1]:g} and {result.y} in {result.y_range[0]:g}..."
        f"{result.y_range[1]:g} ({laws(result.model)}; {len(result.rows)} rows, "
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
