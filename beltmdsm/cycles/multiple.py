"""A branch of cycles on from where single shooting's conditioning fails.

`beltmdsm.cycles.continuation.CycleProblem` shoots over one period; a cycle whose
largest multiplier passes `MULTIPLIER_LIMIT` amplifies the run's errors past Newton's
tolerance there (Stribeck's law continued in ``v_s`` at ``Vb = 1.5``: ``|mu| = 1.07e3``
at ``v_s = 0.142``, the largest ``Vr`` still -0.02 m/s short of the stick onset).
`walk` then hands the branch over to `MultipleCycleProblem`: the same cycle in
`SEGMENTS` segments (`beltmdsm.periodic.cycle_segments`), each amplifying by about
``|mu|^(1/m)``, on the same driver with the same hooks (the stick onset crossed by
`beltmdsm.cycles.stick`). Its own limit: a segment whose monodromy's norm passes
`MULTIPLIER_LIMIT` has single shooting's trouble again.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..continuation.driver import walk as drive
from ..continuation.problem import Residual, Step, failed
from ..continuation.settings import ContinuationSettings
from ..errors import NoPeriodicResponse
from ..periodic.cycle_segments import (
    continuity,
    segment_images,
    segment_jacobian,
    split_run,
    whole,
)
from ..periodic.newton import NEWTON_TOL
from .continuation import _SECTION_TOL, MULTIPLIER_LIMIT, CycleProblem

__all__ = ["MultipleCycleProblem", "SEGMENTS", "walk"]

#: Segments of a multiple-shooting cycle: at the hand-over (``|mu| = 1e3``) each
#: amplifies by about ``1e3^(1/16) = 1.5``; a segment reaches `MULTIPLIER_LIMIT` only
#: where the whole period's largest multiplier is of order ``1e48``.
SEGMENTS = 16
#: Back to single shooting where the largest multiplier falls below this (a tenth of
#: `MULTIPLIER_LIMIT`: no hand-over back and forth at one cycle): the stick-slip cycles
#: beyond the onset have a multiplier 0 and small ones, and single shooting is m times
#: cheaper.
HAND_BACK = MULTIPLIER_LIMIT / 10
#: Hand-overs on one walk at most.
MAX_HANDOVERS = 6
#: Newton's iterations on the grazing cycle.
GRAZING_ITER = 8
#: The largest ``|max Vr|`` [m/s] of the sliding cycles extrapolated to the grazing one.
GRAZING_VR = 4e-4
HANDED_BACK = "handed back to single shooting"


class MultipleCycleProblem(CycleProblem):
    """A self-excited cycle in ``m`` segments, continued in ``z = (x_0 / sx, ..,
    x_{m-1} / sx, T / sT, p / sp)`` (module docstring).

    Takes a `CycleProblem`'s flow, range and scales; its points are `CyclePoint`s whose
    ``segments`` hold the states at ``t = i T / m``. The Step data and ``correct``
    keep the single-shooting form ``(x_0, T, p, image)``, the image a
    `beltmdsm.periodic.cycle_segments.SegmentImages`, so that the stick-onset tools
    work on either problem.
    """

    def __init__(self, single: CycleProblem, m: int = SEGMENTS):
        self.__dict__.update(single.__dict__)
        self.m = int(m)
        self._states: dict[bytes, NDArray[np.float64]] = {}

    # -- unknowns

    def unpack_all(self, z):
        m = self.m
        return (
            z[: 4 * m].reshape(m, 4) * self.sx,
            float(z[4 * m] * self.sT),
            float(z[4 * m + 1] * self.sp),
        )

    def unpack(self, z):
        states, T, p = self.unpack_all(z)
        return states[0], T, p

    def states_of(self, x, T, p) -> NDArray[np.float64]:
        """The segments' starts of a cycle through ``x`` (those of the last solution
        there, else split from one run)."""
        x = np.asarray(x, float)
        if x.ndim == 2:
            return x
        known = self._states.get(x.tobytes())
        return known if known is not None else split_run(self.flow, x, T, p, self.m)

    def z_of(self, x, T, p) -> NDArray[np.float64]:
        states = self.states_of(x, T, p)
        return np.concatenate([states.ravel() / self.sx, [T / self.sT, p / self.sp]])

    def z(self, point) -> NDArray[np.float64]:
        states = point.segments if point.segments is not None else point.state
        return self.z_of(states, point.period, point.value)

    # -- equations

    def residual(self, z, extra, iteration) -> Residual:
        states, T, p = self.unpack_all(z)
        images = segment_images(self.flow, states, T, p)
        G = continuity(states, images) / self.sx
        H = self.flow.section(states[0], p) / self.hs
        size = max(float(np.max(np.abs(G))), abs(H), abs(extra))
        converged = (
            size * self.sx <= NEWTON_TOL * (1.0 + float(np.max(np.abs(states))))
            and abs(H) <= _SECTION_TOL
            and iteration > 1
        )
        return Residual(np.append(G.ravel(), H), size, converged, (states, T, p, images))

    def jacobian(self, *args, column=None) -> NDArray[np.float64]:  # type: ignore[override]
        """``d(G, H)/dz`` (4m+1 x 4m+2) at an evaluation ``(states, T, p, images)`` or
        at ``(x_0, T, p, SegmentImages)``; ``column``: the scaled ``p`` column."""
        if len(args) <= 2:
            data, column = args[0], args[1] if len(args) == 2 else column
        else:
            data, column = args[:4], args[4] if len(args) == 5 else column
        states, T, p, images = data
        if np.ndim(states) == 1 and hasattr(images, "segments"):  # (x_0, T, p, SegmentImages)
            states, images = images.states, images.segments
        elif np.ndim(states) == 1:  # a run from x_0 alone (beltmdsm.cycles.stick)
            states = split_run(self.flow, states, T, p, self.m)
            images = segment_images(self.flow, states, T, p)
        J = segment_jacobian(self.flow, states, T, p, images, column=column is None)
        # scaled: G / sx and H / hs in z = (x / sx, T / sT, p / sp)
        n = 4 * self.m
        J[:n, n] *= self.sT / self.sx
        J[n, :n] *= self.sx / self.hs
        if column is None:
            c = J[:, -1]
            column = np.append(c[:n] * self.sp / self.sx, c[n] * self.sp / self.hs)
        J[:, -1] = column
        return J

    def solution(self, data, iteration) -> Step:
        states, T, p, images = data
        self._states = {states[0].tobytes(): states}
        img = whole(self.flow, states, T, p, images)
        J = self.jacobian(data)
        return Step(self.z_of(states, T, p), p, J, iteration, (states[0], T, p, img))

    def point_at(self, x, T, p, img, tangent_p, J=None):
        point = super().point_at(x, T, p, img, tangent_p, J)
        point.segments = np.array(img.states)
        return point

    # -- the stick onset solved as the grazing cycle

    def rescue(self, points, prev, tangent, ds):
        """`CycleProblem.rescue`, the onset then solved as the cycle whose largest
        ``Vr`` is 0 (`grazing`), where the branch comes from the sliding side: the
        extrapolation of `beltmdsm.cycles.stick.locate` stays about 1e-4 off here."""
        crossed = super().rescue(points, prev, tangent, ds)
        if crossed is None or crossed[1][0].n_sticks:
            return crossed
        solved = self.grazing(crossed[1][0])
        if solved is not None:
            crossed[0].value, crossed[0].accuracy = solved
        return crossed

    def grazing(self, near):
        """``(p, accuracy)`` of the grazing cycle (largest ``Vr = 0``) next to the
        sliding cycle ``near``, or None.

        ``max Vr = 0`` holds on every stick-slip cycle too (``X1' = Vb`` while stuck),
        and beyond a nonsmooth fold those lie next to the sliding ones, so the grazing
        cycle is not solved for itself: the sliding cycles with ``max Vr = -d`` for
        three ``d`` (`_sliding_at`) are, and their ``p``, smooth in ``d`` on the sliding
        side, is extrapolated to ``d = 0`` by a quadratic; the accuracy is its
        difference from the line through the nearest two.
        """
        d0 = min(GRAZING_VR, abs(near.max_relative_velocity))
        z, found = self.z(near), []
        for d in (d0, d0 / 2, d0 / 4):
            z = self._sliding_at(z, -d)
            if z is None:
                return None
            found.append((d, float(z[-1] * self.sp)))
        d, p = np.array(found).T
        value = float(np.polyval(np.polyfit(d, p, 2), 0.0))
        accuracy = abs(value - float(np.polyval(np.polyfit(d[1:], p[1:], 1), 0.0)))
        return value, accuracy

    def _sliding_at(self, z, target):
        """The scaled unknowns of the sliding cycle with ``max Vr = target`` (< 0),
        Newton's method from ``z`` on the segments' equations and that one (its
        gradient by central differences in ``x_0``, ``T`` and ``p``, the unknowns it
        depends on); None where it does not converge or lands on a stick-slip cycle."""
        n = z.size
        for _ in range(GRAZING_ITER):
            try:
                r = self.residual(z, 0.0, 0)
                J = self.jacobian(r.data)
                vr = self.flow.largest_vr(*self.unpack(z)) - target
                row = np.zeros(n)
                for i in (0, 1, 2, 3, n - 2, n - 1):
                    e = np.zeros(n)
                    e[i] = 1e-7 * max(1.0, abs(z[i]))
                    up = self.flow.largest_vr(*self.unpack(z + e))
                    down = self.flow.largest_vr(*self.unpack(z - e))
                    row[i] = (up - down) / (2 * e[i])
                dz = np.linalg.solve(np.vstack([J, row]), -np.append(r.F, vr))
            except (NoPeriodicResponse, np.linalg.LinAlgError):
                return None
            z = z + dz
            if float(np.max(np.abs(dz))) * self.sx <= NEWTON_TOL * 10 * (1 + self.sx):
                x, T, p = self.unpack(z)
                run = self.flow.run(x, T, p)
                stuck = any(int(new) == 0 for _, _, new in run.events)
                return None if stuck else z
        return None

    # -- its limits

    def stop(self, new):
        if new.max_abs_multiplier < HAND_BACK:
            return failed(new, HANDED_BACK)
        worst = max(float(np.linalg.norm(s.monodromy, 2)) for s in new.image.segments)
        if worst > MULTIPLIER_LIMIT:
            return failed(
                new,
                f"a segment of the {self.m} of multiple shooting amplifies by {worst:.3g} "
                f"(the cycle's largest multiplier {new.max_abs_multiplier:.3g}): the "
                "corrector's steps shrink towards nothing there, as single shooting's did",
            )
        return self.period_stop(new)


def _restart(problem, last, direction):
    """``(first point, tangent)`` of ``problem`` at the cycle ``last`` (corrected there
    with the parameter pinned), the tangent along ``direction`` in the components
    ``(x_0, T, p)`` that both shootings share; None where the corrector fails."""
    z = problem.z(last)
    row = np.zeros(z.size)
    row[-1] = 1.0
    try:
        step = problem.solve(z, lambda q: (float(q[-1] - z[-1]), row), fresh=True)
    except NoPeriodicResponse:
        return None
    t = problem.tangent(step.J)
    t = t if float(np.concatenate([t[:4], t[-2:]]) @ direction) >= 0 else -t
    first = problem.point(step, float(t[-1]))
    first.column = step.J[:, -1].copy()
    return first, t


def walk(cont, first, tangent, period0, settings: ContinuationSettings | None = None):
    """`beltmdsm.cycles.continuation.walk`, on multiple shooting while the largest
    multiplier lies above `MULTIPLIER_LIMIT` (handed back below `HAND_BACK`).

    Returns ``(points, special)`` as that walk; a hand-over is no special point (the
    branch goes on); the points solved by multiple shooting have ``segments``.
    """
    cont.period0 = period0
    ms = MultipleCycleProblem(cont)
    problem, points, special = cont, [first], []
    for _ in range(MAX_HANDOVERS + 1):
        more, found = drive(problem, points[-1], tangent, settings)
        points += more[1:]
        special += found
        end, last = special[-1], points[-1]
        if problem is cont:
            go_on = end.kind == "failed" and last.max_abs_multiplier > MULTIPLIER_LIMIT
        else:
            go_on = end.kind == "failed" and end.detail == HANDED_BACK
        if not go_on or len(points) < 2:
            break
        nxt = ms if problem is cont else cont
        direction = _shared(cont, last) - _shared(cont, points[-2])
        restarted = _restart(nxt, last, direction / np.linalg.norm(direction))
        if restarted is None:
            break
        special.pop()
        (points[-1], tangent), problem = restarted, nxt
    if special and special[-1].detail == HANDED_BACK:
        special[-1].detail = "single shooting fails on this cycle again"
    return points, special


def _shared(cont, point):
    """``(x_0 / sx, T / sT, p / sp)`` of a point of either shooting."""
    return cont.z_of(point.state, point.period, point.value)
