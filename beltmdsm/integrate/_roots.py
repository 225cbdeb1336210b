"""The Illinois method and the golden-section search, written once for both integrators.

`beltmdsm.integrate._dop853` refines a crossing on a step's dense output,
`beltmdsm.integrate._switch_scan` on the closed-form tangential motion; both keep a
bracket ``[a, b]`` with ``fa > 0 >= fb`` and call these three steps in the same loop.
Where a switching function dips inside a step without a sample below zero, both look
for its minimum with `golden` steps: a dip shallower than the samples' spacing (an
orbit that grazes a surface and crosses it by a hair) is crossed too, not stepped
over. Plain functions of numbers, so that `beltmdsm.integrate._compiled` compiles them
with either integrator.
"""

from __future__ import annotations

__all__ = ["converged", "secant", "illinois", "GOLDEN", "golden", "GOLDEN_STEPS"]

#: The golden-section ratio ``(3 - sqrt 5) / 2``: each `golden` step keeps ``1 - GOLDEN``
#: of the bracket.
GOLDEN = 0.3819660112501051
#: The most `golden` steps of one search: 0.618^100 ~ 1e-21 of the bracket, past both the
#: resolution asked (``1e-8`` of a step, 38 steps) and the rounding of the time; a bracket
#: that rounding no longer shrinks ends at ulp resolution, not in an endless loop.
GOLDEN_STEPS = 100


def converged(a: float, b: float) -> bool:
    """Whether the bracket is down to a few ulps of its end."""
    return b - a <= 4e-16 * max(1.0, abs(b))


def secant(a: float, fa: float, b: float, fb: float) -> float:
    """The secant point of the bracket, or its midpoint where rounding puts it outside."""
    c = b - fb * (b - a) / (fb - fa)
    return c if a < c < b else 0.5 * (a + b)


def illinois(
    a: float, fa: float, b: float, fb: float, c: float, fc: float, side: int
) -> tuple[float, float, float, float, int]:
    """The bracket after the value ``fc`` at ``c``: ``(a, fa, b, fb, side)``.

    The end kept twice in a row has its value halved (the Illinois modification of
    regula falsi), which keeps the convergence superlinear.
    """
    if fc > 0.0:
        if side == -1:
            fb *= 0.5
        return c, fc, b, fb, -1
    if side == 1:
        fa *= 0.5
    return a, fa, c, fc, 1


def golden(
    a: float, b: float, c: float, fc: float, d: float, fd: float
) -> tuple[float, float, float, float, float]:
    """One step of the golden-section search for a minimum in ``[a, b]``.

    ``c < d`` are the inner points, ``fc``, ``fd`` the values there. Returns the new
    bracket ``(a, b)``, the inner point kept with its value, and the new inner point
    at which the caller evaluates next: ``(a, b, kept, f_kept, new)``.
    """
    if fc <= fd:
        return a, d, c, fc, a + GOLDEN * (d - a)
    return c, b, d, fd, b - GOLDEN * (b - c)
